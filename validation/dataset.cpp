#include "validation/dataset.h"

#include <cmath>
#include <fmt/format.h>
#include <iostream>
#include <map>
#include <set>
#include <toml++/toml.h>

#include "core/input_error.h"
#include "core/units.h"
#include "validation/csv_table.h"

namespace chutelab::validation {
namespace fs = std::filesystem;

const Station* Dataset::station(std::string_view condition) const {
  for (const auto& s : stations)
    if (s.condition == condition) return &s;
  return nullptr;
}

const SourceLine* Dataset::station_line(std::string_view condition) const {
  for (std::size_t i = 0; i < stations.size(); ++i)
    if (stations[i].condition == condition) return &station_lines[i];
  return nullptr;
}

namespace {

void check_range(const RigField& f, double v, const std::string& file, long line,
                 const std::string& field) {
  if (!std::isfinite(v)) throw InputError(file, line, field, "value must be a finite number");
  if (v < f.min || v > f.max)
    throw InputError(file, line, field,
                     fmt::format("{} is outside the physical range [{}, {}]", v, f.min, f.max));
}

// Geometry that no rig can have, whichever file it came from.
void check_geometry(const Setup& s, const std::string& file, long line) {
  if (s.belt.loaded_width > s.belt.belt_width)
    throw InputError(file, line, "loaded_width_mm",
                     fmt::format("loaded width {:.0f} mm is wider than the belt ({:.0f} mm)",
                                 s.belt.loaded_width * 1e3, s.belt.belt_width * 1e3));
  if (s.belt.trough.troughed()) {
    if (!(s.belt.trough.centre_roll > 0.0) || s.belt.trough.centre_roll >= s.belt.loaded_width)
      throw InputError(file, line, "centre_roll_mm",
                       "a troughed belt needs a centre roll shorter than the loaded width");
    if (!(s.belt.trough.surcharge_angle > 0.0))
      throw InputError(file, line, "surcharge_angle_deg", "a troughed belt needs a surcharge angle");
  }
}

}  // namespace

Setup read_setup(const fs::path& path) {
  const std::string file = path.string();
  if (!fs::exists(path)) throw InputError(file, 0, "", "file not found");
  toml::table doc;
  try {
    doc = toml::parse_file(file);
  } catch (const toml::parse_error& e) {
    throw InputError(file, static_cast<long>(e.source().begin.line), "",
                     fmt::format("malformed TOML: {}", e.description()));
  }
  Setup s;
  if (auto n = doc["name"].value<std::string>()) s.name = *n;
  if (auto n = doc["source"].value<std::string>()) s.source = *n;

  std::vector<std::string_view> present;
  for (const auto& f : rig_fields()) {
    const std::string dotted =
        f.section.empty() ? std::string(f.key) : fmt::format("{}.{}", f.section, f.key);
    toml::node_view<toml::node> node =
        f.section.empty() ? doc[f.key] : doc[f.section][f.key];
    if (!node) {
      if (f.required) throw InputError(file, 0, dotted, "required key is missing");
      if (f.fallback) f.ref(s) = *f.fallback * f.to_si;
      continue;
    }
    const long line = static_cast<long>(node.node()->source().begin.line);
    const auto v = node.value<double>();  // integers convert too
    if (!v || !(node.is_number()))
      throw InputError(file, line, dotted, "must be a number");
    check_range(f, *v, file, line, dotted);
    f.ref(s) = *v * f.to_si;
    present.push_back(f.key);
  }
  complete_defaults(s, present);

  // Unknown keys inside the rig's tables are most likely typos: say so, but go on.
  for (std::string_view section : {"belt", "plate", "material"}) {
    const toml::table* t = doc[section].as_table();
    if (!t) continue;
    for (const auto& [key, node] : *t) {
      bool known = false;
      for (const auto& f : rig_fields()) known = known || (f.section == section && f.key == key.str());
      if (!known)
        std::cerr << fmt::format("warning: {}:{}: unknown key {}.{} ignored\n", file,
                                 node.source().begin.line, section, key.str());
    }
  }
  check_geometry(s, file, 0);
  return s;
}

Station make_station(const Setup& setup, std::string condition, double belt_speed,
                     double mass_flow, double plate_distance, double plate_top,
                     std::optional<double> stream_thickness) {
  Station st;
  st.condition = std::move(condition);
  st.belt = setup.belt;
  st.plate = setup.plate;
  st.material = setup.material;
  st.gravity = setup.gravity;
  st.belt_speed = belt_speed;
  st.mass_flow = mass_flow;
  st.plate_distance = plate_distance;
  st.plate_top = plate_top;
  st.stream_thickness = stream_thickness;
  return st;
}

std::vector<Station> read_conditions(const fs::path& path, const Setup& setup,
                                     std::vector<SourceLine>* lines) {
  const CsvTable t = CsvTable::read(
      path, {"condition", "belt_speed_mps", "mass_flow_tph", "plate_distance_mm", "plate_top_mm"});
  const std::size_t c_id = t.require("condition");
  const std::size_t c_speed = t.require("belt_speed_mps");
  const std::size_t c_flow = t.require("mass_flow_tph");
  const std::size_t c_dist = t.require("plate_distance_mm");
  const std::size_t c_top = t.require("plate_top_mm");
  const auto c_thick = t.column("stream_thickness_mm");

  std::vector<std::pair<std::size_t, const RigField*>> overrides;
  static const std::set<std::string> base = {"condition",         "belt_speed_mps",
                                             "mass_flow_tph",     "plate_distance_mm",
                                             "plate_top_mm",      "stream_thickness_mm"};
  for (std::size_t i = 0; i < t.header().size(); ++i) {
    const std::string& col = t.header()[i];
    if (base.count(col)) continue;
    if (const RigField* f = find_override_column(col))
      overrides.emplace_back(i, f);
    else
      std::cerr << fmt::format("warning: {}:1: unknown column '{}' ignored\n", t.file(), col);
  }

  std::vector<Station> out;
  std::map<std::string, long> seen;
  for (const auto& row : t.rows()) {
    const std::string& id = t.text(row, c_id);
    if (id.empty()) throw InputError(t.file(), row.line, "condition", "condition name is empty");
    if (auto [it, fresh] = seen.emplace(id, row.line); !fresh)
      throw InputError(t.file(), row.line, "condition",
                       fmt::format("duplicate condition '{}' (first on line {})", id, it->second));
    const double speed = t.number(row, c_speed);
    const double flow = t.number(row, c_flow);
    if (speed <= 0.0)
      throw InputError(t.file(), row.line, "belt_speed_mps",
                       fmt::format("belt speed must be positive, got {}", speed));
    if (flow <= 0.0)
      throw InputError(t.file(), row.line, "mass_flow_tph",
                       fmt::format("mass flow must be positive, got {}", flow));
    const double dist = t.number(row, c_dist);
    if (dist <= 0.0)
      throw InputError(t.file(), row.line, "plate_distance_mm",
                       fmt::format("the plate must be downstream of the pulley centre (x > 0), got {}",
                                   dist));
    const double top = t.number(row, c_top);
    std::optional<double> thick;
    if (c_thick) {
      thick = t.optional_number(row, *c_thick);
      if (thick && *thick <= 0.0)
        throw InputError(t.file(), row.line, "stream_thickness_mm",
                         fmt::format("stream thickness must be positive, got {}", *thick));
    }
    Setup local = setup;
    for (const auto& [col, f] : overrides) {
      if (t.text(row, col).empty()) continue;
      const double v = t.number(row, col);
      check_range(*f, v, t.file(), row.line, std::string(f->column));
      f->ref(local) = v * f->to_si;
    }
    check_geometry(local, t.file(), row.line);
    out.push_back(make_station(local, id, speed, flow * units::tph, dist * units::mm,
                               top * units::mm,
                               thick ? std::optional<double>(*thick * units::mm) : std::nullopt));
    if (lines) lines->push_back({t.file(), row.line});
  }
  if (out.empty()) throw InputError(t.file(), 0, "", "no conditions in the file");
  return out;
}

namespace {

// The condition column of measurement-like files must name a row of conditions.csv.
std::string known_condition(const CsvTable& t, const CsvRow& row, std::size_t col, const Dataset& d) {
  const std::string& c = t.text(row, col);
  if (!d.station(c))
    throw InputError(t.file(), row.line, t.header()[col],
                     fmt::format("condition '{}' is not in conditions.csv", c));
  return c;
}

// An optional one-sigma uncertainty cell: empty or 0 means unknown; negative is an error.
std::optional<double> uncertainty_cell(const CsvTable& t, const CsvRow& row,
                                       const std::optional<std::size_t>& col, double scale) {
  if (!col) return std::nullopt;
  const auto u = t.optional_number(row, *col);
  if (!u) return std::nullopt;
  if (*u < 0.0)
    throw InputError(t.file(), row.line, t.header()[*col],
                     fmt::format("uncertainty cannot be negative, got {}", *u));
  if (*u == 0.0) return std::nullopt;
  return *u * scale;
}

std::vector<Measurement> read_measurements(const fs::path& path, const Dataset& d) {
  const CsvTable t = CsvTable::read(path, {"condition", "quantity", "value"});
  const std::size_t c_id = t.require("condition");
  const std::size_t c_q = t.require("quantity");
  const std::size_t c_v = t.require("value");
  const auto c_u = t.column("uncertainty");
  std::vector<Measurement> out;
  std::map<std::pair<std::string, Quantity>, long> seen;
  for (const auto& row : t.rows()) {
    Measurement m;
    m.where = {t.file(), row.line};
    m.condition = known_condition(t, row, c_id, d);
    const auto q = parse_quantity(t.text(row, c_q));
    if (!q) {
      std::string known;
      for (Quantity k : kAllQuantities) known += fmt::format("{}{}", known.empty() ? "" : ", ", name(k));
      throw InputError(t.file(), row.line, "quantity",
                       fmt::format("unknown quantity '{}' (known: {})", t.text(row, c_q), known));
    }
    m.quantity = *q;
    const double scale = 1.0 / info(*q).to_boundary;
    const double v = t.number(row, c_v);
    if (info(*q).magnitude && v < 0.0)
      throw InputError(t.file(), row.line, "value",
                       fmt::format("{} is a magnitude and cannot be negative, got {}", name(*q), v));
    m.value = v * scale;
    m.uncertainty = uncertainty_cell(t, row, c_u, scale);
    if (auto [it, fresh] = seen.emplace(std::pair{m.condition, m.quantity}, row.line); !fresh)
      throw InputError(t.file(), row.line, "quantity",
                       fmt::format("duplicate row: {} of condition '{}' is already on line {}",
                                   name(m.quantity), m.condition, it->second));
    out.push_back(std::move(m));
  }
  return out;
}

std::vector<TrajectoryPoint> read_trajectory(const fs::path& path, const Dataset& d) {
  const CsvTable t = CsvTable::read(path, {"condition", "boundary", "x_mm", "y_mm"});
  const std::size_t c_id = t.require("condition");
  const std::size_t c_b = t.require("boundary");
  const std::size_t c_x = t.require("x_mm");
  const std::size_t c_y = t.require("y_mm");
  const auto c_u = t.column("uncertainty_mm");
  std::vector<TrajectoryPoint> out;
  std::map<std::tuple<std::string, Boundary, double>, long> seen;
  for (const auto& row : t.rows()) {
    TrajectoryPoint p;
    p.where = {t.file(), row.line};
    p.condition = known_condition(t, row, c_id, d);
    const auto b = parse_boundary(t.text(row, c_b));
    if (!b)
      throw InputError(t.file(), row.line, "boundary",
                       fmt::format("unknown boundary '{}' (known: upper, lower, centre)",
                                   t.text(row, c_b)));
    p.boundary = *b;
    p.x = t.number(row, c_x) * units::mm;
    p.y = t.number(row, c_y) * units::mm;
    p.uncertainty = uncertainty_cell(t, row, c_u, units::mm);
    if (auto [it, fresh] = seen.emplace(std::tuple{p.condition, p.boundary, p.x}, row.line); !fresh)
      throw InputError(t.file(), row.line, "x_mm",
                       fmt::format("duplicate row: {} boundary of '{}' at x = {} mm is already on "
                                   "line {}",
                                   name(p.boundary), p.condition, p.x * 1e3, it->second));
    out.push_back(p);
  }
  return out;
}

}  // namespace

Dataset read_dataset(const fs::path& dir, MeasurementsRequired need) {
  if (!fs::is_directory(dir)) throw InputError(dir.string(), 0, "", "dataset folder not found");
  Dataset d;
  d.dir = dir;
  d.setup = read_setup(dir / "setup.toml");
  d.stations = read_conditions(dir / "conditions.csv", d.setup, &d.station_lines);
  const fs::path meas = dir / "measurements.csv";
  if (fs::exists(meas))
    d.measurements = read_measurements(meas, d);
  else if (need == MeasurementsRequired::yes)
    throw InputError(meas.string(), 0, "", "file not found (a dataset to validate needs measurements)");
  const fs::path traj = dir / "trajectory.csv";
  if (fs::exists(traj)) d.trajectory = read_trajectory(traj, d);
  return d;
}

}  // namespace chutelab::validation
