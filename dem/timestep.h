#pragma once
// Critical time scales of a DEM scene (reference study §3, Eq 11) and the default time step derived from them.
namespace chutelab::dem {

// Rayleigh wave time across a sphere: pi R sqrt(rho/G) / (0.1631 nu + 0.8766).
double rayleigh_time(double radius, double density, double shear_modulus, double poisson_ratio);
// Hertz collision duration, reference study Eq 11: 2.87 (m*^2 / (R* E*^2 V))^{1/5}.
double hertz_collision_time(double m_eff, double r_eff, double e_star, double impact_speed);
// Linear spring-dashpot collision duration pi / sqrt(k/m* (1 - zeta^2)).
double linear_collision_time(double m_eff, double kn, double zeta);

struct TimeStepEstimate {
  double rayleigh = 0.0;     // smallest Rayleigh time in the scene, s
  double collision = 0.0;    // shortest collision time (Hertz Eq 11 or linear), s
  double speed = 0.0;        // characteristic impact speed used, m/s
  double recommended = 0.0;  // default dt, s
  double unsafe_above = 0.0; // a dt above this is warned about, s
};

// Default dt: 1/10 of the collision time (as in the reference study), capped at 0.2 of the Rayleigh time.
// Unsafe: fewer than 4 steps per collision or more than 0.4 of the Rayleigh time.
inline constexpr double kDtFractionOfCollision = 0.1;
inline constexpr double kDtFractionOfRayleigh = 0.2;
inline constexpr double kUnsafeFractionOfCollision = 0.25;
inline constexpr double kUnsafeFractionOfRayleigh = 0.4;

}  // namespace chutelab::dem
