#include "api/estimate_output.h"

#include <cmath>
#include <fmt/format.h>

#include "analytical/impact_zone.h"
#include "analytical/stream_catch.h"
#include "analytical/streamline_path.h"
#include "core/csv_field.h"
#include "core/message.h"
#include "core/units.h"

namespace chutelab::api {
namespace {
using analytical::Streamline;
}  // namespace

std::string json_string(const std::string& s) {
  std::string out = "\"";
  for (char c : s) {
    switch (c) {
      case '"': out += "\\\""; break;
      case '\\': out += "\\\\"; break;
      case '\n': out += "\\n"; break;
      default:
        if (static_cast<unsigned char>(c) < 0x20) out += fmt::format("\\u{:04x}", c);
        else out += c;
    }
  }
  return out + "\"";
}

// The shortest decimal that reads back as the same double (as CSV cells, core/csv_field.h).
std::string json_number(double v) { return std::isfinite(v) ? fmt::format("{}", v) : "null"; }

namespace {

std::string streamline_label(Streamline s) {
  switch (s) {
    case Streamline::lower: return "lower limit (e = 0)";
    case Streamline::upper: return "upper limit (e = h_b)";
    case Streamline::cema_centroid: return "CEMA centroid (e = a1)";
    case Streamline::korzen_centroid: return "Korzen centroid (e = h_b/2)";
  }
  return "";
}

}  // namespace

std::string stream_miss_note(const analytical::StreamCatch& c) {
  if (c.whole()) return "";
  std::string where;
  if (c.over_top > 0.0) where = fmt::format("{:.3g} % of the stream passes over the plate's top edge", 100.0 * c.over_top);
  if (c.past_foot > 0.0)
    where += fmt::format("{}{:.3g} % falls past its foot", where.empty() ? "" : ", ", 100.0 * c.past_foot);
  // Korzen's forces are linear in the mass flow: the whole stream's are the caught part's over its share.
  return fmt::format("{}: the plate takes R_n = {:.3g} N and R_s = {:.3g} N of the whole stream's {:.3g} N and "
                     "{:.3g} N (Korzen, the caught part taken to strike at the centroid's speed and angle); the "
                     "mean pressure is of that part",
                     where, c.normal_force, c.shear_force, c.normal_force / c.caught, c.shear_force / c.caught);
}

std::vector<std::pair<std::string, double>> estimate_scalars(const analytical::TransferAnalysis& a) {
  const auto& k = a.korzen;
  const auto& kc = *a.line(Streamline::korzen_centroid).hit;
  std::vector<std::pair<std::string, double>> v = {
      {"belt_speed_mps", a.station.belt_speed},
      {"mass_flow_tph", a.station.mass_flow / units::tph},
      {"plate_distance_mm", a.station.plate_distance * 1e3},
      {"plate_top_mm", a.station.plate_top * 1e3},
      {"plate_angle_deg", a.station.plate.angle * units::deg_per_rad},
      {"stream_thickness_mm", a.load.height * 1e3},
      {"cema_centroid_mm", a.load.centroid_height * 1e3},
      {"load_area_mm2", a.load.area * 1e6},
      {"discharge_ratio_K", a.line(Streamline::cema_centroid).release.ratio},
      {"release_angle_deg", a.line(Streamline::cema_centroid).release.theta * units::deg_per_rad},
      {"impact_angle_deg", kc.alpha * units::deg_per_rad},
      {"impact_velocity_mps", kc.speed},
      {"normal_impact_velocity_mps", k.normal_speed},
      {"tangential_impact_velocity_mps", k.tangential_speed},
      {"normal_force_N", k.normal_force},
      {"shear_force_N", k.shear_force},
      {"resultant_force_N", k.resultant_force},
  };
  if (k.exit_speed) v.emplace_back("exit_velocity_mps", *k.exit_speed);
  const auto z = analytical::impact_zone(a);
  v.emplace_back("impact_zone_top_mm", z.top_y * 1e3);
  v.emplace_back("impact_zone_bottom_mm", z.bottom_y * 1e3);
  v.emplace_back("impact_zone_centroid_mm", z.centroid_y * 1e3);
  v.emplace_back("impact_zone_width_mm", z.width * 1e3);
  v.emplace_back("impact_zone_area_mm2", z.area * 1e6);
  v.emplace_back("mean_pressure_Pa", z.mean_pressure);
  v.emplace_back("mean_shear_stress_Pa", z.mean_shear_stress);
  // The part of the stream the plate takes (analytical/stream_catch.h); the mean stresses are of it.
  v.emplace_back("over_top_fraction", z.caught.over_top);
  v.emplace_back("past_foot_fraction", z.caught.past_foot);
  v.emplace_back("caught_normal_force_N", z.caught.normal_force);
  v.emplace_back("caught_shear_force_N", z.caught.shear_force);
  for (Streamline s : analytical::kAllStreamlines) {
    const auto& l = a.line(s);
    if (!l.hit) continue;
    const std::string n(name(s));
    v.emplace_back(n + "_impact_y_mm", l.hit->point.position.y() * 1e3);
    v.emplace_back(n + "_impact_velocity_mps", l.hit->speed);
    v.emplace_back(n + "_impact_angle_deg", l.hit->alpha * units::deg_per_rad);
    v.emplace_back(n + "_flight_time_s", l.hit->point.t);
  }
  return v;
}

namespace {

std::string fmt_opt(const std::optional<double>& v, double scale, const char* spec) {
  return v ? fmt::format(fmt::runtime(spec), *v * scale) : std::string("-");
}

}  // namespace

std::string estimate_table(const analytical::TransferAnalysis& a, const ModelValues& models,
                           const std::vector<effects::EffectSetting>& fx) {
  const auto& st = a.station;
  const auto& k = a.korzen;
  const auto& rel = a.line(Streamline::cema_centroid).release;
  std::string o;
  o += fmt::format("chutelab estimate: condition {} (analytical models)\n\n", one_line(st.condition, 80));
  o += fmt::format("  belt speed {:.2f} m/s, mass flow {:.1f} t/h, plate face x = {:.0f} mm, top y = "
                   "{:.0f} mm, plate angle {:.1f} deg, belt incline {:.1f} deg\n",
                   st.belt_speed, st.mass_flow / units::tph, st.plate_distance * 1e3,
                   st.plate_top * 1e3, st.plate.angle * units::deg_per_rad, st.belt.incline * units::deg_per_rad);
  for (const auto& s : fx)
    if (s.value) o += fmt::format("  effect {} = {} {}\n", s.info->name, *s.value, s.info->unit);
  o += fmt::format("  load: h_b = {:.1f} mm ({}), CEMA centroid a1 = {:.1f} mm, area {:.0f} mm^2, {} belt\n",
                   a.load.height * 1e3,
                   a.thickness_from_continuity ? "from continuity" : "given",
                   a.load.centroid_height * 1e3, a.load.area * 1e6,
                   st.belt.trough.troughed() ? "troughed" : "flat");
  o += fmt::format("  discharge: {} (K = V^2/(g R) = {:.2f} on the CEMA centroid), release {:.1f} deg "
                   "from the upward vertical\n\n",
                   rel.high_speed ? "high-speed, at the tangent point" : "low-speed (Booth), on the pulley",
                   rel.ratio, rel.theta * units::deg_per_rad);
  o += fmt::format("  {:<28} {:>9} {:>10} {:>10} {:>11} {:>8} {:>9} {:>8}\n", "streamline", "e_mm",
                   "release_x", "release_y", "impact_y_mm", "V_p_mps", "alpha_deg", "flight_s");
  for (Streamline s : analytical::kAllStreamlines) {
    const auto& l = a.line(s);
    o += fmt::format("  {:<28} {:>9.1f} {:>10.1f} {:>10.1f} ", streamline_label(s),
                     l.height_above_belt * 1e3, l.release.position.x() * 1e3,
                     l.release.position.y() * 1e3);
    if (l.hit)
      o += fmt::format("{:>11.1f} {:>8.3f} {:>9.2f} {:>8.4f}{}\n", l.hit->point.position.y() * 1e3,
                       l.hit->speed, l.hit->alpha * units::deg_per_rad, l.hit->point.t,
                       l.hit->on_plate ? "" : "  (off the plate)");
    else
      o += "  never reaches the plate line\n";
  }
  const double incidence = a.line(Streamline::korzen_centroid).hit->alpha + st.plate.angle;
  o += fmt::format("\n  Korzen: alpha_p + beta = {:.2f} deg {} atan(mu_pw) = {:.2f} deg: {}\n",
                   incidence * units::deg_per_rad, k.stationary_flow ? ">" : "<=",
                   std::atan(a.plate_interaction.friction) * units::deg_per_rad,
                   k.stationary_flow ? "stationary (build-up) flow (Eq 3)" : "no stationary flow (Eq 3)");
  o += fmt::format("  V_pn = {:.3f} m/s, V_pt = {:.3f} m/s, V_a = {}\n", k.normal_speed,
                   k.tangential_speed,
                   k.exit_speed ? fmt::format("{:.3f} m/s (Eq 4, {} iterations)", *k.exit_speed, k.iterations)
                                : std::string("none (Eq 4 has a negative root)"));
  o += fmt::format("  R_n = {:.2f} N (Eq 5), R_s = {:.2f} N ({}), R = {:.2f} N\n", k.normal_force,
                   k.shear_force, name(k.shear_equation), k.resultant_force);
  const auto z = analytical::impact_zone(a);
  o += fmt::format("  impact zone: y = {:.1f} to {:.1f} mm on the face ({:.0f} mm x {:.0f} mm), "
                   "mean pressure {:.0f} Pa, mean shear {:.0f} Pa\n",
                   z.top_y * 1e3, z.bottom_y * 1e3, z.length() * 1e3, z.width * 1e3, z.mean_pressure,
                   z.mean_shear_stress);
  if (const std::string miss = stream_miss_note(z.caught); !miss.empty()) o += "  " + miss + "\n";
  o += "\n";
  o += fmt::format("  {:<12}", "model");
  for (Quantity q : kAllQuantities) o += fmt::format(" {:>20}", name(q));
  o += "\n";
  for (const auto& [m, vals] : models) {
    o += fmt::format("  {:<12}", m);
    for (Quantity q : kAllQuantities)
      o += fmt::format(" {:>20}", fmt_opt(vals[q], info(q).to_boundary, "{:.3f}"));
    o += "\n";
  }
  return o;
}

std::string estimate_csv(const analytical::TransferAnalysis& a, const ModelValues& models) {
  std::string o = "condition,model,quantity,value\n";
  for (const auto& [n, v] : estimate_scalars(a))
    o += fmt::format("{},analysis,{},{}\n", csv_field(a.station.condition), n, csv_number(v));
  o += fmt::format("{},analysis,stationary_flow,{}\n", csv_field(a.station.condition),
                   a.korzen.stationary_flow ? 1 : 0);
  o += fmt::format("{},analysis,stream_thickness_from_continuity,{}\n", csv_field(a.station.condition),
                   a.thickness_from_continuity ? 1 : 0);
  o += fmt::format("{},analysis,discharge_high_speed,{}\n", csv_field(a.station.condition),
                   a.line(Streamline::cema_centroid).release.high_speed ? 1 : 0);
  const auto z = analytical::impact_zone(a);
  o += fmt::format("{},analysis,impact_zone_top_clipped,{}\n", csv_field(a.station.condition), z.top_clipped ? 1 : 0);
  o += fmt::format("{},analysis,impact_zone_bottom_clipped,{}\n", csv_field(a.station.condition),
                   z.bottom_clipped ? 1 : 0);
  for (const auto& [m, vals] : models)
    for (Quantity q : kAllQuantities)
      if (vals[q])
        o += fmt::format("{},{},{},{}\n", csv_field(a.station.condition), csv_field(m), name(q),
                         csv_number(*vals[q] * info(q).to_boundary));
  return o;
}

std::string streamline_points_csv(const analytical::TransferAnalysis& a) {
  std::string o = "condition,streamline,point,x_mm,y_mm\n";
  for (Streamline s : analytical::kAllStreamlines) {
    const auto pts = analytical::streamline_path(a, s);
    for (std::size_t k = 0; k < pts.size(); ++k)
      o += fmt::format("{},{},{},{},{}\n", csv_field(a.station.condition), name(s), k, csv_number(pts[k].x() * 1e3),
                       csv_number(pts[k].y() * 1e3));
  }
  return o;
}

std::string estimate_json(const analytical::TransferAnalysis& a, const ModelValues& models,
                          const std::vector<effects::EffectSetting>& fx) {
  const auto& st = a.station;
  const auto& k = a.korzen;
  const auto& rel = a.line(Streamline::cema_centroid).release;
  std::string o = "{\n";
  o += fmt::format(
      "  \"condition\": {{\"name\": {}, \"belt_speed_mps\": {}, \"mass_flow_tph\": {}, "
      "\"plate_distance_mm\": {}, \"plate_top_mm\": {}, \"plate_angle_deg\": {}, "
      "\"stream_thickness_mm\": {}, \"stream_thickness_from_continuity\": {}}},\n",
      json_string(st.condition), json_number(st.belt_speed), json_number(st.mass_flow / units::tph),
      json_number(st.plate_distance * 1e3), json_number(st.plate_top * 1e3),
      json_number(st.plate.angle * units::deg_per_rad), json_number(a.load.height * 1e3),
      a.thickness_from_continuity ? "true" : "false");
  o += "  \"effects\": {";
  bool first = true;
  for (const auto& s : fx)
    if (s.value) {
      o += fmt::format("{}{}: {}", first ? "" : ", ", json_string(s.info->name), json_number(*s.value));
      first = false;
    }
  o += "},\n";
  o += fmt::format("  \"discharge\": {{\"type\": {}, \"ratio_K\": {}, \"release_angle_deg\": {}}},\n",
                   json_string(rel.high_speed ? "high-speed" : "low-speed"), json_number(rel.ratio),
                   json_number(rel.theta * units::deg_per_rad));
  o += fmt::format("  \"stationary_flow\": {},\n", k.stationary_flow ? "true" : "false");
  o += fmt::format("  \"impact_angle_deg\": {},\n",
                   json_number(a.line(Streamline::korzen_centroid).hit->alpha * units::deg_per_rad));
  o += fmt::format("  \"shear_equation\": {},\n", json_string(std::string(name(k.shear_equation))));
  const auto z = analytical::impact_zone(a);
  o += fmt::format(
      "  \"impact_zone\": {{\"impact_zone_top_mm\": {}, \"impact_zone_bottom_mm\": {}, "
      "\"impact_zone_centroid_mm\": {}, \"impact_zone_width_mm\": {}, \"impact_zone_area_mm2\": {}, "
      "\"mean_pressure_Pa\": {}, \"mean_shear_stress_Pa\": {}, \"top_clipped\": {}, "
      "\"bottom_clipped\": {}, \"over_top_fraction\": {}, \"past_foot_fraction\": {}, "
      "\"caught_normal_force_N\": {}, \"caught_shear_force_N\": {}, \"note\": {}}},\n",
      json_number(z.top_y * 1e3), json_number(z.bottom_y * 1e3), json_number(z.centroid_y * 1e3),
      json_number(z.width * 1e3), json_number(z.area * 1e6), json_number(z.mean_pressure),
      json_number(z.mean_shear_stress), z.top_clipped ? "true" : "false",
      z.bottom_clipped ? "true" : "false", json_number(z.caught.over_top), json_number(z.caught.past_foot),
      json_number(z.caught.normal_force), json_number(z.caught.shear_force),
      json_string(stream_miss_note(z.caught)));
  {
    // The design's own bounds, those analyse_transfer checks: the belt's capacity at this belt
    // speed and the deepest load it holds (analytical/load_shape.h), and how far the plate may stand
    // with its top and height kept before the stream's centre misses it.
    const auto full = analytical::largest_load(st.belt);
    const auto reach = analytical::farthest_plate_distance(a);
    o += fmt::format("  \"limits\": {{\"mass_flow_tph_max\": {}, \"stream_thickness_mm_max\": {}, "
                     "\"plate_distance_mm_max\": {}}},\n",
                     json_number(full.area * st.material.bulk_density * st.belt_speed / units::tph),
                     json_number(full.height * 1e3), reach ? json_number(*reach * 1e3) : "null");
  }
  o += "  \"streamlines\": {";
  first = true;
  for (Streamline s : analytical::kAllStreamlines) {
    const auto& l = a.line(s);
    o += fmt::format("{}\n    {}: {{\"height_above_belt_mm\": {}, \"release_x_mm\": {}, \"release_y_mm\": {}",
                     first ? "" : ",", json_string(std::string(name(s))),
                     json_number(l.height_above_belt * 1e3), json_number(l.release.position.x() * 1e3),
                     json_number(l.release.position.y() * 1e3));
    if (l.hit)
      o += fmt::format(", \"impact_y_mm\": {}, \"impact_velocity_mps\": {}, \"impact_angle_deg\": {}, "
                       "\"flight_time_s\": {}, \"on_plate\": {}",
                       json_number(l.hit->point.position.y() * 1e3), json_number(l.hit->speed),
                       json_number(l.hit->alpha * units::deg_per_rad), json_number(l.hit->point.t),
                       l.hit->on_plate ? "true" : "false");
    // The path as drawn and exported (DXF, CSV): mm, [x, y] from the top of the pulley to the plate.
    o += ", \"points_mm\": [";
    const auto pts = analytical::streamline_path(a, s);
    for (std::size_t k = 0; k < pts.size(); ++k)
      o += fmt::format("{}[{}, {}]", k ? ", " : "", json_number(pts[k].x() * 1e3), json_number(pts[k].y() * 1e3));
    o += "]}";
    first = false;
  }
  o += "\n  },\n  \"models\": {";
  first = true;
  for (const auto& [m, vals] : models) {
    o += fmt::format("{}\n    {}: {{", first ? "" : ",", json_string(m));
    bool inner = true;
    for (Quantity q : kAllQuantities)
      if (vals[q]) {
        o += fmt::format("{}{}: {}", inner ? "" : ", ", json_string(std::string(name(q))),
                         json_number(*vals[q] * info(q).to_boundary));
        inner = false;
      }
    o += "}";
    first = false;
  }
  o += "\n  }\n}\n";
  return o;
}

}  // namespace chutelab::api
