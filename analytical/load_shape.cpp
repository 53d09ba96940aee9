#include "analytical/load_shape.h"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>

#include "core/input_error.h"

namespace chutelab::analytical {
namespace {

// Segment of a circle of radius r cut by a chord subtending 2*half_angle at the centre.
struct Segment {
  double area;
  double centroid_above_chord;
  double rise;
};

Segment circular_segment(double r, double half_angle) {
  const double theta = 2.0 * half_angle;
  const double area = 0.5 * r * r * (theta - std::sin(theta));
  const double rise = r * (1.0 - std::cos(half_angle));
  if (area <= 0.0) return {0.0, 0.0, 0.0};
  // Centroid of a circular segment from the circle centre: 4 r sin^3(theta/2) / (3 (theta - sin)).
  const double from_centre =
      4.0 * r * std::pow(std::sin(half_angle), 3) / (3.0 * (theta - std::sin(theta)));
  return {area, from_centre - r * std::cos(half_angle), rise};
}

// Segment on a chord with a given edge (surcharge) angle: the arc meets the chord at that angle.
Segment surcharge_segment(double chord, double surcharge_angle) {
  if (chord <= 0.0 || surcharge_angle <= 0.0) return {0.0, 0.0, 0.0};
  const double r = chord / (2.0 * std::sin(surcharge_angle));
  return circular_segment(r, surcharge_angle);
}

// Monotone bisection: the load-shape functions grow with their argument.
template <class F>
double solve_increasing(F f, double target, double lo, double hi) {
  for (int i = 0; i < 200 && hi - lo > 1e-14 * (1.0 + hi); ++i) {
    const double mid = 0.5 * (lo + hi);
    (f(mid) < target ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

// The cap of a circle of radius r above a chord at depth s below its crest (0 <= s <= r): the
// segment of rise s, r^2 acos((r - s)/r) - (r - s) sqrt(2 r s - s^2).
double cap_area(double r, double s) {
  if (s <= 0.0) return 0.0;
  const double c = r - s;
  return r * r * std::acos(std::clamp(c / r, -1.0, 1.0)) - c * std::sqrt(std::max(0.0, 2.0 * r * s - s * s));
}

// Radius of the circle through a chord of width `chord` with a rise `rise`.
double radius_of(double chord, double rise) { return (0.25 * chord * chord + rise * rise) / (2.0 * rise); }

}  // namespace

LoadShape flat_segment(double chord, double height) {
  if (!(chord > 0.0) || !(height > 0.0) || height > 0.5 * chord * (1.0 + 1e-12))
    throw InputError("", 0, "stream_thickness_mm",
                     fmt::format("a flat-belt load of height {:.1f} mm cannot sit on a chord of "
                                 "{:.1f} mm (height must be positive and at most half the chord)",
                                 height * 1e3, chord * 1e3));
  const double r = (0.25 * chord * chord + height * height) / (2.0 * height);
  // atan2 rather than asin(chord / 2r): asin loses half the digits as the segment nears a half disc.
  const double half_angle = std::atan2(0.5 * chord, r - height);
  const Segment s = circular_segment(r, half_angle);
  return {s.area, height, s.centroid_above_chord, chord};
}

LoadShape troughed_load(const Trough& t, double contact_width) {
  const double l = t.centre_roll;
  if (contact_width <= l || t.idler_angle <= 0.0) {
    const Segment s = surcharge_segment(contact_width, t.surcharge_angle);
    return {s.area, s.rise, s.centroid_above_chord, contact_width};
  }
  const double wing = 0.5 * (contact_width - l);
  const double depth = wing * std::sin(t.idler_angle);
  const double top = l + 2.0 * wing * std::cos(t.idler_angle);
  const double trap_area = 0.5 * (l + top) * depth;
  // Trapezoid centroid above its base: h (b + 2 a) / (3 (a + b)), a = top width, b = base width.
  const double trap_centroid = depth * (l + 2.0 * top) / (3.0 * (l + top));
  const Segment s = surcharge_segment(top, t.surcharge_angle);
  const double area = trap_area + s.area;
  const double centroid = (trap_area * trap_centroid + s.area * (depth + s.centroid_above_chord)) / area;
  return {area, depth + s.rise, centroid, contact_width};
}

LoadShape largest_load(const Belt& belt) {
  if (!belt.trough.troughed()) return flat_segment(belt.loaded_width, 0.5 * belt.loaded_width);
  return troughed_load(belt.trough, belt.loaded_width);
}

LoadShape load_shape_for_thickness(const Belt& belt, double thickness) {
  if (!belt.trough.troughed()) return flat_segment(belt.loaded_width, thickness);
  const auto height_of = [&](double w) { return troughed_load(belt.trough, w).height; };
  if (thickness > height_of(belt.loaded_width) * (1.0 + 1e-12))
    throw InputError("", 0, "stream_thickness_mm",
                     fmt::format("a load {:.1f} mm deep does not fit a troughed belt whose "
                                 "loaded width {:.0f} mm holds at most {:.1f} mm",
                                 thickness * 1e3, belt.loaded_width * 1e3,
                                 height_of(belt.loaded_width) * 1e3));
  return troughed_load(belt.trough, solve_increasing(height_of, thickness, 0.0, belt.loaded_width));
}

LoadShape load_shape_for_flow(const Belt& belt, double mass_flow, double bulk_density,
                              double belt_speed) {
  if (!(mass_flow > 0.0) || !(bulk_density > 0.0) || !(belt_speed > 0.0))
    throw InputError("", 0, "mass_flow_tph",
                     "continuity needs a positive mass flow, bulk density and belt speed");
  const double area = mass_flow / (bulk_density * belt_speed);
  if (!belt.trough.troughed()) {
    const double w = belt.loaded_width;
    const double max_area = largest_load(belt).area;
    if (area > max_area)
      throw InputError("", 0, "mass_flow_tph",
                       fmt::format("{:.1f} t/h at {:.2f} m/s needs a {:.0f} mm^2 cross-section; a flat "
                                   "belt loaded {:.0f} mm wide holds at most {:.0f} mm^2",
                                   mass_flow * 3.6, belt_speed, area * 1e6, w * 1e3, max_area * 1e6));
    const double h = solve_increasing([&](double hh) { return flat_segment(w, hh).area; }, area,
                                      1e-12, 0.5 * w);
    return flat_segment(w, h);
  }
  const auto area_of = [&](double w) { return troughed_load(belt.trough, w).area; };
  if (area > largest_load(belt).area)
    throw InputError("", 0, "mass_flow_tph",
                     fmt::format("{:.1f} t/h at {:.2f} m/s overfills the troughed belt "
                                 "({:.0f} mm^2 needed, {:.0f} mm^2 available)",
                                 mass_flow * 3.6, belt_speed, area * 1e6,
                                 largest_load(belt).area * 1e6));
  return troughed_load(belt.trough, solve_increasing(area_of, area, 0.0, belt.loaded_width));
}

double load_area_below(const Belt& belt, const LoadShape& load, double e) {
  e = std::clamp(e, 0.0, load.height);
  // A segment on its chord (the flat belt, or a load on the centre roll alone): the whole less the
  // cap above e. A troughed load: the trapezoid on the rolls, its wings rising at the idler angle
  // (width l + 2 y / tan(lambda) at height y), then the surcharge segment on its top width.
  auto segment_below = [](double chord, double rise, double area, double y) {
    if (rise <= 0.0) return 0.0;
    return area - cap_area(radius_of(chord, rise), rise - y);
  };
  const Trough& t = belt.trough;
  if (!belt.trough.troughed() || load.contact_width <= t.centre_roll || t.idler_angle <= 0.0)
    return segment_below(load.contact_width, load.height, load.area, e);
  const double l = t.centre_roll;
  const double wing = 0.5 * (load.contact_width - l);
  const double depth = wing * std::sin(t.idler_angle);
  const double top = l + 2.0 * wing * std::cos(t.idler_angle);
  const double spread = 1.0 / std::tan(t.idler_angle);
  const double y = std::min(e, depth);
  const double trapezoid = l * y + spread * y * y;
  if (e <= depth) return trapezoid;
  const double segment = load.area - 0.5 * (l + top) * depth;
  return trapezoid + segment_below(top, load.height - depth, segment, e - depth);
}

}  // namespace chutelab::analytical
