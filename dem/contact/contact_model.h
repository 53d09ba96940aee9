#pragma once
// A contact law composed at compile time from a normal law (with its tangential stiffness), a
// tangential friction law and a rolling law, so the hot loop has no virtual call.
#include "dem/contact/coulomb_history_spring.h"
#include "dem/contact/cohesion_sjkr.h"
#include "dem/contact/hertz_mindlin.h"
#include "dem/contact/kinematics.h"
#include "dem/contact/linear_spring_dashpot.h"
#include "dem/contact/rolling_constant_torque.h"
#include "dem/contact/rolling_epsd.h"

namespace chutelab::dem {

template <class Normal, class Tangential, class Rolling>
struct ContactModel {
  using normal_law = Normal;
  static constexpr bool rolling_history = Rolling::has_history;

  // shear and roll are the contact's history (roll is unused unless rolling_history).
  CHUTELAB_INLINE static ContactForce compute(const PairCoeffs& c, const ContactKinematics& k, LaneVec& shear,
                                              LaneVec* roll, double dt) {
    const double vn = k.v_rel.dot(k.n);  // = d(delta)/dt
    NormalResult nr = Normal::normal(c, k.delta, vn, k.r_eff, k.m_eff);
    nr.force -= cohesion_sjkr(c, k.delta, k.r_eff);  // zero without cohesion; no branch in the pair loop
    const LaneVec vt = k.v_rel - vn * k.n;
    const LaneVec ft = Tangential::force(c, nr, k.n, vt, shear, dt);
    ContactForce out;
    out.force = ft - nr.force * k.n;
    const LaneVec nxft = k.n.cross(ft);
    out.torque_i = k.r_i * nxft;  // contact point at +R_i n from i
    out.torque_j = k.r_j * nxft;  // at -R_j n from j, force -ft
    Rolling::torque(c, nr, k, roll, dt, out.torque_i, out.torque_j);
    return out;
  }
};

enum class NormalModel { hertz_mindlin, linear_spring_dashpot };
enum class TangentialModel { coulomb_history, frictionless };
enum class RollingModel { none, constant_torque, epsd };

}  // namespace chutelab::dem
