#define BOOST_TEST_MODULE logs
// The log import's statistics on series whose answer is known in closed form.
#include <boost/test/unit_test.hpp>
#include <cmath>
#include <vector>

#include "logs/correlated_mean.h"
#include "logs/steady_log.h"
#include "logs/uncertainty_budget.h"
#include "validation/synthesize.h"

using namespace chutelab;
using namespace chutelab::logs;

namespace {

// An AR(1) series x_k = a x_{k-1} + sqrt(1 - a^2) e_k: unit variance, integrated autocorrelation
// time (1 + a) / (2 (1 - a)) samples.
std::vector<double> ar1(std::size_t n, double a, std::uint64_t seed) {
  validation::NormalStream r(seed);
  std::vector<double> x(n);
  double v = r.next();
  for (auto& y : x) {
    v = a * v + std::sqrt(1.0 - a * a) * r.next();
    y = v;
  }
  return x;
}

std::vector<double> times(std::size_t n, double dt) {
  std::vector<double> t(n);
  for (std::size_t k = 0; k < n; ++k) t[k] = static_cast<double>(k + 1) * dt;
  return t;
}

}  // namespace

BOOST_AUTO_TEST_CASE(autocorrelation_time_of_white_noise_and_of_ar1) {
  // White noise: 1/2 sample; AR(1) with a = 0.9: 9.5 samples. Tolerance: the estimate's own scatter,
  // about sqrt(2 (2M + 1) / n) relative (Sokal), 0.05 and 0.2 here; three times that.
  BOOST_TEST(std::abs(autocorrelation_time(ar1(20000, 0.0, 1)) - 0.5) < 0.15);
  BOOST_TEST(std::abs(autocorrelation_time(ar1(20000, 0.9, 2)) / 9.5 - 1.0) < 0.3);
}

BOOST_AUTO_TEST_CASE(standard_error_of_correlated_samples_is_neither_too_small_nor_too_large) {
  // 200 AR(1) windows of 3000 samples (tau 9.5, 158 independent samples): the spread of their means
  // is sqrt(2 tau / n) = 0.0796. The mean stated se must match it within 15 % (the batch estimate's
  // own scatter over 200 windows is ~3 %; the exponential-correlation widening is exact for AR(1)
  // only in the continuous limit), and sd/sqrt(n), 4.4 times too small, must not be what it says.
  const double a = 0.9, tau = (1 + a) / (2 * (1 - a));
  const std::size_t n = 3000;
  const auto t = times(n, 0.01);
  double sum_se = 0.0, sum2 = 0.0;
  for (int s = 0; s < 200; ++s) {
    const auto x = ar1(n, a, 100 + s);
    const CorrelatedMean m = correlated_mean(t, x, 0.0, t.back());
    BOOST_REQUIRE(m.ok());
    sum_se += m.se;
    sum2 += m.mean * m.mean;
  }
  const double truth = std::sqrt(2.0 * tau / static_cast<double>(n));
  BOOST_TEST(std::abs(sum_se / 200.0 / truth - 1.0) < 0.15);
  BOOST_TEST(std::abs(std::sqrt(sum2 / 200.0) / truth - 1.0) < 0.15);
}

BOOST_AUTO_TEST_CASE(budget_widens_few_degrees_of_freedom_and_warns) {
  // One part of 5 dof: widened by sqrt(5/3); of 2 dof: too short, widened as 3 dof, sqrt(3).
  const Budget b5 = combine({{"scatter", 1.0, 5.0}, {"calibration", 0.0, kInfiniteDof}});
  BOOST_TEST(b5.widening == std::sqrt(5.0 / 3.0), boost::test_tools::tolerance(1e-12));
  BOOST_TEST(!b5.too_short);
  const Budget b2 = combine({{"scatter", 1.0, 2.0}});
  BOOST_TEST(b2.too_short);
  BOOST_TEST(b2.u == std::sqrt(3.0), boost::test_tools::tolerance(1e-12));
  // Welch-Satterthwaite: two equal parts of 10 dof make 20.
  const Budget ws = combine({{"a", 1.0, 10.0}, {"b", 1.0, 10.0}});
  BOOST_TEST(ws.dof == 20.0, boost::test_tools::tolerance(1e-12));
  BOOST_TEST(t_quantile(0.05, kInfiniteDof) == 1.959964, boost::test_tools::tolerance(1e-6));
}

BOOST_AUTO_TEST_CASE(segments_of_a_log_are_found) {
  // 5 s unloaded, a first-order rise (0.5 s) to 20 N, steady to 30 s, a fall (0.3 s), 5 s unloaded;
  // 50 Hz, noise 0.1 N. The rule accepts the rise within 0.5 % (0.1 N, 5.3 time constants) on whole
  // 1 s blocks, 8-9 s; the window starts as far again after it (11-13 s), where the rise is
  // 20 e^-12 N, nothing. It ends before the fall, by at most twice two blocks (26-30 s); the tares
  // stay clear of both changes.
  const double dt = 0.02;
  validation::NormalStream r(7);
  std::vector<double> t, v;
  for (double s = dt; s <= 36.0; s += dt) {
    double load = 0.0;
    if (s > 5.0) load = 20.0 * (1.0 - std::exp(-(s - 5.0) / 0.5));
    if (s > 30.0) load = 20.0 * std::exp(-(s - 30.0) / 0.3);
    t.push_back(s);
    v.push_back(load + 0.1 * r.next());
  }
  const LogSegments sg = find_segments(t, v);
  BOOST_TEST(sg.loaded);
  BOOST_TEST(sg.steady);
  BOOST_TEST(sg.window.start > 11.0);
  BOOST_TEST(sg.window.start < 13.0);
  BOOST_TEST(sg.window.end <= 30.0);
  BOOST_TEST(sg.window.end > 26.0);
  BOOST_TEST(sg.before.ok());
  BOOST_TEST(sg.before.end < 5.0);
  BOOST_TEST(sg.after.ok());
  BOOST_TEST(sg.after.start > 30.5);
}

BOOST_AUTO_TEST_CASE(a_log_without_load_is_said_so) {
  std::vector<double> t, v;
  validation::NormalStream r(3);
  for (int k = 1; k <= 1000; ++k) {
    t.push_back(0.02 * k);
    v.push_back(0.01 * r.next() - 1.0);
  }
  const LogSegments sg = find_segments(t, v);
  BOOST_TEST(!sg.loaded);
  BOOST_REQUIRE(!sg.warnings.empty());
  BOOST_TEST(sg.warnings.front().find("never carries a load") != std::string::npos);
}
