#pragma once
// Shared set-up for the DEM verification tests: Chung & Ooi (2011) benchmark materials and small
// scenes of one or two spheres.
#include <cmath>
#include <numbers>

#include "dem/world.h"

namespace chutelab::dem::test {

inline constexpr double pi = std::numbers::pi;

inline double sphere_mass(double r, double rho) { return rho * 4.0 / 3.0 * pi * r * r * r; }

// A world with no gravity and a large domain around the origin; warnings are collected, not printed.
inline Settings quiet_settings(double dt, double half_domain = 10.0) {
  Settings s;
  s.dt = dt;
  s.gravity = Vec3::Zero();
  s.domain = Box{Vec3::Constant(-half_domain), Vec3::Constant(half_domain)};
  s.on_warning = [](const std::string&) {};
  s.threads = 1;
  return s;
}

// Hertz theory for a normal elastic impact at relative speed v (Johnson 1985, §11.4).
struct HertzImpact {
  double delta_max, force_max, duration;
};
inline HertzImpact hertz_impact(double e_star, double r_eff, double m_eff, double v) {
  HertzImpact h;
  h.delta_max = std::pow(15.0 * m_eff * v * v / (16.0 * e_star * std::sqrt(r_eff)), 0.4);
  h.force_max = 4.0 / 3.0 * e_star * std::sqrt(r_eff) * std::pow(h.delta_max, 1.5);
  h.duration = 2.868 * std::pow(m_eff * m_eff / (r_eff * e_star * e_star * v), 0.2);  // reference study Eq 11
  return h;
}

}  // namespace chutelab::dem::test
