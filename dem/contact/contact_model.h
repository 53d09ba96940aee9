#pragma once
// A contact model composed at compile time from a normal law (a spring and a damping part, which also
// give the tangential spring its stiffness and dashpot; dem/contact/spring_and_damping.h, the registry
// in dem/contact/normal_laws.h), a tangential friction law, a rolling law and a cohesion part, so the
// hot loop has no virtual call and no branch on the model.
#include <utility>

#include "dem/contact/cohesion_sjkr.h"
#include "dem/contact/coulomb_history_spring.h"
#include "dem/contact/kinematics.h"
#include "dem/contact/normal_laws.h"
#include "dem/contact/pair_coeffs.h"
#include "dem/contact/rolling_constant_torque.h"
#include "dem/contact/rolling_epsd.h"

namespace chutelab::dem {

template <class Normal, class Tangential, class Rolling, class Cohesion>
struct ContactModel {
  using normal_law = Normal;
  using Coeffs = PairCoeffs<Normal>;
  static constexpr bool rolling_history = Rolling::has_history;

  // shear and roll are the contact's history (roll is unused unless rolling_history).
  CHUTELAB_INLINE static ContactForce compute(const Coeffs& c, const ContactKinematics& k, LaneVec& shear,
                                              LaneVec* roll, double dt) {
    const double vn = k.v_rel.dot(k.n);  // = d(delta)/dt
    NormalResult nr = Normal::normal(c.normal, k.delta, vn, k.r_eff, k.m_eff);
    Cohesion::apply(c, k.delta, k.r_eff, nr);
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

enum class TangentialModel { coulomb_history, frictionless };
enum class RollingModel { none, constant_torque, epsd };

// f.template operator()<ContactModel<...>>() for the scene's parts: the one place that turns the
// run-time choice into a compile-time model.
template <class F>
void with_contact_model(NormalLaw law, TangentialModel tangential, RollingModel rolling, bool cohesive, F&& f) {
  law.visit([&]<class N>() {
    auto with_cohesion = [&]<class T, class R>() {
      if (cohesive) f.template operator()<ContactModel<N, T, R, CohesionSjkr>>();
      else f.template operator()<ContactModel<N, T, R, NoCohesion>>();
    };
    auto with_rolling = [&]<class T>() {
      switch (rolling) {
        case RollingModel::none: with_cohesion.template operator()<T, NoRolling>(); break;
        case RollingModel::constant_torque: with_cohesion.template operator()<T, RollingConstantTorque>(); break;
        case RollingModel::epsd: with_cohesion.template operator()<T, RollingEpsd>(); break;
      }
    };
    if (tangential == TangentialModel::coulomb_history) with_rolling.template operator()<CoulombHistorySpring>();
    else with_rolling.template operator()<NoTangential>();
  });
}

}  // namespace chutelab::dem
