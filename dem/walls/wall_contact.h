#pragma once
// What the World tells an observer about each particle-wall contact after a time step (pressure and
// wear maps, dem/station/plate_map.h). Only walls with an observer are visited, once per step, in
// the contact list's order, so runs without observers pay nothing and the sums an observer builds
// do not depend on the thread count.
#include <cstdint>
#include <functional>

#include "dem/types.h"

namespace chutelab::dem {

struct WallContact {
  int wall = -1;
  std::int32_t element = 0;     // triangle of a mesh (0 for a primitive)
  std::int64_t particle = 0;    // persistent id of the sphere
  std::int64_t step = 0;        // step that just ended (World::step_count() before the increment)
  double dt = 0.0;              // s
  Vec3 point = Vec3::Zero();    // contact point on the wall, m
  Vec3 normal = Vec3::Zero();   // unit, from the sphere centre towards the wall
  Vec3 force = Vec3::Zero();    // on the wall, N
  Vec3 velocity = Vec3::Zero(); // of the sphere's surface relative to the wall at the contact point, m/s
  double mass = 0.0;            // kg: the body's (a clump sphere's whole body), as the contact law sees it
  double radius = 0.0;          // m
};

using WallContactObserver = std::function<void(const WallContact&)>;

}  // namespace chutelab::dem
