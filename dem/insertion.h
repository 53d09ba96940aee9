#pragma once
// Particle sources and sinks: insertion at a mass flow into a box region (the feed of a transfer
// station), deletion of particles that cross a sink plane (below the receiving belt).
#include <cstdint>
#include <limits>

#include "dem/types.h"

namespace chutelab::dem {

struct Inserter {
  Box region;                 // particles are placed entirely inside this box, without overlaps
  double mass_rate = 0.0;     // kg/s
  double radius_min = 0.0;    // m, radius uniform in [radius_min, radius_max]
  double radius_max = 0.0;
  int material = 0;
  Vec3 velocity = Vec3::Zero();
  double start_time = 0.0;
  double end_time = std::numeric_limits<double>::infinity();
  double interval = 1e-3;     // s between insertion events (mass accumulates in between)
  std::uint64_t seed = 1;
  int max_attempts = 200;     // random placements tried per particle before giving up for this event
  // >= 0: insert clumps of this shape (World::add_clump_shape) in random orientations instead of spheres,
  // scaled so that their largest sphere has the drawn radius.
  int clump_shape = -1;
  // A stream inserter (what LIGGGHTS' fix insert/stream does with a face and an extrusion): a
  // placed sphere is held, moved rigidly at the velocity's component along hold_axis with no force
  // acting on it (though it pushes what it touches), until its centre crosses the region's face on
  // that axis that the velocity points through; there it is released with the full velocity. So
  // every particle starts free on that face. Spheres only; velocity[hold_axis] must not be zero.
  bool hold_to_face = false;
  int hold_axis = 1;

  // --- state, maintained by World ---
  std::uint64_t rng_state = 0;
  double pending_mass = 0.0;   // kg owed to the flow
  double inserted_mass = 0.0;  // kg
  double next_time = 0.0;
  bool warned_full = false;
};

struct Sink {
  Vec3 point = Vec3::Zero();
  Vec3 normal = Vec3::UnitZ();  // particles with (x - point) . normal < 0 are removed
  double removed_mass = 0.0;    // kg, maintained by World
  std::int64_t removed_count = 0;
};

// Deterministic generator (splitmix64): explicit 64-bit state, so it checkpoints as one number.
inline std::uint64_t splitmix64(std::uint64_t& state) {
  std::uint64_t z = (state += 0x9e3779b97f4a7c15ULL);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}
inline double uniform01(std::uint64_t& state) {
  return static_cast<double>(splitmix64(state) >> 11) * (1.0 / 9007199254740992.0);
}

}  // namespace chutelab::dem
