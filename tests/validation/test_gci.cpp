// The GCI module against ladders with a known order of convergence, and the DEM-like cases
// (noise, oscillation, divergence) where it must fall back to a stated bound.
#include <boost/test/unit_test.hpp>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "validation/gci.h"

using namespace chutelab::validation;
using chutelab::Quantity;

namespace {
std::vector<LadderLevel> ladder(const std::vector<double>& h, double (*f)(double)) {
  std::vector<LadderLevel> out;
  for (double x : h) out.push_back({x, f(x), 0.0});
  return out;
}
}  // namespace

BOOST_AUTO_TEST_SUITE(gci)

// f = f0 + a h^2 at a constant ratio 2: Richardson is exact for a pure power law, so p and f0 come
// back to rounding (1e-9), and the GCI band with Fs = 1.25 covers the true error of f1.
BOOST_AUTO_TEST_CASE(second_order_constant_ratio) {
  const auto lv = ladder({0.01, 0.02, 0.04}, [](double h) { return 3.0 + 0.5 * h * h; });
  const auto g = gci_estimate(lv);
  BOOST_TEST((g.kind == GciCase::three_level));
  BOOST_REQUIRE(g.observed_order);
  BOOST_TEST(*g.observed_order == 2.0, boost::test_tools::tolerance(1e-9));
  BOOST_REQUIRE(g.extrapolated);
  BOOST_TEST(*g.extrapolated == 3.0, boost::test_tools::tolerance(1e-12));
  BOOST_TEST(g.safety_factor == 1.25);
  const double e21 = 0.5 * (0.02 * 0.02 - 0.01 * 0.01);
  BOOST_TEST(g.gci_fine == 1.25 * e21 / 3.0, boost::test_tools::tolerance(1e-9));
  BOOST_TEST(g.gci_fine >= std::abs(lv[0].value - 3.0));
  BOOST_TEST(g.u_disc == g.gci_fine / 1.15, boost::test_tools::tolerance(1e-12));
  BOOST_REQUIRE(g.gci_fine_relative);
  BOOST_TEST(*g.gci_fine_relative == g.gci_fine / lv[0].value, boost::test_tools::tolerance(1e-12));
}

// Non-constant ratios need Celik's fixed-point iteration on q(p); without it p would come out
// wrong (ln(e32/e21)/ln r21 = 2.87 for this ladder instead of 2).
BOOST_AUTO_TEST_CASE(second_order_non_constant_ratio) {
  const auto lv = ladder({1.0, 1.5, 2.5}, [](double h) { return -4.0 + 0.2 * h * h; });
  const auto g = gci_estimate(lv);
  BOOST_REQUIRE(g.observed_order);
  BOOST_TEST(*g.observed_order == 2.0, boost::test_tools::tolerance(1e-9));
  BOOST_TEST(*g.extrapolated == -4.0, boost::test_tools::tolerance(1e-9));
  BOOST_TEST((g.kind == GciCase::three_level));
}

BOOST_AUTO_TEST_CASE(first_order_non_constant_ratio_unsorted_input) {
  std::vector<LadderLevel> lv = ladder({2.2, 1.0, 1.3}, [](double h) { return 2.0 - 0.3 * h; });
  const auto g = gci_estimate(lv);
  BOOST_REQUIRE(g.observed_order);
  BOOST_TEST(*g.observed_order == 1.0, boost::test_tools::tolerance(1e-9));
  BOOST_TEST(*g.extrapolated == 2.0, boost::test_tools::tolerance(1e-9));
  BOOST_TEST(g.fine_value == 2.0 - 0.3, boost::test_tools::tolerance(1e-12));
  // GCI = 1.25 |e21| / (r21 - 1) = 1.25 * 0.3 * 0.3 / 0.3
  BOOST_TEST(g.gci_fine == 1.25 * 0.3, boost::test_tools::tolerance(1e-9));
}

// Unequal ratios where the coarse difference is the smaller one (e32/e21 = 0.68, r32 = 1.24 <
// r21 = 1.7): still convergent, with p = 1.5; the constant-ratio formula would say p = -0.73.
BOOST_AUTO_TEST_CASE(fractional_order) {
  const auto lv = ladder({1.0, 1.7, 2.1}, [](double h) { return 10.0 + std::pow(h, 1.5); });
  const auto g = gci_estimate(lv);
  BOOST_TEST(*g.observed_order == 1.5, boost::test_tools::tolerance(1e-8));
  BOOST_TEST(*g.extrapolated == 10.0, boost::test_tools::tolerance(1e-9));
}

// Third order is outside the default bounds [0.5, 2]: p is clamped to 2 and Fs becomes 3.
BOOST_AUTO_TEST_CASE(order_outside_bounds_is_clamped) {
  const auto lv = ladder({1.0, 2.0, 4.0}, [](double h) { return 1.0 + 0.01 * h * h * h; });
  const auto g = gci_estimate(lv);
  BOOST_TEST((g.kind == GciCase::order_bounded));
  BOOST_TEST(*g.observed_order == 3.0, boost::test_tools::tolerance(1e-9));
  BOOST_TEST(g.order == 2.0);
  BOOST_TEST(g.safety_factor == 3.0);
  BOOST_TEST(g.gci_fine == 3.0 * 0.07 / 3.0, boost::test_tools::tolerance(1e-9));
}

