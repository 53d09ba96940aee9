#pragma once
// A uniform grid of cells over the particles' bounding box, each cell at least as wide as the
// largest cut-off (2 R_max + skin), with the particles listed by cell: what the neighbour list and
// the wall contact list search.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "dem/particles.h"
#include "dem/types.h"

namespace chutelab::dem {

struct CellGrid {
  Vec3 lo = Vec3::Zero(), hi = Vec3::Zero();  // the particles' bounding box
  double rmax = 0.0;                          // largest radius
  double h = 0.0;                             // cell width
  std::array<std::int64_t, 3> dim{1, 1, 1};
  // int32: the grid is capped at a few cells per particle, and these arrays are part of the
  // rebuild's memory peak.
  std::vector<std::int32_t> cell;        // per particle
  std::vector<std::int32_t> cell_start;  // per cell, + 1: where its particles start in `members`
  std::vector<std::int32_t> members;     // particle indices by cell

  // The grid over p with cut-off skin; `order` gets the particles by cell (a permutation of 0..n-1).
  void build(const Particles& p, double skin, int threads, std::vector<std::int32_t>& order);
  // After the particles were reordered by `order`: particle k is in cell cell[order[k]], and each
  // cell's particles are contiguous and ascending.
  void sort_by(const std::vector<std::int32_t>& order);

  std::int64_t cells() const { return dim[0] * dim[1] * dim[2]; }
  std::int64_t coord(const Vec3& x, int d) const {
    auto c = static_cast<std::int64_t>(std::floor((x[d] - lo[d]) / h));
    return std::clamp<std::int64_t>(c, 0, dim[static_cast<std::size_t>(d)] - 1);
  }
  std::int64_t index(std::int64_t x, std::int64_t y, std::int64_t z) const { return (z * dim[1] + y) * dim[0] + x; }
  std::int64_t cell_of(const Vec3& x) const { return index(coord(x, 0), coord(x, 1), coord(x, 2)); }
};

}  // namespace chutelab::dem
