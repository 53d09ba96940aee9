#pragma once
// A circular cylinder wall (a pulley from outside, a drum or pipe from inside), open ends.
#include <limits>

#include "dem/types.h"

namespace chutelab::dem {

struct Cylinder {
  Vec3 point = Vec3::Zero();    // a point on the axis
  Vec3 axis = Vec3::UnitY();    // unit
  double radius = 0.0;          // m
  double axial_min = -std::numeric_limits<double>::infinity();  // extent along axis from point
  double axial_max = std::numeric_limits<double>::infinity();
  bool inside = false;          // particles inside the tube (true) or outside it (false)
};

}  // namespace chutelab::dem
