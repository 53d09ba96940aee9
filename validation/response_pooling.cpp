#include "validation/response_pooling.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace chutelab::validation {

PooledResponse pool_responses(std::span<const double> own, std::span<const double> sd,
                              std::span<const std::optional<double>> shape) {
  if (own.size() != sd.size() || own.size() != shape.size()) throw std::logic_error("pool_responses: one sd and shape per response");
  PooledResponse out;
  out.response.assign(own.begin(), own.end());
  // The shape: the cheap models' response where they give one; where they respond nowhere, a common
  // response (the same at every condition). A response without a shape where others have one is
  // kept as it is.
  bool has_shape = false;
  for (const auto& s : shape) has_shape = has_shape || (s && *s != 0.0);
  std::vector<std::size_t> in;
  for (std::size_t i = 0; i < own.size(); ++i)
    if (!has_shape || shape[i]) in.push_back(i);
  auto g = [&](std::size_t i) { return has_shape ? *shape[i] : 1.0; };
  const double n = static_cast<double>(in.size());
  double noise = 0.0, scale2 = 0.0;
  for (std::size_t i : in) {
    noise += sd[i] * sd[i];
    scale2 += own[i] * own[i];
  }
  // Three responses are the fewest that say anything about their spread once a scale is fitted;
  // with no stated noise there is nothing to weigh.
  if (in.size() < 3 || noise == 0.0) return out;
  // A floor on the weights' variance, far below any response, so that exact responses weigh much
  // and finitely.
  const double floor = 1e-24 * (scale2 / n) + 1e-300;
  // The scale at a given spread (weighted least squares), and the weighted residual sum of squares.
  double beta = 0.0;
  auto q_at = [&](double tau2) {
    double num = 0.0, den = 0.0;
    for (std::size_t i : in) {
      const double w = 1.0 / std::max(sd[i] * sd[i] + tau2, floor);
      num += w * g(i) * own[i];
      den += w * g(i) * g(i);
    }
    beta = den > 0.0 ? num / den : 0.0;
    double q = 0.0;
    for (std::size_t i : in) q += std::pow(own[i] - beta * g(i), 2) / std::max(sd[i] * sd[i] + tau2, floor);
    return q;
  };
  // The spread by Paule and Mandel's rule: the one at which the weighted residuals' sum of squares
  // equals its degrees of freedom (none beyond the noise when it is below them already). Unlike the
  // unweighted moments it lets a noisy response's deviation count only as much as its noise allows.
  double tau2 = 0.0;
  if (q_at(0.0) > n - 1.0) {
    double lo = 0.0, hi = scale2 / n + noise;  // the sum falls below n - 1 there: every weight ~1/hi
    for (int i = 0; i < 200 && q_at(hi) > n - 1.0; ++i) hi *= 2.0;
    for (int i = 0; i < 100; ++i) {
      const double mid = 0.5 * (lo + hi);
      (q_at(mid) > n - 1.0 ? lo : hi) = mid;
    }
    tau2 = hi;
  }
  (void)q_at(tau2);
  for (std::size_t i : in) {
    const double v = sd[i] * sd[i];
    if (v + tau2 > 0.0) out.response[i] = (tau2 * own[i] + v * beta * g(i)) / (tau2 + v);
  }
  out.scale = beta;
  out.spread = std::sqrt(tau2);
  out.pooled = true;
  return out;
}

}  // namespace chutelab::validation
