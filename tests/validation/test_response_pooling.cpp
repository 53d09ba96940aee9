// validation/response_pooling.h: an expensive model's noisy own responses read together.
#include <boost/test/unit_test.hpp>
#include <cmath>

#include "validation/response_pooling.h"

using namespace chutelab;
using namespace chutelab::validation;

BOOST_AUTO_TEST_SUITE(response_pooling)

// Exact responses (no stated noise) are what they are: nothing to weigh.
BOOST_AUTO_TEST_CASE(responses_without_noise_are_kept) {
  const std::vector<double> own = {1.0, 5.0, -2.0, 0.5}, sd(4, 0.0);
  const std::vector<std::optional<double>> shape = {1.0, 1.0, 1.0, 1.0};
  const auto r = pool_responses(own, sd, shape);
  BOOST_TEST(!r.pooled);
  BOOST_TEST(r.response == own, boost::test_tools::per_element());
}

// Two responses say nothing about their spread about a fitted scale.
BOOST_AUTO_TEST_CASE(too_few_responses_are_kept) {
  const std::vector<double> own = {1.0, 9.0}, sd = {0.1, 5.0};
  const std::vector<std::optional<double>> shape = {1.0, 1.0};
  const auto r = pool_responses(own, sd, shape);
  BOOST_TEST(!r.pooled);
  BOOST_TEST(r.response == own, boost::test_tools::per_element());
}

// Six precise responses twice the shape (a code responding twice as strongly as the analytical
// chain) and one probe that caught a fluctuation: 12 times the shape, with a standard error 40
// times the others'. The precise ones fix the scale at 2 and leave no spread beyond their noise, so
// the noisy one is read as twice its shape; the precise ones move by less than their own sd.
BOOST_AUTO_TEST_CASE(a_noisy_probe_is_read_with_the_shape_the_precise_ones_give) {
  const std::vector<std::optional<double>> shape = {-0.3, -0.5, -0.8, -1.2, -1.5, -1.7, -0.4};
  std::vector<double> own, sd;
  for (std::size_t i = 0; i + 1 < shape.size(); ++i) own.push_back(2.0 * *shape[i] + (i % 2 ? 0.02 : -0.02)), sd.push_back(0.05);
  own.push_back(12.0 * *shape.back());
  sd.push_back(2.0);
  const auto r = pool_responses(own, sd, shape);
  BOOST_TEST(r.pooled);
  // The scale from the precise six (their +-0.02 alternate); the noisy one weighs 1/1600 as much.
  BOOST_TEST(r.scale == 2.0, boost::test_tools::tolerance(0.02));
  // Its excess over the shape (4) is 2 of its sd: no spread beyond the noise is needed (the weighted
  // sum of squares ~5 is below its 6 degrees of freedom), so it is read as the shape.
  BOOST_TEST(std::abs(r.response.back() - 2.0 * *shape.back()) < 0.1 * std::abs(own.back() - 2.0 * *shape.back()));
  for (std::size_t i = 0; i + 1 < own.size(); ++i) BOOST_TEST(std::abs(r.response[i] - own[i]) < sd[i]);
}

// A precise response that disagrees with the shape is the code's own physics there: kept.
BOOST_AUTO_TEST_CASE(a_precise_response_that_departs_from_the_shape_is_kept) {
  const std::vector<std::optional<double>> shape = {1.0, 2.0, 3.0, 4.0, 5.0};
  const std::vector<double> own = {1.0, 2.0, 3.0, 4.0, -5.0}, sd = {0.3, 0.3, 0.3, 0.3, 0.001};
  const auto r = pool_responses(own, sd, shape);
  BOOST_TEST(r.pooled);
  BOOST_TEST(r.response[4] == -5.0, boost::test_tools::tolerance(1e-3));
}

// Where the cheap models do not respond at all, the shape is a common response: responses that are
// noise about one value move toward it, not toward zero.
BOOST_AUTO_TEST_CASE(without_a_shape_the_responses_share_a_common_value) {
  const std::vector<double> own = {-1.1, -0.9, -1.05, -0.95, -1.0, 3.0}, sd = {0.2, 0.2, 0.2, 0.2, 0.2, 4.0};
  const std::vector<std::optional<double>> shape(6, std::nullopt);
  const auto r = pool_responses(own, sd, shape);
  BOOST_TEST(r.pooled);
  BOOST_TEST(r.scale == -1.0, boost::test_tools::tolerance(0.05));
  BOOST_TEST(r.response.back() < -0.5);
  BOOST_TEST(r.response.back() > -1.5);
}

// A response with no shape where the others have one is not pooled with them.
BOOST_AUTO_TEST_CASE(a_response_without_a_shape_among_shaped_ones_is_kept) {
  const std::vector<double> own = {1.0, 2.0, 3.0, 7.0}, sd = {0.5, 0.5, 0.5, 3.0};
  const std::vector<std::optional<double>> shape = {1.0, 2.0, 3.0, std::nullopt};
  const auto r = pool_responses(own, sd, shape);
  BOOST_TEST(r.response[3] == 7.0);
}

BOOST_AUTO_TEST_SUITE_END()
