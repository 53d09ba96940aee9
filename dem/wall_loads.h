#pragma once
// The walls' loads (force, torque about the load point, force per element) summed with the same
// thread independence as the particles' forces (dem/force_blocks.h): each force block sums the wall
// contacts of its own particles, in entry order, into its share (per wall, and per element touched),
// and a wall's load is the blocks' shares in block order. A serial sum over all entries would read
// every entry the other threads have just written (bench bed, 2 threads: their wall contacts 45 %
// dearer).
#include <cstdint>
#include <vector>

#include "dem/types.h"
#include "dem/walls/wall.h"
#include "dem/walls/wall_contact_list.h"

namespace chutelab::dem {

class WallLoads {
 public:
  // Sizes the shares for `blocks` force blocks and `threads` threads over the walls' elements.
  void prepare(const std::vector<Wall>& walls, std::size_t blocks, std::size_t threads);
  // The particles [lo, hi) of force block b, on thread `thread`: to each particle its wall contacts'
  // forces and torques (in entry order) and its weight mass * g; to block b's share the reactions
  // of the same contacts.
  void finish_block(std::size_t b, std::size_t thread, std::size_t lo, std::size_t hi, const WallContactList& list,
                    const double* mass, const Vec3& g, Vec3* f, Vec3* t);
  // Each wall's force, torque and element forces: the blocks' shares in block order.
  void sum_into(std::vector<Wall>& walls) const;

 private:
  struct ElementShare {
    std::int32_t wall, element;
    Vec3 f;
  };
  std::size_t walls_ = 0, blocks_ = 0;
  bool meshes_ = false;
  std::vector<Vec3> force_, torque_;                 // per block and wall
  std::vector<std::vector<ElementShare>> elements_;  // per block: the elements it touched
  // Per wall: the slot of its first element, or -1 for a wall of one element (a primitive: its
  // element's load is its load).
  std::vector<std::int32_t> element_base_;
  std::vector<std::vector<std::int32_t>> slot_;      // per thread: slot -> index in its block's list, or -1
};

}  // namespace chutelab::dem
