#pragma once
// Force blocks: how the forces on the particles are cut between threads and summed.
//
// Invariant (thread independence): the rows of the pair list are cut into a fixed number of blocks
// (kForceBlocks; the cut comes from the lists alone, never from the thread count). Block b owns the
// rows [first_row(b), first_row(b + 1)) and a partial-sum buffer over the particles its pairs reach.
// The pair loop scatters the forces of a block's pairs, in list order, into that block's buffer
// only. A particle's force is then the sum of the buffers that reach it, in block order (reduce),
// followed by its wall contacts in list order, its weight and the body force; a wall's load is the
// blocks' shares in block order (dem/wall_loads.h). Every sum has one fixed order, and which thread
// computes a block changes no number, so 1 and N threads give bit-identical results.
//
// Each thread takes a contiguous run of blocks (ThreadCut) in every pass over the particles (wall
// contacts, pair blocks, reduction, the integrator), so it works on the particles whose state it
// wrote: on this project's VM a cache line that crosses between cores costs ~250-500 ns
// (bench/core_latency). The cut moves with the measured busy time, which moves work, not numbers.
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "dem/types.h"

namespace chutelab::dem {

inline constexpr std::size_t kForceBlocks = 16;

// Which force blocks each thread takes: a contiguous run, [at[t], at[t+1]). It starts even and moves
// by a block when one thread's share took longer over the last kWindow steps (the rows' work
// differs, and on a VM so does the speed of the cores).
struct ThreadCut {
  static constexpr int kWindow = 32;
  std::vector<std::size_t> at;  // threads + 1 block indices
  std::vector<double> busy;     // per thread: seconds in its blocks over the window
  int steps = 0;
  void fit(std::size_t threads, std::size_t blocks);  // even, when the thread or block count changed
  // The blocks of thread t of a team of nt (even shares for a team smaller than asked for).
  std::pair<std::size_t, std::size_t> blocks(std::size_t t, std::size_t nt, std::size_t nblocks) const;
  void step();  // after each timed evaluation
};

class ForceBlocks {
 public:
  // Cuts the rows [0, n) of a pair list (CSR: row_begin, neighbor) into `count` blocks of equal
  // estimated work, from the pair slots and wall entries (CSR wall_begin, n + 1 entries) before each
  // row; sizes and zeroes the buffers.
  void layout(std::size_t n, std::size_t count, int threads, const std::vector<std::int32_t>& row_begin,
              const std::vector<std::int32_t>& neighbor, const std::vector<std::int32_t>& wall_begin);
  std::size_t count() const { return reach_end_.size(); }
  std::size_t first_row(std::size_t b) const { return first_row_[b]; }
  // Block b's partial sums as arrays indexed by particle, valid for the particles its pairs reach.
  Vec3* forces(std::size_t b) { return force_.data() + offset_[b] - first_row_[b]; }
  Vec3* torques(std::size_t b) { return torque_.data() + offset_[b] - first_row_[b]; }
  // f and t of block b's own particles: the buffers that reach them summed in block order. Each
  // buffer entry is read once, by the block that owns its particle, and zeroed for the next
  // evaluation.
  void reduce(std::size_t b, Vec3* f, Vec3* t);

  ThreadCut& cut() { return cut_; }
  // Inside a parallel region: the calling thread's blocks, and their rows clipped to n particles
  // (n may differ from the list's rows after insertions or removals: the last thread takes the
  // rows beyond).
  std::pair<std::size_t, std::size_t> thread_blocks() const;
  std::pair<std::size_t, std::size_t> thread_rows(std::size_t n) const;

 private:
  std::vector<std::size_t> first_row_;      // count + 1 entries, the last n
  std::vector<std::size_t> reach_end_;      // per block: one past the highest particle its pairs reach
  std::vector<std::size_t> offset_;         // per block: where its buffer starts in force_/torque_
  std::vector<std::size_t> first_reaching_; // per block: the first block whose buffer reaches into it
  std::vector<Vec3> force_, torque_;
  ThreadCut cut_;
};

}  // namespace chutelab::dem
