#include "logs/uncertainty_budget.h"

#include <algorithm>
#include <cmath>
#include <gsl/gsl_cdf.h>

namespace chutelab::logs {

Budget combine(std::vector<UncertaintyPart> parts) {
  Budget b;
  b.parts = std::move(parts);
  double s2 = 0.0, s4 = 0.0;
  for (const auto& p : b.parts) {
    s2 += p.u * p.u;
    if (std::isfinite(p.dof) && p.dof > 0.0) s4 += std::pow(p.u, 4) / p.dof;
  }
  b.combined = std::sqrt(s2);
  b.dof = s4 > 0.0 ? s2 * s2 / s4 : kInfiniteDof;
  b.too_short = b.dof < kMinDof;
  const double nu = std::max(b.dof, kMinDof - 1.0);
  b.widening = std::isfinite(nu) ? std::sqrt(nu / (nu - 2.0)) : 1.0;
  b.u = b.combined * b.widening;
  return b;
}

double t_quantile(double alpha, double dof) {
  if (!std::isfinite(dof) || dof > 1e6) return gsl_cdf_ugaussian_Pinv(1.0 - alpha / 2.0);
  return gsl_cdf_tdist_Pinv(1.0 - alpha / 2.0, std::max(dof, 1.0));
}

}  // namespace chutelab::logs
