#pragma once
// Tangential spring with history and a Coulomb limit (Cundall & Strack 1979; with the Mindlin no-slip
// stiffness of hertz_mindlin.h this is the tangential half of Hertz-Mindlin). The history is the
// accumulated tangential displacement of i relative to j; it is kept in the current tangent plane
// (rotated with the contact, length preserved) and truncated at the Coulomb limit so that the spring
// alone carries mu F_n while sliding.
#include <cmath>

#include "dem/contact/kinematics.h"
#include "dem/contact/pair_coeffs.h"

namespace chutelab::dem {

struct CoulombHistorySpring {
  // Written with selects instead of branches so that the pair loop vectorises across contacts; each
  // select gives what the branch would.
  CHUTELAB_INLINE static LaneVec force(const SharedCoeffs& c, const NormalResult& nr, const LaneVec& n,
                                       const LaneVec& vt, LaneVec& shear, double dt) {
    const double s2 = shear.squared_norm();
    const LaneVec in_plane = shear - shear.dot(n) * n;
    const double p2 = in_plane.squared_norm();
    // p2 == 0: the history was zero or along n, and nothing is left to turn.
    const double keep = p2 > 0.0 ? std::sqrt(s2 / (p2 > 0.0 ? p2 : 1.0)) : 0.0;
    const LaneVec spring = in_plane * keep + vt * dt;
    LaneVec ft = -nr.kt * spring - nr.ct * vt;
    const double limit = c.friction * std::max(nr.force, 0.0);
    const double f2 = ft.squared_norm();
    const bool sliding = f2 > limit * limit;
    ft *= sliding ? limit / std::sqrt(sliding ? f2 : 1.0) : 1.0;
    // While sliding the spring holds exactly the Coulomb force.
    const bool reset = sliding && nr.kt > 0.0;
    shear = select(reset, ft * (-1.0 / (reset ? nr.kt : 1.0)), spring);
    return ft;
  }
};

// Frictionless contacts (used by verification tests that isolate the normal law).
struct NoTangential {
  CHUTELAB_INLINE static LaneVec force(const SharedCoeffs&, const NormalResult&, const LaneVec&, const LaneVec&,
                                       LaneVec& shear, double) {
    shear = LaneVec::zero();
    return LaneVec::zero();
  }
};

}  // namespace chutelab::dem
