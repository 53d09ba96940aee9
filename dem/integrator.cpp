#include "dem/integrator.h"

#include <algorithm>

namespace chutelab::dem {
namespace {

// The blow-up and lost-particle test (NaN fails every comparison, so one chain of && catches
// non-finite states too).
inline bool state_ok(const Vec3& v, const Vec3& w, const Vec3& x, double vlim2, const Box& dom) {
  return v.squaredNorm() <= vlim2 && w.squaredNorm() < 1e300 && x.x() >= dom.lo.x() && x.x() <= dom.hi.x() &&
         x.y() >= dom.lo.y() && x.y() <= dom.hi.y() && x.z() >= dom.lo.z() && x.z() <= dom.hi.z();
}

// One instance per kind of pass, so the loop carries no test of what the pass does.
template <bool Close, bool Open>
void rows(const VerletState& s, bool check, const StateLimits& limits, std::size_t lo, std::size_t hi,
          std::size_t& first_bad, double& maxd2) {
  Vec3* __restrict x = s.x;
  Vec3* __restrict v = s.v;
  Vec3* __restrict w = s.w;
  const Vec3* __restrict f = s.f;
  const Vec3* __restrict t = s.t;
  const double* __restrict im = s.inv_mass;
  const double* __restrict ii = s.inv_inertia;
  const Vec3* __restrict xr = s.x_ref;
  const double dt = s.dt, h = 0.5 * dt, vlim2 = limits.max_speed * limits.max_speed;
  const Box dom = limits.domain;
  std::size_t bad_first = first_bad;
  double m = maxd2;
  for (std::size_t i = lo; i < hi; ++i) {
    Vec3 vi = v[i], wi = w[i];
    if constexpr (Close) {
      vi += (h * im[i]) * f[i];
      wi += (h * ii[i]) * t[i];
      const bool bad = check && !state_ok(vi, wi, x[i], vlim2, dom);
      if (bad) bad_first = std::min(bad_first, i);
      if (!Open || bad) {
        v[i] = vi;
        w[i] = wi;
        continue;
      }
    }
    if constexpr (Open) {
      const Vec3 vn = vi + (h * im[i]) * f[i];
      v[i] = vn;
      w[i] = wi + (h * ii[i]) * t[i];
      const Vec3 xn = x[i] + dt * vn;
      x[i] = xn;
      m = std::max(m, (xn - xr[i]).squaredNorm());
    }
  }
  first_bad = bad_first;
  maxd2 = m;
}

}  // namespace

void verlet_rows(const VerletState& s, const VerletPass& pass, const StateLimits& limits, std::size_t lo,
                 std::size_t hi, std::size_t& first_bad, double& maxd2) {
  if (pass.close && pass.open) rows<true, true>(s, pass.check, limits, lo, hi, first_bad, maxd2);
  else if (pass.close) rows<true, false>(s, pass.check, limits, lo, hi, first_bad, maxd2);
  else if (pass.open) rows<false, true>(s, false, limits, lo, hi, first_bad, maxd2);
}

std::size_t BlockClosing::first_bad() const { return *std::min_element(first_bad_.begin(), first_bad_.end()); }

double BlockClosing::maxd2() const { return *std::max_element(maxd2_.begin(), maxd2_.end()); }

}  // namespace chutelab::dem
