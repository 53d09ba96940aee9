#pragma once
// Booth's discharge of a streamline from the head pulley (Booth 1934, as used by the reference study):
// the material rides the belt at speed V and leaves the pulley where the centripetal acceleration
// it needs, V^2 / r, exceeds what gravity (and any holding force) can supply.
#include <Eigen/Core>

#include "analytical/effect.h"

namespace chutelab::analytical {

struct Release {
  bool high_speed = false;   // left at the tangent point where the belt meets the pulley
  double ratio = 0.0;        // K = V^2 / (g r), the reference study's high-speed criterion
  double theta = 0.0;        // rad, release point's angle from the upward vertical, + towards plate
  Eigen::Vector2d position = Eigen::Vector2d::Zero();  // m, pulley centre at the origin
  Eigen::Vector2d velocity = Eigen::Vector2d::Zero();  // m/s
};

// Throws InputError when the material cannot leave the pulley (it would be carried round).
Release booth_release(const DischargeInput& in);

}  // namespace chutelab::analytical
