// The part of the stream a plate catches (analytical/stream_catch.h) against closed forms.
#include <boost/test/unit_test.hpp>
#include <cmath>

#include "analytical/impact_zone.h"
#include "analytical/load_shape.h"
#include "analytical/stream_catch.h"

using namespace chutelab;
using namespace chutelab::analytical;
namespace tt = boost::test_tools;

namespace {
constexpr double kPi = 3.14159265358979323846;

// A flat belt delivering horizontally onto a vertical plate: every layer leaves the pulley at its
// top with V_b (high-speed, K = V_b^2 / (g R_b) = 12.5), so the layer at height e crosses the plate
// face x = d at y(e) = R_b + e - g d^2 / (2 V_b^2), the same parabola shifted by e.
Station flat_station() {
  Station st;
  st.condition = "closed-form";
  st.belt.pulley_diameter = 0.25;
  st.belt.belt_thickness = 0.005;
  st.belt.belt_width = 0.3;
  st.belt.loaded_width = 0.2;
  st.plate.width = 0.4;
  st.plate.height = 0.5;
  st.plate.angle = 0.0;
  st.material.particle_diameter = 4.55e-3;
  st.material.solid_density = 925.0;
  st.material.bulk_density = 540.0;
  st.material.friction_plate = 0.27;
  st.belt_speed = 4.0;
  st.mass_flow = 35.0 / 3.6;
  st.plate_distance = 0.45;
  st.stream_thickness = 0.04;
  return st;
}

double crossing_y(const Station& st, double e) {
  const double d = st.plate_distance, v = st.belt_speed;
  return st.belt.belt_radius() + e - st.gravity * d * d / (2.0 * v * v);
}

// The cap of rise s of a circle of radius r (the segment above a chord s below the crest).
double cap(double r, double s) { return r * r * std::acos((r - s) / r) - (r - s) * std::sqrt(2.0 * r * s - s * s); }
}  // namespace

BOOST_AUTO_TEST_SUITE(stream_catch_closed_form)

BOOST_AUTO_TEST_CASE(a_stream_whose_top_30_percent_of_thickness_passes_over_the_edge) {
  // The plate's top edge where the layer at 0.7 h_b crosses: the layers above it (a cap of the load's
  // circular segment, rise 0.3 h_b) pass over. The load is a segment of chord W = 200 mm, rise
  // h_b = 40 mm, on a circle of radius r = (W^2/4 + h_b^2) / (2 h_b).
  Station st = flat_station();
  const double h = *st.stream_thickness, w = st.belt.loaded_width, q = 0.3;
  st.plate_top = crossing_y(st, (1.0 - q) * h);
  const auto a = analyse_transfer(st);
  BOOST_REQUIRE(a.line(Streamline::lower).release.high_speed);
  BOOST_REQUIRE(a.line(Streamline::upper).release.high_speed);
  const double r = (0.25 * w * w + h * h) / (2.0 * h);
  const double over = cap(r, q * h) / cap(r, h);
  const StreamCatch c = stream_catch(a);
  // Tolerances: the layers' crossings are linear in e here, so the interpolation between the flown
  // layers is exact; what is left is rounding in the hits (solved quadratics) and in acos.
  BOOST_TEST(c.over_top == over, tt::tolerance(1e-9));
  BOOST_TEST(c.past_foot == 0.0);
  BOOST_TEST(c.caught == 1.0 - over, tt::tolerance(1e-9));
  BOOST_REQUIRE(c.top_edge_layer.has_value());
  BOOST_TEST(*c.top_edge_layer == (1.0 - q) * h, tt::tolerance(1e-9));
  // Korzen Eq 5 on a vertical plate without drag: V_pn is the horizontal speed, V_b, so the whole
  // stream's R_n = m_s V_b and the caught part's is (1 - over) m_s V_b; Eq 7 (no stationary flow
  // at this shallow angle) R_s = mu_pw R_n.
  BOOST_TEST(a.korzen.normal_force == st.mass_flow * st.belt_speed, tt::tolerance(1e-12));
  BOOST_TEST(c.normal_force == (1.0 - over) * st.mass_flow * st.belt_speed, tt::tolerance(1e-9));
  BOOST_TEST(c.shear_force == (1.0 - over) * a.korzen.shear_force, tt::tolerance(1e-9));
  // The loaded band runs from the top edge to the lower limit's crossing, (1 - q) h_b, as wide as
  // the load: the mean pressure is the caught force over it, not the whole stream's.
  const ImpactZone z = impact_zone(a);
  BOOST_TEST(z.top_clipped);
  BOOST_TEST(z.length() == (1.0 - q) * h, tt::tolerance(1e-9));
  BOOST_TEST(z.width == w);
  BOOST_TEST(z.mean_pressure == (1.0 - over) * st.mass_flow * st.belt_speed / ((1.0 - q) * h * w),
             tt::tolerance(1e-9));
  BOOST_TEST_MESSAGE("q = 0.3 of h_b over the edge: " << 100.0 * over << " % of the mass; R_n " << c.normal_force
                                                      << " N of " << a.korzen.normal_force << " N; mean pressure "
                                                      << z.mean_pressure << " Pa");
}

