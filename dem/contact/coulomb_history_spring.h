#pragma once
// Tangential spring with history and a Coulomb limit (Cundall & Strack 1979; with the Mindlin no-slip
// stiffness of hertz_mindlin.h this is the tangential half of Hertz-Mindlin). The history is the
// accumulated tangential displacement of i relative to j; it is kept in the current tangent plane
// (rotated with the contact, length preserved) and truncated at the Coulomb limit so that the spring
// alone carries mu F_n while sliding.
#include <cmath>

#include "dem/contact/kinematics.h"

namespace chutelab::dem {

struct CoulombHistorySpring {
  CHUTELAB_INLINE static Vec3 force(const PairCoeffs& c, const NormalResult& nr, const Vec3& n, const Vec3& vt,
                    Vec3& shear, double dt) {
    const double s2 = shear.squaredNorm();
    if (s2 > 0.0) {
      shear -= shear.dot(n) * n;
      const double p2 = shear.squaredNorm();
      if (p2 > 0.0) shear *= std::sqrt(s2 / p2);
    }
    shear += vt * dt;
    Vec3 ft = -nr.kt * shear - nr.ct * vt;
    const double limit = c.friction * std::max(nr.force, 0.0);
    const double f2 = ft.squaredNorm();
    if (f2 > limit * limit) {
      ft *= limit / std::sqrt(f2);
      if (nr.kt > 0.0) shear = ft / -nr.kt;
    }
    return ft;
  }
};

// Frictionless contacts (used by verification tests that isolate the normal law).
struct NoTangential {
  CHUTELAB_INLINE static Vec3 force(const PairCoeffs&, const NormalResult&, const Vec3&, const Vec3&, Vec3& shear,
                    double) {
    shear.setZero();
    return Vec3::Zero();
  }
};

}  // namespace chutelab::dem
