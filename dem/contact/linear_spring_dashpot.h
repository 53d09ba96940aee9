#pragma once
// Linear spring-dashpot (reference study Eq 8): F_n = k_n delta + D_n d(delta)/dt with D_n = 2 zeta sqrt(k_n m*),
// zeta = -ln e / sqrt(ln^2 e + pi^2), which is the exact restitution of the damped linear oscillator
// when the contact ends at delta = 0 (tensile tail kept). Tangential spring k_t = ratio * k_n with the
// same damping ratio. The spring is LinearSpring; the damping the restitution damping part
// (dem/contact/damping_restitution.h).
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>
#include <string_view>

#include "dem/contact/damping_restitution.h"
#include "dem/contact/kinematics.h"
#include "dem/contact/law_parameters.h"
#include "dem/contact/spring_and_damping.h"
#include "dem/timestep.h"

namespace chutelab::dem {

struct LinearSpring {
  static constexpr std::string_view key = "lsd";
  static constexpr std::string_view title = "linear spring";
  static constexpr bool hertz_elastic = false;
  static constexpr bool fixed_tangential_ratio = false;
  static constexpr std::array<LawParameter, 2> parameters{{
      {"normal_stiffness", "N/m", "normal spring k_n", LawParameter::kRequired},
      // 2/7 gives equal normal and tangential periods.
      {"tangential_ratio", "", "tangential spring k_t / k_n", 2.0 / 7.0},
  }};

  struct Coeffs {
    double kn = 0.0;  // N/m
    double kt = 0.0;  // N/m
  };
  static Coeffs mix(const Material&, const Material&, const Interaction& in) {
    const double kn = in.law.value(parameters[0]);
    return {kn, kn * in.law.value(parameters[1])};
  }
  static std::string check(const Coeffs& c) {
    if (!(c.kn > 0.0)) return "needs normal_stiffness > 0 N/m";
    if (!(c.kt >= 0.0)) return "needs tangential_ratio >= 0";
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
    return c.kn > 0.0 ? linear_collision_time(m_eff, c.kn, zeta < 1.0 ? zeta : 0.0)
                      : std::numeric_limits<double>::infinity();
  }
  static double elastic_energy(const Coeffs& c, double delta, double /*r_eff*/) { return 0.5 * c.kn * delta * delta; }
  // The k_n that makes a collision of effective mass m_eff and damping ratio zeta last `duration`.
  static LawParameters matched_stiffness(double zeta, double m_eff, double duration, double& w0) {
    const double w = std::numbers::pi / duration;
    const double kn = m_eff * w * w / (1.0 - zeta * zeta);
    w0 = std::sqrt(kn / m_eff);
    return {{"normal_stiffness", kn}};
  }
};

struct LinearSpringDashpot : SpringAndDamping<LinearSpring, RestitutionDamping> {
  static constexpr std::string_view key = "lsd";
  static constexpr std::string_view title = "linear spring-dashpot (the reference study's Eq 8)";
  // None in LIGGGHTS: its hooke takes k_n from the moduli, and its hooke/stiffness damps by m* gamma_n
  // (as LAMMPS' gran/hooke/history), not by a restitution.
  static constexpr std::string_view liggghts = "";
  static LawParameters liggghts_pair_properties(const Coeffs&) { return {}; }  // no LIGGGHTS counterpart
};

}  // namespace chutelab::dem
