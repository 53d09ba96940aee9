// Contact detection: whether the neighbour and wall contact lists must be rebuilt, and the rebuild
// (the cell grid, the particles sorted by cell, both lists' search, the force blocks' layout, the
// touching contacts' history carried over, and the reference the next displacements are measured
// from).
#include <algorithm>
#include <cmath>
#include <limits>

#include "dem/world.h"
#include "dem/team.h"

namespace chutelab::dem {

bool World::needs_rebuild() const {
  if (contacts_.dirty) return true;
  if (2.0 * contacts_.max_disp > contacts_.skin) return true;
  for (std::size_t k = 0; k < walls_.size(); ++k)
    if (walls_[k].motion.moving()) {
      // Set moving after the last rebuild: its elements were listed only for a still wall's reach.
      if (!contacts_.reference.wall_listed_moving[k]) return true;
      if (contacts_.max_disp + wall_displacement_since_rebuild(walls_[k]) > contacts_.skin) return true;
    }
  return false;
}

double World::wall_displacement_since_rebuild(const Wall& w) const {
  const std::size_t k = static_cast<std::size_t>(&w - walls_.data());
  const double dt = clock_.time - contacts_.reference.wall_time[k];
  return w.motion.velocity.norm() * std::abs(dt) +
         std::abs(w.motion.omega.norm() * dt) * reach_from_pivot(w);
}

void World::rebuild() {
  const std::size_t n = p_.size();
  const int nt = thread_count();
  contacts_.history.save(contacts_.pairs, contacts_.walls, nt);
  std::vector<std::int32_t> map = std::move(contacts_.reference.index_map);  // old list index -> current index
  CellGrid grid;
  std::vector<std::int32_t> order;
  grid.build(p_, contacts_.skin, nt, order);
  if (settings_.sort_particles) sort_by_cell(grid, order, map);
  contacts_.pairs.build(grid, p_, contacts_.skin, settings_.sort_particles, nt);
  contacts_.walls.build(grid, p_, walls_, contacts_.skin, nt);
  blocks_.layout(n, kForceBlocks, nt, contacts_.pairs.row_begin, contacts_.pairs.neighbor, contacts_.walls.begin);
  // Each old contact lands in its own new slot, so the rows can be carried over in parallel.
  contacts_.pairs.carry_history(contacts_.history, map, nt);
  contacts_.walls.carry_history(contacts_.history, map, nt);
  take_reference(nt);
  scan_sinks();
  contacts_.dirty = false;
  ++contacts_.rebuilds;
}

// Particles in cell order, for memory locality and the sorted search (NeighborList::build).
void World::sort_by_cell(CellGrid& grid, const std::vector<std::int32_t>& order, std::vector<std::int32_t>& map) {
  const std::size_t n = order.size();
  p_.permute(order, thread_count());
  if (!sources_.held.empty()) index_held();
  std::vector<std::int32_t> inv(n);
  for (std::size_t k = 0; k < n; ++k) inv[static_cast<std::size_t>(order[k])] = static_cast<std::int32_t>(k);
  for (auto& m : map)
    if (m >= 0) m = inv[static_cast<std::size_t>(m)];
  grid.sort_by(order);
}

void World::take_reference(int nt) {
  const std::size_t n = p_.size();
  contacts_.reference.index_map.resize(n);
  contacts_.reference.x.resize(n);
  {
    const Vec3* __restrict px = p_.x.data();
    Vec3* __restrict xr = contacts_.reference.x.data();
    std::int32_t* __restrict im = contacts_.reference.index_map.data();
    on_team(nt, [&] {
#pragma omp for schedule(static)
      for (std::size_t i = 0; i < n; ++i) {
        im[i] = static_cast<std::int32_t>(i);
        xr[i] = px[i];
      }
    });
  }
  contacts_.pairs.measure_gaps(contacts_.reference.x.data(), p_.radius.data(), n, nt);
  for (std::size_t k = 0; k < walls_.size(); ++k) {
    contacts_.reference.wall_time[k] = clock_.time;
    contacts_.reference.wall_listed_moving[k] = walls_[k].motion.moving() ? 1 : 0;
  }
  contacts_.max_disp = 0.0;
}

}  // namespace chutelab::dem
