#pragma once
// The wall elements near each particle (CSR by particle, sorted by wall then element) with each
// entry's contact history and what its contact gave in the last force evaluation: the walls'
// counterpart of the neighbour list, built and kept with it (World::rebuild).
#include <cstdint>
#include <vector>

#include "dem/cell_grid.h"
#include "dem/contact_history.h"
#include "dem/particles.h"
#include "dem/types.h"
#include "dem/walls/wall.h"

namespace chutelab::dem {

struct WallContactList {
  std::vector<std::int32_t> begin;  // size N+1
  std::vector<std::int32_t> wall, element;
  std::vector<Vec3> shear, roll;    // tangential and rolling history
  std::vector<std::uint8_t> touch;
  std::vector<Vec3> force, torque;  // on the particle
  std::vector<Vec3> point;          // contact point on the wall
  std::vector<Vec3> wall_torque;    // the wall's torque about its load point
  // For the wall observers, when a wall is observed (else empty): what the contact saw of its
  // particle, taken with the forces, since the particle moves on before the observers run.
  std::vector<Vec3> observed_normal, observed_velocity;
  std::vector<std::int32_t> owners;  // particles with at least one entry, ascending (derived)
  std::vector<std::int32_t> owner;   // particle of each entry (derived)

  // Every (particle, wall, element) within R + skin of each other (a wall that does not move: within
  // R + skin/2, all that can touch before the next rebuild); history starts at zero.
  void build(const CellGrid& grid, const Particles& p, const std::vector<Wall>& walls, double skin, int threads);
  // The touching entries of the last list into this one; map: old particle index -> new (-1 gone).
  void carry_history(const TouchingHistory& saved, const std::vector<std::int32_t>& map, int threads);
  std::size_t size() const { return wall.size(); }
  void index_owners() {
    owners.clear();
    owner.resize(wall.size());
    for (std::size_t i = 0; i + 1 < begin.size(); ++i) {
      if (begin[i] != begin[i + 1]) owners.push_back(static_cast<std::int32_t>(i));
      for (auto e = begin[i]; e < begin[i + 1]; ++e) owner[static_cast<std::size_t>(e)] = static_cast<std::int32_t>(i);
    }
  }
};

}  // namespace chutelab::dem
