#include <boost/test/unit_test.hpp>
#include <cmath>
#include <vector>

#include "analytical/load_shape.h"
#include "core/input_error.h"

using namespace chutelab;
using namespace chutelab::analytical;
namespace tt = boost::test_tools;

namespace {
constexpr double pi = 3.14159265358979323846;

// Area and centroid height of a polygon (shoelace).
std::pair<double, double> polygon_area_centroid(const std::vector<std::pair<double, double>>& p) {
  double a = 0.0, cy = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const auto [x0, y0] = p[i];
    const auto [x1, y1] = p[(i + 1) % p.size()];
    const double cross = x0 * y1 - x1 * y0;
    a += cross;
    cy += (y0 + y1) * cross;
  }
  a *= 0.5;
  return {std::abs(a), cy / (6.0 * a)};
}
}  // namespace

BOOST_AUTO_TEST_SUITE(load_shape)

BOOST_AUTO_TEST_CASE(segment_area_and_centroid_against_numerical_integral) {
  // Chord 0.2 m, rise 0.04 m: R = (0.01 + 0.0016) / 0.08 = 0.145 m. Integrate the width
  // w(y) = 2 sqrt(R^2 - (y + R - h)^2) over 0..h with Simpson's rule (20 000 panels: error
  // well below 1e-9 of the area).
  const double W = 0.2, h = 0.04, R = (W * W / 4 + h * h) / (2 * h);
  const int n = 20000;
  double area = 0.0, moment = 0.0;
  for (int i = 0; i <= n; ++i) {
    const double y = h * i / n;
    const double w = 2.0 * std::sqrt(std::max(0.0, R * R - (y + R - h) * (y + R - h)));
    const double c = (i == 0 || i == n) ? 1.0 : (i % 2 ? 4.0 : 2.0);
    area += c * w;
    moment += c * w * y;
  }
  area *= h / (3.0 * n);
  moment *= h / (3.0 * n);
  const LoadShape s = flat_segment(W, h);
  BOOST_TEST(s.area == area, tt::tolerance(1e-6));
  BOOST_TEST(s.centroid_height == moment / area, tt::tolerance(1e-6));
  BOOST_TEST(s.height == h);
  // A half disc: area pi r^2 / 2 and centroid 4 r / (3 pi) above the chord.
  const LoadShape half = flat_segment(0.2, 0.1);
  BOOST_TEST(half.area == pi * 0.01 / 2, tt::tolerance(1e-12));
  BOOST_TEST(half.centroid_height == 0.4 / (3 * pi), tt::tolerance(1e-12));
}

BOOST_AUTO_TEST_CASE(segment_taller_than_half_its_chord_is_impossible) {
  BOOST_CHECK_THROW(flat_segment(0.2, 0.11), InputError);
  BOOST_CHECK_THROW(flat_segment(0.2, 0.0), InputError);
}

BOOST_AUTO_TEST_CASE(trough_area_and_centroid_against_polygon) {
  // 3-roll trough: centre roll 0.1 m, idlers at 35 deg, surcharge 20 deg, contact width 0.24 m.
  // Wings 0.07 m, depth 0.07 sin35 = 0.04015 m, top chord 0.1 + 2 * 0.07 cos35 = 0.21468 m.
  Trough t{35.0 * pi / 180, 0.1, 20.0 * pi / 180};
  const double w = 0.24, wing = 0.07, lam = t.idler_angle, th = t.surcharge_angle;
  const double depth = wing * std::sin(lam), top = 0.1 + 2 * wing * std::cos(lam);
  const double R = top / (2 * std::sin(th)), yc = depth - R * std::cos(th);
  std::vector<std::pair<double, double>> poly = {{-0.05, 0.0}, {0.05, 0.0}, {top / 2, depth}};
  const int n = 4000;  // arc as a 4000-gon: area error ~ (angle/n)^2, below 1e-7 relative
  for (int i = 1; i < n; ++i) {
    const double a = pi / 2 - th + 2 * th * i / n;
    poly.emplace_back(R * std::cos(a), yc + R * std::sin(a));
  }
  poly.emplace_back(-top / 2, depth);
  const auto [area, centroid] = polygon_area_centroid(poly);
  const LoadShape s = troughed_load(t, w);
  BOOST_TEST(s.area == area, tt::tolerance(1e-6));
  BOOST_TEST(s.centroid_height == centroid, tt::tolerance(1e-6));
  BOOST_TEST(s.height == depth + R * (1 - std::cos(th)), tt::tolerance(1e-12));
}

BOOST_AUTO_TEST_CASE(continuity_gives_the_area_of_the_flow) {
  // 26 t/h = 7.2222 kg/s at 2 m/s, rho_bl = 540: A = 7.2222 / (540 * 2) = 6.6872e-3 m^2.
  Belt flat;
  flat.loaded_width = 0.2;
  const LoadShape s = load_shape_for_flow(flat, 26.0 / 3.6, 540.0, 2.0);
  BOOST_TEST(s.area == 26.0 / 3.6 / (540.0 * 2.0), tt::tolerance(1e-9));
  BOOST_TEST(flat_segment(0.2, s.height).area == s.area, tt::tolerance(1e-9));
  // The thickness found by continuity gives back the same shape.
  BOOST_TEST(load_shape_for_thickness(flat, s.height).centroid_height == s.centroid_height,
             tt::tolerance(1e-12));

  Belt trough = flat;
  trough.loaded_width = 0.26;
  trough.trough = {35.0 * pi / 180, 0.1, 20.0 * pi / 180};
  const LoadShape ts = load_shape_for_flow(trough, 20.0 / 3.6, 540.0, 2.0);
  BOOST_TEST(ts.area == 20.0 / 3.6 / 1080.0, tt::tolerance(1e-9));
  BOOST_TEST(ts.contact_width <= 0.26);
  // More than the belt can hold is an input error, not a silent overflow.
  BOOST_CHECK_THROW(load_shape_for_flow(flat, 200.0, 540.0, 1.0), InputError);
  BOOST_CHECK_THROW(load_shape_for_flow(trough, 200.0, 540.0, 1.0), InputError);
}

BOOST_AUTO_TEST_SUITE_END()
