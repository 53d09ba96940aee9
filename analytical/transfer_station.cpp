#include "analytical/transfer_station.h"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <stdexcept>

#include "core/input_error.h"

namespace chutelab::analytical {

std::string_view name(Streamline s) {
  switch (s) {
    case Streamline::lower: return "lower";
    case Streamline::upper: return "upper";
    case Streamline::cema_centroid: return "cema_centroid";
    case Streamline::korzen_centroid: return "korzen_centroid";
  }
  throw std::logic_error("unknown streamline");
}

double TransferAnalysis::drop_height() const {
  const auto& l = line(Streamline::cema_centroid);
  return l.release.position.y() - l.hit->point.position.y();
}

double TransferAnalysis::flight_time() const { return line(Streamline::cema_centroid).hit->point.t; }

namespace {

void check_station(const Station& s) {
  auto bad = [](std::string_view field, const std::string& problem) {
    throw InputError("", 0, std::string(field), problem);
  };
  if (!(s.belt_speed > 0.0) || !std::isfinite(s.belt_speed))
    bad("belt_speed_mps", fmt::format("must be a positive number, got {}", s.belt_speed));
  if (!(s.mass_flow > 0.0) || !std::isfinite(s.mass_flow))
    bad("mass_flow_tph", fmt::format("must be a positive number, got {}", s.mass_flow * 3.6));
  if (!std::isfinite(s.plate_distance) || !std::isfinite(s.plate_top))
    bad("plate_distance_mm", "plate position must be finite");
  if (s.stream_thickness && !(*s.stream_thickness > 0.0))
    bad("stream_thickness_mm", "must be positive when given");
}

// The largest plate distance at which both centre lines still meet the plate above its foot, with
// the plate's top, angle and height kept; nullopt when none does. Only the error path uses it, to
// tell the user how far the stream reaches.
std::optional<double> farthest_plate_distance(const TransferAnalysis& a, double plate_top) {
  auto reaches = [&](double z) {
    PlateLine p = a.plate;
    p.top = {z, plate_top};
    for (Streamline c : {Streamline::cema_centroid, Streamline::korzen_centroid}) {
      const auto& l = a.line(c);
      if (p.signed_distance(l.release.position) >= 0.0) return false;
      const auto h = l.trajectory.hit(p);
      if (!h || h->along > p.height) return false;
    }
    return true;
  };
  double near = 0.0, far = a.plate.top.x();
  for (Streamline c : {Streamline::cema_centroid, Streamline::korzen_centroid})
    near = std::max(near, a.line(c).release.position.x());
  near += 1e-3;
  if (!(near < far) || !reaches(near)) return std::nullopt;
  // Past its apex the stream only falls, so where it crosses the plate line sinks as the plate
  // moves away: the edge between reaching and missing is one point, found by bisection.
  for (int i = 0; i < 40 && far - near > 1e-4; ++i) {
    const double mid = 0.5 * (near + far);
    (reaches(mid) ? near : far) = mid;
  }
  return near;
}

}  // namespace

std::optional<double> farthest_plate_distance(const TransferAnalysis& a) {
  return farthest_plate_distance(a, a.station.plate_top);
}

TransferAnalysis analyse_transfer(const Station& recorded, const EffectList& effects, TransferMemo* memo) {
  const Station st = as_really_was(recorded, effects);
  check_station(st);
  TransferAnalysis a;
  a.station = st;
  a.operating = {st.belt_speed, st.mass_flow};
  for (const auto& e : effects) e->adjust_operating_point(a.operating);

  // The stream's thickness is a property of the belt load, so it follows from the mass flow that
  // is really on the belt, at belt speed (the layer rides the belt before the pulley).
  a.thickness_from_continuity = !st.stream_thickness;
  const bool known = memo && memo->operating && memo->operating->belt_speed == a.operating.belt_speed &&
                     memo->operating->mass_flow == a.operating.mass_flow &&
                     memo->belt.belt_width == st.belt.belt_width && memo->belt.loaded_width == st.belt.loaded_width &&
                     memo->belt.trough.idler_angle == st.belt.trough.idler_angle &&
                     memo->belt.trough.centre_roll == st.belt.trough.centre_roll &&
                     memo->belt.trough.surcharge_angle == st.belt.trough.surcharge_angle &&
                     memo->bulk_density == st.material.bulk_density && memo->stream_thickness == st.stream_thickness;
  if (known) {
    a.load = memo->load;
  } else {
    a.load = st.stream_thickness ? load_shape_for_thickness(st.belt, *st.stream_thickness)
                                 : load_shape_for_flow(st.belt, a.operating.mass_flow, st.material.bulk_density,
                                                       a.operating.belt_speed);
    if (memo) {
      memo->operating = a.operating;
      memo->load = a.load;
      memo->belt = st.belt;
      memo->bulk_density = st.material.bulk_density;
      memo->stream_thickness = st.stream_thickness;
    }
  }

  a.plate.top = {st.plate_distance, st.plate_top};
  a.plate.angle = st.plate.angle;
  a.plate.height = st.plate.height;

  {
    // The plate must stand clear of the belt on the pulley: a face that cuts the pulley circle
    // (radius R_b) is an impossible rig, however the stream might fly.
    const Eigen::Vector2d d = a.plate.down();
    const double along = std::clamp(-a.plate.top.dot(d), 0.0, a.plate.height);
    const double clearance = (a.plate.top + along * d).norm();
    if (clearance <= st.belt.belt_radius())
      throw InputError("", 0, "plate_distance_mm",
                       fmt::format("the plate (face at x = {:.0f} mm) cuts into the head pulley and "
                                   "belt (radius {:.0f} mm): it is behind the pulley's front",
                                   st.plate_distance * 1e3, st.belt.belt_radius() * 1e3));
  }

  const FlightContext ctx{st.material.particle_diameter, st.material.solid_density};
  bool has_force = false;
  for (const auto& e : effects) has_force = has_force || e->has_flight_force();
  // A force in flight (air drag) acts per unit mass of one particle: without its size and density
  // there is no acceleration to give, and a setup for the plain chain may leave them out.
  if (has_force && !(std::isfinite(ctx.particle_diameter) && std::isfinite(ctx.solid_density)))
    throw InputError("setup.toml", 0,
                     std::isfinite(ctx.particle_diameter) ? "material.solid_density_kgm3" : "material.particle_diameter_mm",
                     "a force on the particles in flight (air drag) needs their size and density: give "
                     "material.particle_diameter_mm and material.solid_density_kgm3 in setup.toml");
  AccelerationFn extra;
  if (has_force)
    // By value: the trajectory integrates lazily and may outlive the caller's list.
    extra = [effects, ctx](const Eigen::Vector2d& v) {
      Eigen::Vector2d acc = Eigen::Vector2d::Zero();
      for (const auto& e : effects) acc += e->flight_acceleration(v, ctx);
      return acc;
    };

  const double rb = st.belt.belt_radius();
  const std::array<double, 4> heights = {0.0, a.load.height, a.load.centroid_height,
                                         0.5 * a.load.height};
  for (Streamline which : kAllStreamlines) {
    auto& f = a.streamlines[static_cast<std::size_t>(which)];
    f.which = which;
    f.height_above_belt = heights[static_cast<std::size_t>(which)];
    DischargeInput din{rb + f.height_above_belt, a.operating.belt_speed, st.belt.incline,
                       st.gravity, 0.0,
                       st.material.bulk_density * a.load.area / a.load.contact_width};
    for (const auto& e : effects) e->adjust_discharge(din, st);
    f.release = booth_release(din);
    if (a.plate.signed_distance(f.release.position) >= 0.0)
      throw InputError("", 0, "plate_distance_mm",
                       fmt::format("the plate face (x = {:.0f} mm at its top) is behind the point "
                                   "where the stream leaves the pulley (x = {:.0f} mm)",
                                   st.plate_distance * 1e3, f.release.position.x() * 1e3));
    Eigen::Vector2d v0 = f.release.velocity;
    if (which == Streamline::upper || which == Streamline::lower)
      for (const auto& e : effects)
        e->adjust_release(which == Streamline::upper ? Boundary::upper : Boundary::lower, v0);
    f.trajectory = Trajectory(FlightPoint{0.0, f.release.position, v0}, st.gravity, extra);
    f.hit = f.trajectory.hit(a.plate);
  }

  for (Streamline centre : {Streamline::cema_centroid, Streamline::korzen_centroid}) {
    const auto& hit = a.line(centre).hit;
    if (hit && hit->on_plate) continue;
    // Name the field whose change puts the plate in the stream: passing above the top edge asks
    // for a higher plate; falling past the foot (or never arriving) for a nearer one, which is how
    // a too-distant plate shows, unless no distance would do because the plate hangs above the
    // stream.
    if (hit && hit->along < 0.0)
      throw InputError("", 0, "plate_top_mm",
                       fmt::format("the stream misses the plate: its centre line ({}) passes the plate "
                                   "line at y = {:.0f} mm, above the plate's top edge (y = {:.0f} mm); "
                                   "raise plate_top_mm or move the plate farther (plate_distance_mm)",
                                   name(centre), hit->point.position.y() * 1e3, st.plate_top * 1e3));
    const std::string where =
        hit ? fmt::format("passes the plate line at y = {:.0f} mm, below the plate's foot "
                          "({:.0f} mm under its top at y = {:.0f} mm)",
                          hit->point.position.y() * 1e3, st.plate.height * 1e3, st.plate_top * 1e3)
            : std::string("never reaches the plate line");
    const auto reach = farthest_plate_distance(a, st.plate_top);
    if (!reach)
      throw InputError("", 0, "plate_top_mm",
                       fmt::format("the stream misses the plate: its centre line ({}) {}; no plate "
                                   "distance reaches the stream with the plate this high: lower "
                                   "plate_top_mm or lengthen plate_height_mm",
                                   name(centre), where));
    throw InputError("", 0, "plate_distance_mm",
                     fmt::format("the stream misses the plate: its centre line ({}) {}; the plate is "
                                 "too far: bring it within x = {:.0f} mm (plate_distance_mm), or lower "
                                 "plate_top_mm or lengthen plate_height_mm",
                                 name(centre), where, std::floor(*reach * 1e3)));
  }

  a.plate_interaction = {st.material.friction_plate, 0.0};
  for (const auto& e : effects) e->adjust_plate(a.plate_interaction);
  const auto& hit = *a.line(Streamline::korzen_centroid).hit;
  a.korzen = korzen_impact({a.operating.mass_flow, st.material.bulk_density, hit.speed, hit.alpha,
                            st.plate.angle, a.plate_interaction.friction,
                            a.plate_interaction.rebound});
  return a;
}

}  // namespace chutelab::analytical
