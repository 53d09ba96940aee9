#pragma once
// A plane wall: a half-space boundary. Particles live on the side the normal points to. Optionally
// bounded to a rectangle (a belt strip) by two in-plane axes and half-lengths.
#include <limits>

#include "dem/types.h"

namespace chutelab::dem {

struct Plane {
  Vec3 point = Vec3::Zero();
  Vec3 normal = Vec3::UnitZ();  // unit, towards the particles
  // Optional rectangular extent: |(p - point) . axis_u| <= half_u, same for v. Infinite by default.
  Vec3 axis_u = Vec3::UnitX();
  Vec3 axis_v = Vec3::UnitY();
  double half_u = std::numeric_limits<double>::infinity();
  double half_v = std::numeric_limits<double>::infinity();
  bool bounded() const { return half_u < std::numeric_limits<double>::infinity() || half_v < std::numeric_limits<double>::infinity(); }
};

}  // namespace chutelab::dem
