#pragma once
// Finnie's erosion by cutting (Finnie 1960, Wear 3:87): a hard particle of mass M striking a ductile
// surface at speed v and angle alpha (between its velocity and the surface) ploughs out
//     Q = c M v^2 f(alpha) / (p psi K)                       [m^3] = [kg m^2/s^2] / [Pa]
//     f(alpha) = sin(2 alpha) - (6 / K) sin^2(alpha)   for tan(alpha) <= K / 6,
//     f(alpha) = K cos^2(alpha) / 6                     beyond (the particle leaves while still cutting),
// with p the plastic flow pressure of the surface, K the ratio of the vertical to the horizontal
// force on the particle's tip, psi the ratio of the contact length to the cut's depth and c the
// fraction of particles that cut as idealised (the rest merely dent). The two branches meet at
// tan(alpha) = K / 6; f peaks near 17 deg for K = 2, and vanishes at normal incidence: Finnie's model
// is of ductile cutting and gives no wear for head-on impacts. Experiments give a speed exponent a
// little above the model's 2; `velocity_exponent` n replaces v^2 by v^2 (v / 1 m/s)^(n - 2).
#include <cmath>

namespace chutelab::dem::wear {

struct FinnieParams {
  double flow_pressure = 1.2e9;   // p, Pa (default: mild steel plate, as ArchardParams::hardness)
  double force_ratio = 2.0;       // K (Finnie's value)
  double depth_ratio = 2.0;       // psi (Finnie's value)
  double cutting_fraction = 0.5;  // c (Finnie's estimate)
  double velocity_exponent = 2.0; // n (the model's own)
};

// f(alpha), alpha in radians in [0, pi/2].
inline double finnie_angle_function(double alpha, double K) {
  const double s = std::sin(alpha), c = std::cos(alpha);
  if (s <= (K / 6.0) * c) return std::sin(2.0 * alpha) - (6.0 / K) * s * s;
  return K * c * c / 6.0;
}

// The part of Q that depends on the impact: M v^2 (v / 1 m/s)^(n-2) f(alpha), kg m^2/s^2.
inline double finnie_impact_measure(const FinnieParams& p, double mass, double speed, double alpha) {
  return mass * speed * speed * std::pow(speed, p.velocity_exponent - 2.0) *
         finnie_angle_function(alpha, p.force_ratio);
}

// Eroded volume, m^3, from a sum of finnie_impact_measure.
inline double finnie_volume(const FinnieParams& p, double impact_measure) {
  return p.cutting_fraction * impact_measure / (p.flow_pressure * p.depth_ratio * p.force_ratio);
}

}  // namespace chutelab::dem::wear
