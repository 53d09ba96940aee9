#pragma once
// Coulomb-like rolling friction of reference study Eq 10: a constant directional torque
//   T_R,i = -mu_r F_n R_i w_rel/|w_rel|,   T_R,j = +mu_r F_n R_j w_rel/|w_rel|,
// with w_rel = w_i - w_j (w_i alone against a non-rotating wall, which is Eq 10 as printed; the
// relative form gives no torque to two spheres rotating together). A constant torque would reverse
// the rotation of a sphere that has (nearly) stopped and make it chatter, so the torque is capped at
// what stops the relative rotation within one step. Stopping exactly leaves a round-off residue that the
// cap would shrink by ~1e-16 per step into subnormal numbers (which are ~100x slower on x86); below
// kRestSpin (1e-9 rad/s, a surface speed of ~1e-12 m/s for millimetre grains) the contact is at rest.
#include <cmath>

#include "dem/contact/kinematics.h"
#include "dem/contact/pair_coeffs.h"

namespace chutelab::dem {

struct RollingConstantTorque {
  static constexpr bool has_history = false;
  static constexpr double kRestSpin = 1e-9;  // rad/s
  // Selects instead of branches, so the pair loop vectorises across contacts: an inactive contact
  // adds a zero torque.
  CHUTELAB_INLINE static void torque(const SharedCoeffs& c, const NormalResult& nr, const ContactKinematics& k,
                                     LaneVec* /*history*/, double dt, LaneVec& ti, LaneVec& tj) {
    const double fn = std::max(nr.force, 0.0);
    const double w2 = k.w_rel.squared_norm();
    const bool active = c.rolling_friction > 0.0 && fn > 0.0 && w2 > kRestSpin * kRestSpin;
    const double w = std::sqrt(active ? w2 : 1.0);
    const double mag = c.rolling_friction * fn;  // torque per unit lever arm
    const double stop = mag * (k.r_i * k.inv_inertia_i + k.r_j * k.inv_inertia_j) * dt;
    const double capped = stop > w ? mag * (w / stop) : mag;
    const LaneVec dir = k.w_rel * ((active ? capped : 0.0) / w);  // one division, not three
    ti -= k.r_i * dir;
    tj += k.r_j * dir;
  }
};

struct NoRolling {
  static constexpr bool has_history = false;
  CHUTELAB_INLINE static void torque(const SharedCoeffs&, const NormalResult&, const ContactKinematics&, LaneVec*,
                                     double, LaneVec&, LaneVec&) {}
};

}  // namespace chutelab::dem
