#pragma once
// The history of the contacts that touch (tangential and rolling springs), copied out of the
// neighbour and wall contact lists at the start of a rebuild (CSR by the old particle index) and
// carried into the new lists' slots by NeighborList::carry_history and
// WallContactList::carry_history. Only the touching contacts' history outlives a rebuild: the lists
// are rebuilt in their own storage. (Fresh list arrays at every rebuild cost a page fault per 4 kB of
// new slots, most of them in the 48 B of history per slot: a fifth of a station run's time. Keeping
// the old lists whole beside the new ones raised the bench bed's peak memory from 0.97 to 1.15 kB
// per particle.)
#include <cstdint>
#include <vector>

#include "dem/types.h"

namespace chutelab::dem {

class NeighborList;
struct WallContactList;

struct TouchingHistory {
  std::vector<std::int32_t> pair_begin, pair_other;
  std::vector<Vec3> pair_shear, pair_roll;
  std::vector<std::int32_t> wall_begin, wall_wall, wall_element;
  std::vector<Vec3> wall_shear, wall_roll;
  // Kept between rebuilds only for its storage.
  void save(const NeighborList& pairs, const WallContactList& walls, int threads);
};

}  // namespace chutelab::dem
