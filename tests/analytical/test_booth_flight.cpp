#define BOOST_TEST_MODULE analytical
#include <boost/test/unit_test.hpp>
#include <cmath>

#include "analytical/booth.h"
#include "analytical/flight.h"

using namespace chutelab::analytical;
namespace tt = boost::test_tools;

namespace {
constexpr double g = 9.80665;
constexpr double pi = 3.14159265358979323846;
}  // namespace

BOOST_AUTO_TEST_SUITE(booth)

BOOST_AUTO_TEST_CASE(high_speed_leaves_at_the_top) {
  // V = 2 m/s on R = 0.13 m: K = 4 / (9.80665 * 0.13) = 3.1376 >= cos(0) -> tangent point.
  const Release r = booth_release({0.13, 2.0, 0.0, g, 0.0});
  BOOST_TEST(r.high_speed);
  BOOST_TEST(r.ratio == 4.0 / (g * 0.13), tt::tolerance(1e-12));
  BOOST_TEST(r.theta == 0.0);
  BOOST_TEST(r.position.x() == 0.0, tt::tolerance(1e-15));
  BOOST_TEST(r.position.y() == 0.13, tt::tolerance(1e-12));
  BOOST_TEST(r.velocity.x() == 2.0, tt::tolerance(1e-12));
  BOOST_TEST(std::abs(r.velocity.y()) < 1e-15);
}

BOOST_AUTO_TEST_CASE(low_speed_release_angle_is_acos_K) {
  // V = 1 m/s on R = 0.13 m: K = 1 / 1.27486 = 0.78440; theta = acos(K) = 38.32 deg.
  const double K = 1.0 / (g * 0.13);
  const Release r = booth_release({0.13, 1.0, 0.0, g, 0.0});
  BOOST_TEST(!r.high_speed);
  BOOST_TEST(r.theta == std::acos(K), tt::tolerance(1e-12));
  BOOST_TEST(r.theta * 180 / pi == 38.32, tt::tolerance(1e-3));
  // Leaves on the pulley surface, moving along the tangent at belt speed.
  BOOST_TEST(r.position.norm() == 0.13, tt::tolerance(1e-12));
  BOOST_TEST(std::abs(r.position.dot(r.velocity)) < 1e-14);
  BOOST_TEST(r.velocity.norm() == 1.0, tt::tolerance(1e-12));
  BOOST_TEST(r.velocity.y() < 0.0);  // past the top the tangent points down
}

BOOST_AUTO_TEST_CASE(inclined_belt_moves_the_tangent_point_back) {
  // A belt climbing at 10 deg meets the pulley 10 deg behind the top; at 2 m/s it leaves there,
  // along the belt direction.
  const double inc = 10.0 * pi / 180.0;
  const Release hi = booth_release({0.13, 2.0, inc, g, 0.0});
  BOOST_TEST(hi.high_speed);
  BOOST_TEST(hi.theta == -inc, tt::tolerance(1e-12));
  BOOST_TEST(hi.position.x() == -0.13 * std::sin(inc), tt::tolerance(1e-12));
  BOOST_TEST(hi.velocity.y() == 2.0 * std::sin(inc), tt::tolerance(1e-12));
  // At 1.1 m/s, K = 1.21 / 1.27486 = 0.949 < cos(10 deg) = 0.985: low-speed, released past the top.
  const Release lo = booth_release({0.13, 1.1, inc, g, 0.0});
  BOOST_TEST(!lo.high_speed);
  BOOST_TEST(lo.theta == std::acos(1.21 / (g * 0.13)), tt::tolerance(1e-12));
}

BOOST_AUTO_TEST_CASE(holding_force_delays_release) {
  // 25 m/s^2 towards the axis at 2 m/s on r = 0.13 m: cos(theta) = (V^2/r - a) / g
  // = (30.769 - 25) / 9.80665 = 0.5883, so the material rides the pulley to theta = 53.96 deg.
  const Release r = booth_release({0.13, 2.0, 0.0, g, 25.0});
  BOOST_TEST(!r.high_speed);
  BOOST_TEST(r.theta == std::acos((4.0 / 0.13 - 25.0) / g), tt::tolerance(1e-12));
}

BOOST_AUTO_TEST_SUITE_END()

BOOST_AUTO_TEST_SUITE(flight)

