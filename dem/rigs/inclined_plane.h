#pragma once
// Inclined-plane rig for the particle-wall rolling friction (reference study §5: "an inclination rig to determine
// the required rolling resistance to prevent particles either rolling or sliding down the inclined
// surface prematurely", details in Grima & Wypych 2010, reference [25] of the reference study).
//
// Theory (what the rig checks the DEM against). A sphere of radius R at rest on a plane at angle
// theta: gravity pulls m g sin(theta) down the slope, the normal force is N = m g cos(theta). At rest
// the contact friction F balances the pull, F = m g sin(theta), and F R is a moment that must be
// balanced by the rolling resistance; with the constant rolling torque of reference study Eq 10 the resistance
// can supply at most T = mu_r N R. So the sphere stays at rest while
//   F R <= mu_r N R   <=>  tan(theta) <= mu_r       (else it rolls), and
//   F   <= mu_s N     <=>  tan(theta) <= mu_s       (else it slides),
// and starts to move at tan(theta_c) = min(mu_r, mu_s): rolling when mu_r < mu_s (it then rolls without
// slipping, since the friction it needs, m g (2/7 sin + 5/7 mu_r cos), stays below mu_s N near the
// onset), sliding without rotation when mu_s < mu_r (the friction moment mu_s N R cannot overcome the
// rolling resistance). The rig finds the onset angle by bisection over fixed angles: at each angle the
// grain is released at rest (at its equilibrium overlap) and watched for hold_time: it has started to
// move when it accelerates down the slope.
#include <string>

#include "core/rig.h"
#include "dem/rigs/grain.h"

namespace chutelab::dem::rigs {

enum class Motion { rest, roll, slide };
std::string_view name(Motion m);

struct InclineSettings {
  double modulus_scale = 0.01;   // Young's modulus multiplier (the onset is a force balance; E only sets dt)
  double hold_time = 0.25;       // s watched at each angle
  double resolution_deg = 0.05;  // bisection stops at this bracket width
  double max_angle_deg = 60.0;
  double accel_threshold = 2e-3; // m/s^2 down the slope that counts as motion (rolling onset + ~0.015 deg)
  RollingModel rolling = RollingModel::constant_torque;
};

// The reference study's Eq 10 with Coulomb friction: onset angle (deg) and the motion that starts there.
struct InclinePrediction {
  double onset_deg = 0.0;
  Motion motion = Motion::roll;
};
InclinePrediction predict_incline_onset(double wall_friction, double wall_rolling_friction);

struct InclineResult {
  double onset_deg = 0.0;  // midpoint of the final bracket (NaN if it never moves below max_angle_deg)
  Motion motion = Motion::rest;  // what the grain did just above the onset
  InclinePrediction predicted;
  int runs = 0;
};

// What the grain does at one fixed angle (radians).
Motion incline_motion_at(const chutelab::Material& m, double wall_friction, double wall_rolling_friction,
                         const Grain& g, double angle, const InclineSettings& s);
// Bisection for the onset angle.
InclineResult find_incline_onset(const chutelab::Material& m, double wall_friction, double wall_rolling_friction,
                                 const Grain& g, const InclineSettings& s = {});

}  // namespace chutelab::dem::rigs
