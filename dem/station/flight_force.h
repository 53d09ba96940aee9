#pragma once
// Extra acceleration on particles in flight (beyond gravity), the DEM counterpart of an
// analytical effect's flight hook (analytical/effect.h: flight_acceleration). For air drag
// (effects/air_drag.cpp) that is a = -(3 rho_air C_d / (4 rho_s d)) |v| v with the dataset's real
// particle diameter and density, so a scaled-up DEM particle feels the acceleration of a real one.
// "In flight" is everything past the pulley's tangent point (s > 0): the stream, and the slow layer
// on the plate where drag is negligible anyway. The analytical hook is planar (x-y); the lateral
// velocity, small in the stream, is left out of its argument and gets no acceleration.
#include <cstddef>
#include <functional>
#include <vector>

#include <Eigen/Core>

#include "dem/particles.h"
#include "dem/station/frames.h"

namespace chutelab::dem::station {

using FlightAcceleration = std::function<Eigen::Vector2d(const Eigen::Vector2d& velocity_xy)>;

struct FlightForce {
  BeltFrame belt;
  FlightAcceleration acceleration;  // empty = none

  // Adds to force[begin, end); `acceleration` is called concurrently (it must be a pure function).
  void add(const Particles& p, std::size_t begin, std::size_t end, std::vector<Vec3>& force) const {
    if (!acceleration) return;
    for (std::size_t i = begin; i < end; ++i) {
      if (belt.s(p.x[i]) <= 0.0) continue;
      const Eigen::Vector2d a = acceleration(Eigen::Vector2d(p.v[i].x(), p.v[i].y()));
      force[i] += p.mass[i] * Vec3(a.x(), a.y(), 0.0);
    }
  }
};

}  // namespace chutelab::dem::station