BOOST_AUTO_TEST_CASE(the_mean_pressure_is_continuous_as_the_edge_crosses_the_stream) {
  // The issue this answers: the whole stream's force on the part of the band left on the plate
  // made the mean pressure jump as the upper limit crossed the top edge. The caught force shrinks
  // with the band: from the edge at the upper limit down to the Korzen centroid, the pressure moves
  // by no more than its closed form says, and the first step over the edge changes nothing abruptly.
  Station st = flat_station();
  const double h = *st.stream_thickness, w = st.belt.loaded_width;
  const double r = (0.25 * w * w + h * h) / (2.0 * h);
  double last = -1.0;
  for (int i = 0; i <= 20; ++i) {
    const double q = 0.02 * i;  // 0 to 40 % of h_b over the edge (the centroid at 50 % stays on)
    st.plate_top = crossing_y(st, (1.0 - q) * h) + (i == 0 ? 1e-6 : 0.0);
    const ImpactZone z = impact_zone(analyse_transfer(st));
    const double over = i == 0 ? 0.0 : cap(r, q * h) / cap(r, h);
    const double expected = (1.0 - over) * st.mass_flow * st.belt_speed / ((1.0 - q) * h * w);
    BOOST_TEST_CONTEXT("q = " << q) {
      BOOST_TEST(z.caught.over_top == over, tt::tolerance(1e-9));
      BOOST_TEST(z.mean_pressure == expected, tt::tolerance(1e-6));
      // Little mass sits near a segment's crest, so the band shortens a little faster than the caught
      // force falls: the pressure creeps up by a few per cent per step of 2 % of h_b, never the 80 %
      // jump of the whole force on a cut band.
      if (last > 0.0) BOOST_TEST(std::abs(z.mean_pressure / last - 1.0) < 0.05);
    }
    last = z.mean_pressure;
  }
}

BOOST_AUTO_TEST_CASE(a_stream_wholly_on_the_plate_is_caught_whole) {
  Station st = flat_station();
  st.plate_top = crossing_y(st, *st.stream_thickness) + 0.05;
  const auto a = analyse_transfer(st);
  const StreamCatch c = stream_catch(a);
  BOOST_TEST(c.whole());
  BOOST_TEST(c.caught == 1.0);
  BOOST_TEST(!c.top_edge_layer.has_value());
  BOOST_TEST(c.normal_force == a.korzen.normal_force);
  BOOST_TEST(impact_zone(a).mean_pressure * impact_zone(a).area == a.korzen.normal_force, tt::tolerance(1e-12));
}

BOOST_AUTO_TEST_CASE(a_short_plate_lets_the_lower_layers_fall_past_its_foot) {
  // The foot where the layer at 0.25 h_b crosses: the layers below it fall past. The segment's part
  // below 0.25 h_b is the whole less the cap of rise 0.75 h_b.
  Station st = flat_station();
  const double h = *st.stream_thickness, w = st.belt.loaded_width;
  st.plate_top = crossing_y(st, h) + 0.01;
  st.plate.height = st.plate_top - crossing_y(st, 0.25 * h);
  const StreamCatch c = stream_catch(analyse_transfer(st));
  const double r = (0.25 * w * w + h * h) / (2.0 * h);
  BOOST_TEST(c.over_top == 0.0);
  BOOST_TEST(c.past_foot == 1.0 - cap(r, 0.75 * h) / cap(r, h), tt::tolerance(1e-9));
  BOOST_REQUIRE(c.foot_edge_layer.has_value());
  BOOST_TEST(*c.foot_edge_layer == 0.25 * h, tt::tolerance(1e-9));
}

BOOST_AUTO_TEST_CASE(troughed_load_area_below_a_height_integrates_its_width) {
  // A 3-roll trough: the width at height y is l + 2 y / tan(lambda) on the rolls and the surcharge
  // arc's chord above them; the area below e by the midpoint rule on 200 000 strips (error ~1e-10
  // of the area; the arc's square-root end is the worst, hence 1e-6).
  Belt belt;
  belt.pulley_diameter = 0.5;
  belt.belt_width = 0.8;
  belt.loaded_width = 0.7;
  belt.trough.idler_angle = 35.0 * kPi / 180.0;
  belt.trough.centre_roll = 0.3;
  belt.trough.surcharge_angle = 20.0 * kPi / 180.0;
  const LoadShape load = load_shape_for_thickness(belt, 0.12);
  const double l = belt.trough.centre_roll, lambda = belt.trough.idler_angle;
  const double wing = 0.5 * (load.contact_width - l), depth = wing * std::sin(lambda);
  const double top = l + 2.0 * wing * std::cos(lambda);
  const double rise = load.height - depth, r = (0.25 * top * top + rise * rise) / (2.0 * rise);
  auto width = [&](double y) {
    if (y <= depth) return l + 2.0 * y / std::tan(lambda);
    const double from_centre = y - (load.height - r);
    return 2.0 * std::sqrt(std::max(0.0, r * r - from_centre * from_centre));
  };
  for (double f : {0.1, 0.3, 0.5, 0.8, 1.0}) {
    const double e = f * load.height;
    const int n = 200000;
    double area = 0.0;
    for (int i = 0; i < n; ++i) area += width((i + 0.5) * e / n) * e / n;
    BOOST_TEST_CONTEXT("e = " << f << " h_b") { BOOST_TEST(load_area_below(belt, load, e) == area, tt::tolerance(1e-6)); }
  }
  BOOST_TEST(load_area_below(belt, load, load.height) == load.area, tt::tolerance(1e-12));
  BOOST_TEST(load_area_below(belt, load, 0.0) == 0.0);
}

BOOST_AUTO_TEST_SUITE_END()
