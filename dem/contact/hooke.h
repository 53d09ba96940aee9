#pragma once
// Hooke with mass-proportional damping, the law of LAMMPS' pair_style gran/hooke/history (and of its
// chute benchmark, in.chute; Silbert, Ertas, Grest, Halsey, Levine & Plimpton, Phys. Rev. E 64,
// 051302, 2001; LIGGGHTS: model hooke/stiffness):
//   normal:     F_n = k_n delta + m* gamma_n d(delta)/dt
//   tangential: spring k_t (the tangential part's history), damping m* gamma_t
// k_n, k_t in N/m (HookeSpring) and gamma_n, gamma_t in 1/s (the mass-proportional damping part,
// dem/contact/damping_mass_proportional.h) are given per material pair (LAMMPS' defaults: k_t =
// 2/7 k_n, gamma_t = gamma_n / 2). Unlike the linear spring-dashpot (reference study Eq 8), whose
// damping is set per pair from a restitution, here the damping rate is fixed, so the restitution
// depends on the effective mass: with w0^2 = k_n / m* and zeta = gamma_n / (2 w0) < 1, a binary
// collision (tensile tail kept, as LAMMPS does without limit_damping) lasts pi / (w0 sqrt(1 - zeta^2))
// and rebounds with
//   e = exp(-pi zeta / sqrt(1 - zeta^2)),
// lighter contacts less damped than heavier ones (a sphere on a wall loses more than on its twin).
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>
#include <string_view>

#include "dem/contact/damping_mass_proportional.h"
#include "dem/contact/kinematics.h"
#include "dem/contact/law_parameters.h"
#include "dem/contact/spring_and_damping.h"
#include "dem/timestep.h"

namespace chutelab::dem {

// A linear spring with both stiffnesses given in N/m (LAMMPS' kn, kt).
struct HookeSpring {
  static constexpr std::string_view key = "hooke";
  static constexpr std::string_view title = "Hooke";
  static constexpr bool hertz_elastic = false;
  static constexpr bool fixed_tangential_ratio = false;
  static constexpr std::array<LawParameter, 2> parameters{{
      {"normal_stiffness", "N/m", "normal spring k_n", LawParameter::kRequired},
      {"tangential_stiffness", "N/m", "tangential spring k_t; 2/7 k_n if not given", LawParameter::kOwnRule},
  }};

  struct Coeffs {
    double kn = 0.0;  // N/m
    double kt = 0.0;  // N/m
  };
  static Coeffs mix(const Material&, const Material&, const Interaction& in) {
    Coeffs c;
    c.kn = in.law.value(parameters[0]);
    c.kt = in.law.get(parameters[1].key).value_or(2.0 / 7.0 * c.kn);
    return c;
  }
  static std::string check(const Coeffs& c) {
    if (!(c.kn > 0.0)) return "needs normal_stiffness > 0 N/m";
    if (!(c.kt >= 0.0)) return "needs tangential_stiffness >= 0 N/m";
    return {};
  }

  CHUTELAB_INLINE static SpringForce spring(const Coeffs& c, double delta, double /*r_eff*/) {
    return {c.kn * delta, c.kn, c.kt, 0.0};
  }
  static double restitution_scale() { return 1.0; }
  static double linear_stiffness(const Coeffs& c) { return c.kn; }
  // pi / w_d; an overdamped contact (zeta >= 1) does not rebound, and the undamped half period pi / w0
  // is then its time scale.
  static double collision_time(const Coeffs& c, double m_eff, double /*r_eff*/, double /*v*/, double zeta) {
    if (!(c.kn > 0.0)) return std::numeric_limits<double>::infinity();
    return linear_collision_time(m_eff, c.kn, zeta < 1.0 ? zeta : 0.0);
  }
  static double elastic_energy(const Coeffs& c, double delta, double /*r_eff*/) { return 0.5 * c.kn * delta * delta; }
  // The k_n that gives a collision of effective mass m_eff and damping ratio zeta the duration
  // `duration` (other masses then rebound differently: see above).
  static LawParameters matched_stiffness(double zeta, double m_eff, double duration, double& w0) {
    w0 = std::numbers::pi / duration / std::sqrt(1.0 - zeta * zeta);
    return {{"normal_stiffness", m_eff * w0 * w0}};
  }
};

struct Hooke : SpringAndDamping<HookeSpring, MassProportionalDamping> {
  static constexpr std::string_view key = "hooke";
  static constexpr std::string_view title = "Hooke with mass-proportional damping (LAMMPS gran/hooke/history)";
  static constexpr std::string_view liggghts = "hooke/stiffness";
  // LIGGGHTS' hooke/stiffness reads the four numbers per type pair (its damping, without
  // absolute_damping, is m* gamma as here).
  static LawParameters liggghts_pair_properties(const Coeffs& c) {
    return {{"kn", c.spring.kn}, {"kt", c.spring.kt}, {"gamman", c.damping.gamma_n}, {"gammat", c.damping.gamma_t}};
  }
};

}  // namespace chutelab::dem
