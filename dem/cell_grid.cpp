#include "dem/cell_grid.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "dem/team.h"

namespace chutelab::dem {

void CellGrid::build(const Particles& p, double skin, int nt, std::vector<std::int32_t>& order) {
  const std::size_t n = p.size();
  constexpr double inf = std::numeric_limits<double>::infinity();
  double r_max = 0.0;
  double lx = inf, ly = inf, lz = inf;
  double hx = -inf, hy = -inf, hz = -inf;
  {
    const Vec3* __restrict px = p.x.data();
    const double* __restrict pr = p.radius.data();
    // min and max are exact, so the box does not depend on the thread count.
#pragma omp parallel for num_threads(nt) schedule(static) reduction(max : r_max, hx, hy, hz) reduction(min : lx, ly, lz)
    for (std::size_t i = 0; i < n; ++i) {
      r_max = std::max(r_max, pr[i]);
      lx = std::min(lx, px[i].x()), ly = std::min(ly, px[i].y()), lz = std::min(lz, px[i].z());
      hx = std::max(hx, px[i].x()), hy = std::max(hy, px[i].y()), hz = std::max(hz, px[i].z());
    }
  }
  rmax = r_max;
  lo = Vec3(lx, ly, lz);
  hi = Vec3(hx, hy, hz);
  h = 2.0 * rmax + skin;
  dim = {1, 1, 1};
  if (n > 0) {
    // Cap the number of cells (sparse scenes, long trajectories) at a few per particle.
    const double cap = std::max(8.0 * static_cast<double>(n), 4096.0);
    for (;;) {
      double total = 1.0;
      for (int d = 0; d < 3; ++d) total *= std::floor((hi[d] - lo[d]) / h) + 1.0;
      if (total <= cap) break;
      h *= 1.25;
    }
    for (int d = 0; d < 3; ++d) dim[static_cast<std::size_t>(d)] = static_cast<std::int64_t>(std::floor((hi[d] - lo[d]) / h)) + 1;
  }
  const std::int64_t ncell = cells();
  cell.assign(n, 0);
  cell_start.assign(static_cast<std::size_t>(ncell) + 1, 0);
  on_team(nt, [&] {
#pragma omp for schedule(static)
    for (std::size_t i = 0; i < n; ++i) cell[i] = static_cast<std::int32_t>(cell_of(p.x[i]));
  });
  for (std::size_t i = 0; i < n; ++i) ++cell_start[static_cast<std::size_t>(cell[i]) + 1];
  for (std::int64_t c = 0; c < ncell; ++c) cell_start[static_cast<std::size_t>(c) + 1] += cell_start[static_cast<std::size_t>(c)];
  order.resize(n);
  std::vector<std::int32_t> fill(cell_start.begin(), cell_start.end() - 1);
  for (std::size_t i = 0; i < n; ++i) order[static_cast<std::size_t>(fill[static_cast<std::size_t>(cell[i])]++)] = static_cast<std::int32_t>(i);
  members = order;
}

void CellGrid::sort_by(const std::vector<std::int32_t>& order) {
  const std::size_t n = order.size();
  std::vector<std::int32_t> sorted_cell(n);
  for (std::size_t k = 0; k < n; ++k) sorted_cell[k] = cell[static_cast<std::size_t>(order[k])];
  cell = std::move(sorted_cell);
  for (std::size_t k = 0; k < n; ++k) members[k] = static_cast<std::int32_t>(k);
}

}  // namespace chutelab::dem