// Two levels: assumed order (1 by default), Fs = 3; with p right the extrapolation is exact.
BOOST_AUTO_TEST_CASE(two_levels) {
  const auto lv = ladder({0.009, 0.0136}, [](double h) { return 100.0 + 500.0 * h; });
  const auto g = gci_estimate(lv);
  BOOST_TEST((g.kind == GciCase::two_level));
  BOOST_TEST(!g.observed_order);
  BOOST_TEST(g.safety_factor == 3.0);
  const double r = 0.0136 / 0.009, e = 500.0 * (0.0136 - 0.009);
  BOOST_TEST(g.gci_fine == 3.0 * e / (r - 1.0), boost::test_tools::tolerance(1e-9));
  BOOST_TEST(*g.extrapolated == 100.0, boost::test_tools::tolerance(1e-9));
  GciOptions o;
  o.assumed_order = 2.0;
  const auto g2 = gci_estimate(lv, o);
  BOOST_TEST(g2.gci_fine == 3.0 * e / (r * r - 1.0), boost::test_tools::tolerance(1e-9));
}

// Oscillatory: opposite signs; the bound is the larger of the finest pair's Fs = 3 band and
// Fs = 3 times half the range of the three values.
BOOST_AUTO_TEST_CASE(oscillatory_falls_back_to_a_bound) {
  const std::vector<LadderLevel> lv = {{1.0, 1.0, 0.0}, {2.0, 1.02, 0.0}, {4.0, 0.7, 0.0}};
  const auto g = gci_estimate(lv);
  BOOST_TEST((g.kind == GciCase::oscillatory));
  BOOST_TEST(!g.extrapolated);
  BOOST_TEST(g.gci_fine == 3.0 * 0.5 * 0.32, boost::test_tools::tolerance(1e-9));
  const std::vector<LadderLevel> lv2 = {{1.0, 1.0, 0.0}, {2.0, 1.2, 0.0}, {4.0, 1.1, 0.0}};
  const auto g2 = gci_estimate(lv2);
  BOOST_TEST((g2.kind == GciCase::oscillatory));
  BOOST_TEST(g2.gci_fine == 3.0 * 0.2 / 1.0, boost::test_tools::tolerance(1e-9));
}

// Noise: the fine difference (0.01) is inside 2 standard errors (2 * sqrt(2) * 0.02), so no order
// can be observed. The estimate is statistical, on the widest pair (e = 0.20, se = sqrt(2) 0.02,
// r = 2.25, p = 1): u = sqrt(e^2 + se^2) / 1.25, with no safety factor.
BOOST_AUTO_TEST_CASE(noise_dominated_is_a_statistical_estimate) {
  const std::vector<LadderLevel> lv = {{1.0, 1.00, 0.02}, {1.5, 1.01, 0.02}, {2.25, 1.20, 0.02}};
  const auto g = gci_estimate(lv);
  BOOST_TEST((g.kind == GciCase::noise_dominated));
  BOOST_TEST(!g.extrapolated);
  const double se = std::sqrt(2.0) * 0.02;
  BOOST_TEST(g.u_disc == std::hypot(0.20, se) / 1.25, boost::test_tools::tolerance(1e-9));
  BOOST_TEST(g.safety_factor == 1.0);
  BOOST_TEST(g.method.find("not resolved") != std::string::npos);
  // The same values without noise are a resolved ladder (monotone: p computed, not a bound).
  std::vector<LadderLevel> exact = lv;
  for (auto& l : exact) l.standard_error = 0.0;
  BOOST_TEST((gci_estimate(exact).kind != GciCase::noise_dominated));
  // Two levels within noise (e = 0.01, r = 1.5): the same estimate on that pair, which is a
  // fraction of the old Fs = 3 bound on 2 se, 3 * 2 se / 0.5.
  const auto g2 = gci_estimate(std::span(lv).first(2));
  BOOST_TEST((g2.kind == GciCase::noise_dominated));
  BOOST_TEST(g2.u_disc == std::hypot(0.01, se) / 0.5, boost::test_tools::tolerance(1e-9));
  BOOST_TEST(g2.u_disc < 3.0 * 2.0 * se / 0.5 / 1.15 / 4.0);
  // A pure-noise pair with no difference still carries its standard error: the ladder cannot
  // resolve an error smaller than that.
  const std::vector<LadderLevel> flat = {{1.0, 1.0, 0.02}, {2.0, 1.0, 0.02}};
  BOOST_TEST(gci_estimate(flat).u_disc == se, boost::test_tools::tolerance(1e-9));
}