BOOST_AUTO_TEST_CASE(ballistic_hand_calculation_vertical_plate) {
  // Released at (0, 0.15) with (3, 0) m/s towards a vertical plate at x = 0.4 m:
  // t = 0.4 / 3 = 0.13333 s, drop s = g t^2 / 2 = 0.087163 m, vy = -g t = -1.30755 m/s,
  // alpha_p = atan(1.30755 / 3) = 23.552 deg, V_p^2 = 3^2 + 2 g s.
  const Trajectory tr({0.0, {0.0, 0.15}, {3.0, 0.0}}, g);
  PlateLine plate{{0.4, 0.25}, 0.0, 0.5};
  const auto hit = tr.hit(plate);
  BOOST_REQUIRE(hit);
  const double t = 0.4 / 3.0, s = 0.5 * g * t * t;
  BOOST_TEST(hit->point.t == t, tt::tolerance(1e-12));
  BOOST_TEST(hit->point.position.y() == 0.15 - s, tt::tolerance(1e-12));
  BOOST_TEST(hit->alpha == std::atan(g * t / 3.0), tt::tolerance(1e-12));
  BOOST_TEST(hit->alpha * 180 / pi == 23.552, tt::tolerance(1e-4));
  BOOST_TEST(hit->speed * hit->speed == 9.0 + 2.0 * g * s, tt::tolerance(1e-12));
  BOOST_TEST(hit->on_plate);
  BOOST_TEST(hit->along == 0.25 - (0.15 - s), tt::tolerance(1e-12));
}

BOOST_AUTO_TEST_CASE(inclined_plate_hit_lies_on_the_face) {
  // Plate hinged at (0.4, 0.25), top leaning 20 deg towards the pulley.
  const Trajectory tr({0.0, {0.0, 0.15}, {3.0, 0.0}}, g);
  PlateLine plate{{0.4, 0.25}, 20.0 * pi / 180.0, 0.5};
  const auto hit = tr.hit(plate);
  BOOST_REQUIRE(hit);
  BOOST_TEST(std::abs(plate.signed_distance(hit->point.position)) < 1e-12);
  BOOST_TEST(hit->point.position.x() > 0.4);  // below the hinge the face is further away
  BOOST_TEST(hit->on_plate);
}

BOOST_AUTO_TEST_CASE(integrator_matches_closed_form_without_added_force) {
  // Requirement: closed form and integrator agree to 1e-6 m when no force is added. RK4 is exact
  // for constant acceleration, so the difference is rounding; 1e-9 m would still pass.
  const FlightPoint start{0.0, {-0.02, 0.16}, {2.5, 0.4}};
  const Trajectory exact(start, g);
  const Trajectory integrated(start, g, [](const Eigen::Vector2d&) { return Eigen::Vector2d::Zero(); },
                              1e-3);
  for (double t : {0.0123, 0.1, 0.25}) {
    BOOST_TEST((exact.at_time(t).position - integrated.at_time(t).position).norm() < 1e-6);
  }
  for (double beta : {0.0, 0.3, -0.2}) {
    PlateLine plate{{0.35, 0.25}, beta, 0.5};
    const auto a = exact.hit(plate), b = integrated.hit(plate);
    BOOST_REQUIRE(a);
    BOOST_REQUIRE(b);
    BOOST_TEST((a->point.position - b->point.position).norm() < 1e-6);
    BOOST_TEST(std::abs(a->speed - b->speed) < 1e-6);
  }
  const auto xa = exact.at_x(0.2), xb = integrated.at_x(0.2);
  BOOST_REQUIRE(xa);
  BOOST_REQUIRE(xb);
  BOOST_TEST(std::abs(xa->position.y() - xb->position.y()) < 1e-6);
}

BOOST_AUTO_TEST_CASE(integrator_with_linear_drag_matches_exact_solution) {
  // a = -k v - g ey has the exact solution x = v0x (1 - e^{-kt}) / k,
  // vy = (vy0 + g/k) e^{-kt} - g/k, y = y0 + (vy0 + g/k)(1 - e^{-kt})/k - g t / k.
  const double k = 2.0;
  const FlightPoint start{0.0, {0.0, 0.2}, {4.0, 1.0}};
  const Trajectory tr(start, g, [k](const Eigen::Vector2d& v) { return Eigen::Vector2d(-k * v); },
                      1e-3);
  const double t = 0.3, e = std::exp(-k * t);
  const auto p = tr.at_time(t);
  // RK4 global error ~ (k dt)^4 k t: far below 1e-9 m here.
  BOOST_TEST(std::abs(p.position.x() - 4.0 * (1 - e) / k) < 1e-9);
  BOOST_TEST(std::abs(p.position.y() - (0.2 + (1.0 + g / k) * (1 - e) / k - g * t / k)) < 1e-9);
  BOOST_TEST(std::abs(p.velocity.y() - ((1.0 + g / k) * e - g / k)) < 1e-9);
}

BOOST_AUTO_TEST_CASE(stream_that_falls_short_is_reported) {
  const Trajectory tr({0.0, {0.0, 0.15}, {0.5, 0.0}}, g);
  PlateLine plate{{0.6, 0.25}, 0.0, 0.3};  // the stream is far below the plate's lower edge
  const auto hit = tr.hit(plate);
  BOOST_REQUIRE(hit);
  BOOST_TEST(!hit->on_plate);
  // A stream moving away from the plate never reaches it.
  const Trajectory away({0.0, {0.0, 0.15}, {-1.0, 0.0}}, g);
  BOOST_TEST(!away.hit(plate));
}

BOOST_AUTO_TEST_SUITE_END()
