#include "dem/rigs/inclined_plane.h"

#include <cmath>
#include <limits>
#include <numbers>

#include <fmt/format.h>

#include "core/input_error.h"
#include "dem/contact/mixing.h"

namespace chutelab::dem::rigs {
namespace {
constexpr double pi = std::numbers::pi;
}

std::string_view name(Motion m) {
  switch (m) {
    case Motion::rest: return "rest";
    case Motion::roll: return "roll";
    case Motion::slide: return "slide";
  }
  return "?";
}

InclinePrediction predict_incline_onset(double mu_s, double mu_r) {
  InclinePrediction p;
  p.motion = mu_r < mu_s ? Motion::roll : Motion::slide;
  p.onset_deg = std::atan(std::min(mu_r, mu_s)) * 180.0 / pi;
  return p;
}

Motion incline_motion_at(const chutelab::Material& m, double mu_s, double mu_r, const Grain& g, double angle,
                         const InclineSettings& s) {
  const double g_acc = 9.80665;
  Settings st;
  st.gravity = Vec3(0, 0, -g_acc);
  st.rolling = s.rolling;
  st.threads = 1;
  st.domain = Box{Vec3::Constant(-1.0), Vec3::Constant(1.0)};
  st.characteristic_speed = 0.1;
  st.on_warning = [](const std::string&) {};
  World w(st);
  const RigMaterials rm = add_rig_materials(w, m, m.solid_density > 0 ? m.solid_density : 1000.0, s.modulus_scale, mu_s, mu_r);
  // The plane through the origin rises towards +x: normal (-sin, 0, cos); down the slope is -x'.
  const Vec3 n(-std::sin(angle), 0.0, std::cos(angle));
  const Vec3 down(-std::cos(angle), 0.0, -std::sin(angle));
  w.add_wall(Wall::plane("incline", Vec3::Zero(), n, rm.wall));

  // Released at rest at the Hertz equilibrium overlap of its weight (split over its contacts), so no
  // bounce disturbs the onset. A clump lies with its long axis across the slope (it can roll like a
  // cylinder), both spheres on the plane.
  const double r = 0.5 * g.diameter;
  const double rho = w.materials().material(rm.pellet).density;
  const double mass = rho * g.volume();
  const int contacts = g.kind == GrainKind::sphere ? 1 : static_cast<int>(g.clump.spheres.size());
  const double e_star = effective_youngs_modulus(w.materials().material(rm.pellet), w.materials().material(rm.wall));
  const double delta = std::pow(mass * g_acc * std::cos(angle) / contacts / (4.0 / 3.0 * e_star * std::sqrt(r)), 2.0 / 3.0);
  Mat3 R;
  R.col(0) = Vec3::UnitY();
  R.col(1) = down;
  R.col(2) = R.col(0).cross(R.col(1));
  const Vec3 start = (r - delta) * n;
  add_grain(w, g, start, Quat(R), rm.pellet, rho);
  w.initialise();

  // Grain velocity (mass-weighted over its spheres) and the largest slip speed at its contacts.
  auto state = [&](double& v_down, double& slip, double& speed) {
    const Particles& p = w.particles();
    Vec3 v = Vec3::Zero();
    double mt = 0.0;
    slip = 0.0;
    for (std::size_t i = 0; i < p.size(); ++i) {
      v += p.mass[i] * p.v[i];
      mt += p.mass[i];
      slip = std::max(slip, (p.v[i] + p.w[i].cross(-p.radius[i] * n)).norm());  // contact point's velocity
    }
    v /= mt;
    v_down = v.dot(down);
    speed = v.norm();
  };
  // Motion = acceleration down the slope between the middle and the end of the hold. Not displacement:
  // below the onset the constant-torque law (dem/contact/rolling_constant_torque.h) stops the spin
  // every step but cannot hold a static moment, so a grain creeps at a small constant speed
  // (~0.1 mm/s at mu_r = 0.1, growing with the angle and the time step) without ever accelerating.
  const auto half = static_cast<std::int64_t>(std::llround(0.5 * s.hold_time / w.dt()));
  w.step(half);
  double v_mid, slip_mid, speed_mid;
  state(v_mid, slip_mid, speed_mid);
  w.step(half);
  double v_end, slip_end, speed_end;
  state(v_end, slip_end, speed_end);
  const double accel = (v_end - v_mid) / (static_cast<double>(half) * w.dt());
  if (accel < s.accel_threshold) return Motion::rest;
  return slip_end > 0.5 * speed_end ? Motion::slide : Motion::roll;
}

InclineResult find_incline_onset(const chutelab::Material& m, double mu_s, double mu_r, const Grain& g,
                                 const InclineSettings& s) {
  if (!(mu_s >= 0.0) || !(mu_r >= 0.0))
    throw InputError("", 0, "incline", fmt::format("friction coefficients must be >= 0, got {} and {}", mu_s, mu_r));
  if (!(s.resolution_deg > 0.0) || !(s.max_angle_deg > 0.0) || s.max_angle_deg >= 90.0)
    throw InputError("", 0, "incline", "need resolution > 0 and 0 < max angle < 90 deg");
  InclineResult res;
  res.predicted = predict_incline_onset(mu_s, mu_r);
  double lo = 0.0, hi = s.max_angle_deg;
  Motion at_hi = incline_motion_at(m, mu_s, mu_r, g, hi * pi / 180.0, s);
  ++res.runs;
  if (at_hi == Motion::rest) {
    res.onset_deg = std::numeric_limits<double>::quiet_NaN();
    return res;
  }
  while (hi - lo > s.resolution_deg) {
    const double mid = 0.5 * (lo + hi);
    const Motion mm = incline_motion_at(m, mu_s, mu_r, g, mid * pi / 180.0, s);
    ++res.runs;
    if (mm == Motion::rest) {
      lo = mid;
    } else {
      hi = mid;
      at_hi = mm;
    }
  }
  res.onset_deg = 0.5 * (lo + hi);
  res.motion = at_hi;
  return res;
}

}  // namespace chutelab::dem::rigs