// Two one-factor ladders of one run (time step and particle size) add in quadrature where both
// estimate a value, and a value only one of them estimates keeps that one's part.
BOOST_AUTO_TEST_CASE(ladders_combine_in_quadrature) {
  LadderUncertainty dt, size;
  dt.u_disc[Quantity::normal_force] = 0.3;
  dt.methods[static_cast<std::size_t>(Quantity::normal_force)] = {"dt"};
  size.u_disc[Quantity::normal_force] = 0.4;
  size.u_disc[Quantity::shear_force] = 0.1;
  size.methods[static_cast<std::size_t>(Quantity::normal_force)] = {"size"};
  dt.trajectory = {0.003, std::nullopt};
  size.trajectory = {0.004, 0.002};
  const std::vector<LadderUncertainty> parts = {dt, size};
  const LadderUncertainty c = combine_ladders(parts);
  BOOST_TEST(*c.u_disc[Quantity::normal_force] == 0.5, boost::test_tools::tolerance(1e-12));
  BOOST_TEST(*c.u_disc[Quantity::shear_force] == 0.1);
  BOOST_TEST(!c.u_disc[Quantity::exit_velocity]);
  BOOST_TEST(c.methods[static_cast<std::size_t>(Quantity::normal_force)].size() == 2u);
  BOOST_REQUIRE(c.trajectory.size() == 2u);
  BOOST_TEST(*c.trajectory[0] == 0.005, boost::test_tools::tolerance(1e-12));
  BOOST_TEST(*c.trajectory[1] == 0.002);
}

BOOST_AUTO_TEST_CASE(diverging_falls_back_to_a_bound) {
  // Differences grow as h falls: 0.1 between the fine pair, 0.05 between the coarse one.
  const std::vector<LadderLevel> lv = {{1.0, 1.0, 0.0}, {2.0, 1.1, 0.0}, {4.0, 1.15, 0.0}};
  const auto g = gci_estimate(lv);
  BOOST_TEST((g.kind == GciCase::diverging));
  BOOST_REQUIRE(g.observed_order);
  BOOST_TEST(*g.observed_order < 0.0);
  BOOST_TEST(g.gci_fine == 3.0 * 0.1 / 1.0, boost::test_tools::tolerance(1e-9));
}

BOOST_AUTO_TEST_CASE(bad_ladders_are_refused) {
  const std::vector<LadderLevel> one = {{1.0, 1.0, 0.0}};
  BOOST_CHECK_THROW(gci_estimate(one), std::invalid_argument);
  const std::vector<LadderLevel> same_h = {{1.0, 1.0, 0.0}, {1.0, 2.0, 0.0}};
  BOOST_CHECK_THROW(gci_estimate(same_h), std::invalid_argument);
  const std::vector<LadderLevel> neg_h = {{-1.0, 1.0, 0.0}, {1.0, 2.0, 0.0}};
  BOOST_CHECK_THROW(gci_estimate(neg_h), std::invalid_argument);
  const std::vector<LadderLevel> neg_se = {{1.0, 1.0, -0.1}, {2.0, 2.0, 0.0}};
  BOOST_CHECK_THROW(gci_estimate(neg_se), std::invalid_argument);
  const std::vector<LadderLevel> nan = {{1.0, std::nan(""), 0.0}, {2.0, 2.0, 0.0}};
  BOOST_CHECK_THROW(gci_estimate(nan), std::invalid_argument);
}

BOOST_AUTO_TEST_SUITE_END()

// A ladder of model predictions: every value two runs predict gets a GCI; the finest run's
// prediction carries it.
BOOST_AUTO_TEST_CASE(ladder_of_predictions) {
  using chutelab::Quantity;
  std::vector<ModelPrediction> p(3);
  const double h[3] = {0.009, 0.0136, 0.018};
  for (int i = 0; i < 3; ++i) {
    p[i].values[Quantity::normal_force] = 35.0 + 100.0 * h[i];   // first order
    p[i].uncertainty[Quantity::normal_force] = 1e-4;
    p[i].trajectory = {0.15 + 50.0 * h[i] * h[i]};                // second order
  }
  p[2].values[Quantity::shear_force] = 4.0;                       // one run only: not estimated
  const std::vector<LadderRun> runs = {{h[2], &p[2]}, {h[0], &p[0]}, {h[1], &p[1]}};
  const auto u = ladder_uncertainty(runs);
  BOOST_REQUIRE(u.estimate[0]);
  BOOST_TEST(*u.estimate[0]->observed_order == 1.0, boost::test_tools::tolerance(1e-6));
  BOOST_TEST(*u.estimate[0]->extrapolated == 35.0, boost::test_tools::tolerance(1e-9));
  BOOST_TEST(!u.u_disc[Quantity::shear_force]);
  BOOST_REQUIRE(u.trajectory.at(0));
  BOOST_TEST(*u.trajectory_estimate[0]->observed_order == 2.0, boost::test_tools::tolerance(1e-6));
  ModelPrediction fine = p[0];
  apply_discretisation(fine, u);
  BOOST_TEST(*fine.discretisation[Quantity::normal_force] == *u.u_disc[Quantity::normal_force]);
  BOOST_TEST(*fine.trajectory_discretisation.at(0) == *u.trajectory[0]);
  BOOST_TEST(fine.notes.size() == 1u);
}
