#include "validation/dataset.h"

#include <array>
#include <cmath>
#include <functional>
#include <fmt/format.h>
#include <iostream>
#include <algorithm>
#include <limits>
#include <map>
#include <mutex>
#include <set>
#include <unordered_map>
#include <toml++/toml.h>

#include "core/input_error.h"
#include "core/message.h"
#include "core/text_file.h"
#include "core/rig_needs.h"
#include "core/toml_file.h"
#include "core/unicode.h"
#include "core/units.h"
#include "validation/csv_table.h"
#include "validation/dataset_fields.h"

namespace chutelab::validation {
namespace fs = std::filesystem;

namespace {
std::optional<std::size_t> find_station(const Dataset& d, std::string_view condition) {
  auto& ix = *d.station_index;
  std::lock_guard lock(ix.m);
  if (ix.data != d.stations.data() || ix.size != d.stations.size()) {
    ix.at.clear();
    for (std::size_t i = 0; i < d.stations.size(); ++i) ix.at.emplace(d.stations[i].condition, i);
    ix.data = d.stations.data();
    ix.size = d.stations.size();
  }
  const auto it = ix.at.find(std::string(condition));
  // A name changed in place since the index was built: fall back to a scan.
  if (it != ix.at.end() && d.stations[it->second].condition == condition) return it->second;
  for (std::size_t i = 0; i < d.stations.size(); ++i)
    if (d.stations[i].condition == condition) return i;
  return std::nullopt;
}
}  // namespace

const Station* Dataset::station(std::string_view condition) const {
  const auto i = find_station(*this, condition);
  return i ? &stations[*i] : nullptr;
}

const SourceLine* Dataset::station_line(std::string_view condition) const {
  const auto i = find_station(*this, condition);
  return i && *i < station_lines.size() ? &station_lines[*i] : nullptr;
}

namespace {

void check_range(const RigField& f, double v, const std::string& file, long line,
                 const std::string& field) {
  if (!std::isfinite(v)) throw InputError(file, line, field, "value must be a finite number");
  if (v < f.min || v > f.max)
    throw InputError(file, line, field,
                     fmt::format("{} is outside the physical range [{}, {}]", v, f.min, f.max));
}

// Geometry (and material) that no rig can have, whichever file it came from.
void check_geometry(const Setup& s, const std::string& file, long line) {
  if (s.material.bulk_density > s.material.solid_density)
    throw InputError(file, line, "bulk_density_kgm3",
                     fmt::format("bulk density {:g} kg/m^3 is above the solid density {:g} kg/m^3 (a bulk "
                                 "solid has voids)",
                                 s.material.bulk_density, s.material.solid_density));
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

// An input uncertainty is one standard deviation, finite and >= 0 (0 = known exactly), and no wider
// than the whole range the input may take (`span`, in the key's unit): beyond it the perturbed inputs
// leave any rig, and u_input silently went missing (5e307 m/s on the belt speed).
void check_input_uncertainty(double v, double span, const std::string& file, long line, const std::string& field) {
  if (!std::isfinite(v)) throw InputError(file, line, field, "uncertainty must be a finite number");
  if (v < 0.0) throw InputError(file, line, field, fmt::format("uncertainty cannot be negative, got {}", v));
  if (v > span)
    throw InputError(file, line, field,
                     fmt::format("uncertainty {:g} is wider than the whole range the input can take ({:g}); give "
                                 "one standard deviation in the key's unit",
                                 v, span));
}

// [uncertainty]: keys are the setup's own, dotted ("material.friction_plate" = 0.02) or in
// sub-tables ([uncertainty.material] friction_plate = 0.02), in the key's unit; top-level keys are
// gravity_mps2 and the operating inputs' setup-wide defaults (belt_speed_mps, mass_flow_tph, ...).
InputUncertainties read_uncertainty_table(const toml::table& doc, const std::string& file) {
  InputUncertainties u;
  const toml::node* root = doc.get("uncertainty");
  if (!root) return u;
  const toml::table* t = root->as_table();
  if (!t)
    throw InputError(file, static_cast<long>(root->source().begin.line), "uncertainty", "must be a table");
  std::map<const RigField*, double> rig;
  std::set<std::string> seen;
  auto take = [&](std::string_view section, std::string_view key, const toml::node& n) {
    const std::string dotted = section.empty() ? std::string(key) : fmt::format("{}.{}", section, key);
    const std::string field = "uncertainty." + dotted;
    const long line = static_cast<long>(n.source().begin.line);
    if (!seen.insert(dotted).second) throw InputError(file, line, field, "given twice");
    const auto v = n.value<double>();
    if (!v || !n.is_number())
      throw InputError(file, line, field, "must be a number (one standard deviation, in the key's unit)");
    check_input_uncertainty(*v, std::numeric_limits<double>::infinity(), file, line, field);
    if (section.empty())
      for (const auto& op : operating_uncertainty_columns())
        if (op.setup_key == key) {
          check_input_uncertainty(*v, op.span, file, line, field);
          u.*op.member = *v * op.to_si;
          return;
        }
    for (const auto& f : rig_fields())
      if (f.section == section && f.key == key) {
        check_input_uncertainty(*v, f.max - f.min, file, line, field);
        rig[&f] = *v * f.to_si;
        return;
      }
    throw InputError(file, line, field,
                     fmt::format("unknown key '{}': not a setup key (e.g. material.friction_plate, "
                                 "belt.pulley_diameter_mm) nor an operating input (belt_speed_mps, "
                                 "mass_flow_tph, plate_distance_mm, plate_top_mm, stream_thickness_mm)",
                                 dotted));
  };
  for (const auto& [k, n] : *t) {
    if (const toml::table* sub = n.as_table()) {
      for (const auto& [k2, n2] : *sub) take(k.str(), k2.str(), n2);
      continue;
    }
    const std::string_view ks = k.str();
    const auto dot = ks.find('.');
    if (dot == std::string_view::npos) take("", ks, n);
    else take(ks.substr(0, dot), ks.substr(dot + 1), n);
  }
  for (const auto& f : rig_fields())
    if (auto it = rig.find(&f); it != rig.end()) u.rig.emplace_back(&f, it->second);
  return u;
}

}  // namespace

namespace {

Setup setup_from(const std::string& file, const DatasetFile* text, InputUncertainties* uncertainty) {
  toml::table doc = text ? parse_toml_text(text->text, file) : read_toml_file(file);
  Setup s;
  // Texts, when given: `name = 42` is a mistake to say, not a name to drop.
  for (const char* key : {"name", "source"})
    if (const toml::node* n = doc.get(key)) {
      const auto v = n->value<std::string>();
      if (!v || !n->is_string())
        throw InputError(file, static_cast<long>(n->source().begin.line), key,
                         fmt::format("must be a text in quotes, e.g. {} = \"...\"", key));
      (std::string_view(key) == "name" ? s.name : s.source) = *v;
    }

  std::vector<std::string_view> present;
  std::vector<std::string> missing;
  for (const auto& f : rig_fields()) {
    const std::string dotted = dotted_key(f);
    toml::node_view<toml::node> node =
        f.section.empty() ? doc[f.key] : doc[f.section][f.key];
    if (!node) {
      if (f.required) missing.push_back(dotted);
      if (f.fallback) f.ref(s) = *f.fallback * f.to_si;
      // Absent, not zero: the DEM asks for it by name (core/rig_needs.h) rather than run on a 0.
      if (read_by_dem_only(f)) f.ref(s) = std::numeric_limits<double>::quiet_NaN();
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
  if (!missing.empty())
    throw InputError(file, 0, missing.front(),
                     fmt::format("required key{} missing: {} (every model reads {}; each key and its unit: "
                                 "docs/dataset-reference.md)",
                                 missing.size() == 1 ? " is" : "s are", fmt::join(missing, ", "),
                                 missing.size() == 1 ? "it" : "them"));
  complete_defaults(s, present);

  // A table of its own that chutelab does not know is a typo ([materal]) or a misplaced key; its
  // keys would silently fall back to defaults, so it is an error. [dem] is read by the DEM.
  for (const auto& [key, node] : doc) {
    const std::string k(key.str());
    if (!node.is_table()) {
      if (k != "name" && k != "source" && k != "gravity_mps2")
        warn(fmt::format("{}:{}: unknown key {} ignored", file, key.source().begin.line, shown(k)));
      continue;
    }
    if (k == "belt" || k == "plate" || k == "material" || k == "dem" || k == "uncertainty") continue;
    throw InputError(file, static_cast<long>(key.source().begin.line), k,
                     fmt::format("unknown table [{}] (known: [belt], [plate], [material], [uncertainty], [dem])", k));
  }
  // Unknown keys inside the rig's tables are most likely typos: say so, but go on.
  for (std::string_view section : {"belt", "plate", "material"}) {
    const toml::table* t = doc[section].as_table();
    if (!t) continue;
    for (const auto& [key, node] : *t) {
      bool known = false;
      for (const auto& f : rig_fields()) known = known || (f.section == section && f.key == key.str());
      if (!known)
        warn(fmt::format("{}:{}: unknown key {}.{} ignored", file, node.source().begin.line, section,
                         std::string_view(key.str())));
    }
  }
  check_geometry(s, file, 0);
  // Checked even when the caller has no use for it: a bad table is bad input wherever it is read.
  InputUncertainties u = read_uncertainty_table(doc, file);
  if (uncertainty) *uncertainty = std::move(u);
  return s;
}

// A dataset's CSV file, from the folder or as already read, with its required columns and the
// layout a missing one is explained with (validation/dataset_fields.h).
CsvTable table_from(const fs::path& path, const DatasetFile* text, std::span<const ColumnSpec> columns,
                    const std::string& what) {
  const std::string layout = fmt::format("{}: {}", what, layout_of(columns));
  return text ? CsvTable::parse(text->text, text->shown, required_columns(columns), layout)
              : CsvTable::read(path, required_columns(columns), layout);
}

}  // namespace

Setup read_setup(const fs::path& path, InputUncertainties* uncertainty) {
  return setup_from(path.string(), nullptr, uncertainty);
}

Setup read_setup(const DatasetFile& setup, InputUncertainties* uncertainty) {
  return setup_from(setup.shown, &setup, uncertainty);
}

DatasetFile read_setup_file(const fs::path& file) {
  return DatasetFile{file.string(), read_text_file(file.string(), kTomlMaxBytes)};
}

namespace {
// The fastest belts run ~15 m/s, the largest carry ~40 000 t/h.
constexpr std::array<OperatingLimit, 5> kOperatingLimits = {{
    {"belt_speed_mps", 0.0, true, 50.0},
    {"mass_flow_tph", 0.0, true, 1e5},
    {"plate_distance_mm", 0.0, true, 1e5},
    {"plate_top_mm", -1e5, false, 1e5},
    {"stream_thickness_mm", 0.0, true, 1e4},
}};
}  // namespace

std::span<const OperatingLimit> operating_limits() { return kOperatingLimits; }

void check_operating_input(std::string_view column, double v, const std::string& field) {
  auto fail = [&](const std::string& why) { throw InputError("", 0, field, why); };
  if (std::isnan(v)) fail("must be a number, got nan");
  const auto* lim = std::find_if(kOperatingLimits.begin(), kOperatingLimits.end(),
                                 [&](const OperatingLimit& l) { return l.column == column; });
  if (lim == kOperatingLimits.end()) return;
  const bool low = lim->min_open ? !(v > lim->min) : !(v >= lim->min);
  const bool high = !(v <= lim->max);
  if (column == "belt_speed_mps") {
    if (low) fail(fmt::format("belt speed must be positive, got {}", v));
    if (high) fail(fmt::format("belt speed {:g} m/s is beyond any conveyor (at most {:g} m/s)", v, lim->max));
  } else if (column == "mass_flow_tph") {
    if (low) fail(fmt::format("mass flow must be positive, got {}", v));
    if (high) fail(fmt::format("mass flow {:g} t/h is beyond any conveyor (at most {:.0f} t/h)", v, lim->max));
  } else if (column == "plate_distance_mm") {
    if (high) fail(fmt::format("plate distance {:g} mm is beyond a transfer station (at most {:g} m)", v, lim->max / 1e3));
    if (low) fail(fmt::format("the plate must be downstream of the pulley centre (x > 0), got {}", v));
  } else if (column == "plate_top_mm") {
    if (low || high)
      fail(fmt::format("plate top {:g} mm is beyond a transfer station (|y| at most {:g} m)", v, lim->max / 1e3));
  } else if (column == "stream_thickness_mm") {
    if (low) fail(fmt::format("stream thickness must be positive, got {}", v));
    if (high) fail(fmt::format("stream thickness {:g} mm is beyond any belt load (at most {:g} m)", v, lim->max / 1e3));
  }
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

const Station& condition_row(const std::vector<Station>& stations, std::string_view condition,
                             const fs::path& conditions_file, std::string_view field) {
  for (const auto& s : stations)
    if (s.condition == condition) return s;
  std::vector<std::string> names;
  for (const auto& s : stations) names.push_back(s.condition);
  throw InputError(conditions_file.string(), 0, std::string(field),
                   fmt::format("no condition named '{}' (known: {})", condition, fmt::join(names, ", ")));
}

namespace {

std::vector<Station> conditions_from(const fs::path& path, const DatasetFile* text, const Setup& setup,
                                     std::vector<SourceLine>* lines, std::vector<InputUncertainties>* uncertainties,
                                     const InputUncertainties& defaults) {
  const CsvTable t = table_from(path, text, condition_columns(), "conditions.csv has one test condition a row");
  const std::size_t c_id = t.require("condition");
  const std::size_t c_speed = t.require("belt_speed_mps");
  const std::size_t c_flow = t.require("mass_flow_tph");
  const std::size_t c_dist = t.require("plate_distance_mm");
  const std::size_t c_top = t.require("plate_top_mm");
  const auto c_thick = t.column("stream_thickness_mm");
  std::vector<std::pair<std::size_t, const UncertaintyColumn*>> c_unc;
  for (const auto& op : operating_uncertainty_columns())
    if (auto c = t.column(std::string(op.column))) c_unc.emplace_back(*c, &op);

  std::vector<std::pair<std::size_t, const RigField*>> overrides;
  for (std::size_t i = 0; i < t.header().size(); ++i) {
    const std::string& col = t.header()[i];
    bool own = false;
    for (const auto& c : condition_columns()) own = own || c.name == col;
    if (own) continue;
    bool is_uncertainty = false;
    for (const auto& op : operating_uncertainty_columns()) is_uncertainty = is_uncertainty || op.column == col;
    if (is_uncertainty) continue;
    if (const RigField* f = find_override_column(col))
      overrides.emplace_back(i, f);
    else
      warn(fmt::format("{}:1: unknown column {} ignored", t.file(), shown(col)));
  }

  std::vector<Station> out;
  // Conditions by the name a reader sees (core/unicode.h): two names that print alike would be
  // tabled and plotted as two conditions nobody can tell apart.
  std::map<std::string, std::pair<long, std::string>> seen;
  for (const auto& row : t.rows()) {
    const std::string& id = t.text(row, c_id);
    if (id.empty()) throw InputError(t.file(), row.line, "condition", "condition name is empty");
    const std::string printed = printed_form(id);
    if (printed.empty())
      throw InputError(t.file(), row.line, "condition",
                       fmt::format("condition name {} prints as nothing (only spaces or invisible characters)", shown(id)));
    if (auto [it, fresh] = seen.emplace(printed, std::pair{row.line, id}); !fresh) {
      if (it->second.second == id)
        throw InputError(t.file(), row.line, "condition",
                         fmt::format("duplicate condition '{}' (first on line {})", id, it->second.first));
      throw InputError(t.file(), row.line, "condition",
                       fmt::format("condition {} prints the same as {} on line {} (they differ only by spaces, "
                                   "invisible characters or the spelling of an accent); name them apart",
                                   shown(id), shown(it->second.second), it->second.first));
    }
    auto checked = [&](const char* column, double v) {
      try {
        check_operating_input(column, v, column);
      } catch (const InputError& e) {
        throw e.located(t.file(), row.line);
      }
      return v;
    };
    const double speed = checked("belt_speed_mps", t.number(row, c_speed));
    const double flow = checked("mass_flow_tph", t.number(row, c_flow));
    const double dist = checked("plate_distance_mm", t.number(row, c_dist));
    const double top = checked("plate_top_mm", t.number(row, c_top));
    std::optional<double> thick;
    if (c_thick) {
      thick = t.optional_number(row, *c_thick);
      if (thick) checked("stream_thickness_mm", *thick);
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
    if (uncertainties) {
      InputUncertainties u = defaults;
      for (const auto& [col, op] : c_unc)
        if (const auto v = t.optional_number(row, col)) {
          check_input_uncertainty(*v, op->span, t.file(), row.line, std::string(op->column));
          u.*op->member = *v * op->to_si;
        }
      uncertainties->push_back(std::move(u));
    }
  }
  if (out.empty()) throw InputError(t.file(), 0, "", "no conditions in the file");
  return out;
}

}  // namespace

std::vector<Station> read_conditions(const fs::path& path, const Setup& setup,
                                     std::vector<SourceLine>* lines,
                                     std::vector<InputUncertainties>* uncertainties,
                                     const InputUncertainties& defaults) {
  return conditions_from(path, nullptr, setup, lines, uncertainties, defaults);
}

namespace {

// Condition name -> station, built once per file: a look-up per row keeps big datasets linear.
using ConditionMap = std::unordered_map<std::string, const Station*>;
ConditionMap condition_map(const Dataset& d) {
  ConditionMap m;
  for (const auto& s : d.stations) m.emplace(s.condition, &s);
  return m;
}

// The condition column of measurement-like files must name a row of conditions.csv (without a
// dataset, e.g. another code's predictions read before the dataset is known: any name, and no
// station to return).
const Station* known_condition(const CsvTable& t, const CsvRow& row, std::size_t col, const ConditionMap* d) {
  const std::string& c = t.text(row, col);
  if (c.empty()) throw InputError(t.file(), row.line, t.header()[col], "empty condition");
  if (!d) return nullptr;
  const auto it = d->find(c);
  if (it == d->end())
    throw InputError(t.file(), row.line, t.header()[col],
                     fmt::format("condition '{}' is not in conditions.csv", c));
  return it->second;
}

// What a rig can measure, in the boundary unit: the largest magnitude (beyond it a value is a unit
// slip or a digitising error, and chi-squared sums overflow) and the smallest uncertainty anyone
// can state (below it a normalised error is meaningless: 1e-300 made chi^2 = inf and p = nan).
struct Bounds {
  double max_abs, min_uncertainty;
  const char* unit;
};
Bounds bounds(Quantity q) {
  switch (q) {
    case Quantity::normal_force:
    case Quantity::shear_force:
    case Quantity::resultant_force: return {1e7, 1e-6, "N"};
    case Quantity::impact_velocity:
    case Quantity::exit_velocity:
    case Quantity::belt_layer_velocity: return {200.0, 1e-6, "m/s"};
    case Quantity::stream_mass_flow: return {1e6, 1e-6, "t/h"};  // the largest belts carry ~4e4 t/h
    case Quantity::impact_point_y: return {1e5, 1e-4, "mm"};
  }
  return {1e7, 1e-6, ""};
}
constexpr Bounds kTrajectoryBounds{1e5, 1e-4, "mm"};
// Plate maps: pressures and shear stresses (a liner's limit is a few MPa), wear depths and rates.
Bounds plate_bounds(const std::string& quantity) {
  if (quantity == "wear_depth_um") return {1e6, 1e-6, "µm"};
  if (quantity == "wear_rate_um_per_h") return {1e6, 1e-9, "µm/h"};
  return {1e9, 1e-6, "Pa"};
}

// An optional one-sigma uncertainty cell: empty or 0 means unknown; negative, or below what any
// instrument states, is an error.
std::optional<double> uncertainty_cell(const CsvTable& t, const CsvRow& row,
                                       const std::optional<std::size_t>& col, double scale, const Bounds& b) {
  if (!col) return std::nullopt;
  const auto u = t.optional_number(row, *col);
  if (!u) return std::nullopt;
  if (*u < 0.0)
    throw InputError(t.file(), row.line, t.header()[*col],
                     fmt::format("uncertainty cannot be negative, got {}", *u));
  if (*u == 0.0) return std::nullopt;
  if (*u < b.min_uncertainty)
    throw InputError(t.file(), row.line, t.header()[*col],
                     fmt::format("uncertainty {:g} {} is below what any instrument states (at least {:g} {}); give "
                                 "the real one, or leave the cell empty when it is unknown",
                                 *u, b.unit, b.min_uncertainty, b.unit));
  if (*u > b.max_abs)
    throw InputError(t.file(), row.line, t.header()[*col],
                     fmt::format("uncertainty {:g} {} is beyond any measurement (at most {:g} {})", *u, b.unit,
                                 b.max_abs, b.unit));
  return *u * scale;
}

}  // namespace

namespace {

std::vector<Measurement> measurements_from(const fs::path& path, const DatasetFile* text, const Dataset* d) {
  const CsvTable t = table_from(path, text, measurement_columns(),
                                "measurements.csv has one measured value a row; a wide table (one row a test, one "
                                "column a quantity) becomes one row per value here, its operating point a row of "
                                "conditions.csv");
  const std::size_t c_id = t.require("condition");
  const std::size_t c_q = t.require("quantity");
  const std::size_t c_v = t.require("value");
  const auto c_u = t.column("uncertainty");
  std::vector<Measurement> out;
  std::map<std::pair<std::string, Quantity>, long> seen;
  const std::optional<ConditionMap> index = d ? std::optional(condition_map(*d)) : std::nullopt;
  for (const auto& row : t.rows()) {
    Measurement m;
    m.where = {t.file(), row.line};
    known_condition(t, row, c_id, index ? &*index : nullptr);
    m.condition = t.text(row, c_id);
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
    if (std::abs(v) > bounds(*q).max_abs)
      throw InputError(t.file(), row.line, "value",
                       fmt::format("{} = {:g} is beyond anything a transfer station shows (|value| at most {:g} {})",
                                   name(*q), v, bounds(*q).max_abs, bounds(*q).unit));
    m.value = v * scale;
    m.uncertainty = uncertainty_cell(t, row, c_u, scale, bounds(*q));
    if (auto [it, fresh] = seen.emplace(std::pair{m.condition, m.quantity}, row.line); !fresh)
      throw InputError(t.file(), row.line, "quantity",
                       fmt::format("duplicate row: {} of condition '{}' is already on line {}",
                                   name(m.quantity), m.condition, it->second));
    out.push_back(std::move(m));
  }
  return out;
}

std::vector<TrajectoryPoint> trajectory_from(const fs::path& path, const DatasetFile* text, const Dataset* d) {
  const CsvTable t = table_from(path, text, trajectory_columns(), "trajectory.csv has one point of a stream's edge a row");
  const std::size_t c_id = t.require("condition");
  const std::size_t c_b = t.require("boundary");
  const std::size_t c_x = t.require("x_mm");
  const std::size_t c_y = t.require("y_mm");
  const auto c_u = t.column("uncertainty_mm");
  std::vector<TrajectoryPoint> out;
  std::map<std::tuple<std::string, Boundary, double>, long> seen;
  const std::optional<ConditionMap> index = d ? std::optional(condition_map(*d)) : std::nullopt;
  for (const auto& row : t.rows()) {
    TrajectoryPoint p;
    p.where = {t.file(), row.line};
    const Station* st = known_condition(t, row, c_id, index ? &*index : nullptr);
    p.condition = t.text(row, c_id);
    const auto b = parse_boundary(t.text(row, c_b));
    if (!b)
      throw InputError(t.file(), row.line, "boundary",
                       fmt::format("unknown boundary '{}' (known: upper, lower, centre)",
                                   t.text(row, c_b)));
    p.boundary = *b;
    p.x = t.number(row, c_x) * units::mm;
    p.y = t.number(row, c_y) * units::mm;
    if (std::abs(p.y) > kTrajectoryBounds.max_abs * units::mm)
      throw InputError(t.file(), row.line, "y_mm",
                       fmt::format("y = {:g} mm is beyond a transfer station (|y| at most 100 m)", p.y * 1e3));
    // The stream flies from the pulley (x = 0 is its centre) to the plate face: a point behind the
    // pulley or past the face cannot be compared with a flight (the parabola would be continued
    // through the plate, or the point dropped).
    if (p.x < 0.0)
      throw InputError(t.file(), row.line, "x_mm",
                       fmt::format("x = {:g} mm is behind the pulley centre (x = 0); the stream is measured "
                                   "between the pulley and the plate",
                                   p.x * 1e3));
    // (Without a dataset, another code's predictions, there is no plate to check against yet.)
    const double face_x =
        st ? st->plate_distance + std::max(0.0, st->plate_top - p.y) * std::tan(st->plate.angle) : 0.0;
    if (st && p.y <= st->plate_top && p.x > face_x + 1e-9)
      throw InputError(t.file(), row.line, "x_mm",
                       fmt::format("x = {:g} mm is past the plate face (x = {:.1f} mm at y = {:g} mm) of condition "
                                   "'{}'; the stream ends at the plate",
                                   p.x * 1e3, face_x * 1e3, p.y * 1e3, p.condition));
    p.uncertainty = uncertainty_cell(t, row, c_u, units::mm, kTrajectoryBounds);
    if (auto [it, fresh] = seen.emplace(std::tuple{p.condition, p.boundary, p.x}, row.line); !fresh)
      throw InputError(t.file(), row.line, "x_mm",
                       fmt::format("duplicate row: {} boundary of '{}' at x = {} mm is already on "
                                   "line {}",
                                   name(p.boundary), p.condition, p.x * 1e3, it->second));
    out.push_back(p);
  }
  return out;
}

std::vector<PlatePoint> plate_map_from(const fs::path& path, const DatasetFile* text, const Dataset& d) {
  const CsvTable t = table_from(path, text, plate_map_columns(), "plate_map.csv has one value at a point of the plate a row");
  const std::size_t c_id = t.require("condition");
  const std::size_t c_y = t.require("y_mm");
  const std::size_t c_z = t.require("z_mm");
  const std::size_t c_q = t.require("quantity");
  const std::size_t c_v = t.require("value");
  const auto c_u = t.column("uncertainty");
  std::vector<PlatePoint> out;
  std::map<std::tuple<std::string, std::string, double, double>, long> seen;
  const ConditionMap index = condition_map(d);
  for (const auto& row : t.rows()) {
    PlatePoint p;
    p.where = {t.file(), row.line};
    const Station* st = known_condition(t, row, c_id, &index);
    p.condition = t.text(row, c_id);
    p.quantity = t.text(row, c_q);
    const auto& qs = plate_quantities();
    const auto q = std::find_if(qs.begin(), qs.end(), [&](const auto& e) { return e.first == p.quantity; });
    if (q == qs.end()) {
      std::string known;
      for (const auto& e : qs) known += (known.empty() ? "" : ", ") + e.first;
      throw InputError(t.file(), row.line, "quantity",
                       fmt::format("unknown plate quantity '{}' (known: {})", p.quantity, known));
    }
    p.scale = q->second;
    p.y = t.number(row, c_y) * units::mm;
    p.z = t.number(row, c_z) * units::mm;
    const double v = t.number(row, c_v);
    if (v < 0.0 && p.quantity != "plate_shear_stress_Pa")
      throw InputError(t.file(), row.line, "value", fmt::format("{} cannot be negative, got {}", p.quantity, v));
    const Bounds b = plate_bounds(p.quantity);
    if (std::abs(v) > b.max_abs)
      throw InputError(t.file(), row.line, "value",
                       fmt::format("{} = {:g} is beyond anything a transfer station shows (|value| at most {:g} {})",
                                   p.quantity, v, b.max_abs, b.unit));
    if (std::abs(p.y) > kTrajectoryBounds.max_abs * units::mm || std::abs(p.z) > kTrajectoryBounds.max_abs * units::mm)
      throw InputError(t.file(), row.line, std::abs(p.y) > kTrajectoryBounds.max_abs * units::mm ? "y_mm" : "z_mm",
                       "the point is beyond a transfer station (|y|, |z| at most 100 m)");
    // A point off the face carries no load in any model: comparing it would test nothing but the
    // record of where the sensor sat. Half a millimetre of slack for coordinates read to the mm.
    if (st && st->plate.height > 0.0 && st->plate.width > 0.0) {
      constexpr double kSlack = 0.5 * units::mm;
      const double top = st->plate_top, bottom = st->plate_top - st->plate.height * std::cos(st->plate.angle);
      const double half = 0.5 * st->plate.width;
      const bool off_y = p.y > top + kSlack || p.y < bottom - kSlack;
      if (off_y || std::abs(p.z) > half + kSlack)
        throw InputError(t.file(), row.line, off_y ? "y_mm" : "z_mm",
                         fmt::format("the point (y = {:g} mm, z = {:g} mm) is off the plate of condition '{}' "
                                     "(its face spans y from {:g} to {:g} mm and z from {:g} to {:g} mm): no "
                                     "model loads it, so it cannot be compared",
                                     p.y / units::mm, p.z / units::mm, p.condition, bottom / units::mm,
                                     top / units::mm, -half / units::mm, half / units::mm));
    }
    p.value = v / p.scale;
    p.uncertainty = uncertainty_cell(t, row, c_u, 1.0 / p.scale, b);
    if (auto [it, fresh] = seen.emplace(std::tuple{p.condition, p.quantity, p.y, p.z}, row.line); !fresh)
      throw InputError(t.file(), row.line, "y_mm",
                       fmt::format("duplicate row: {} of '{}' at y = {} mm, z = {} mm is already on line {}",
                                   p.quantity, p.condition, p.y * 1e3, p.z * 1e3, it->second));
    out.push_back(p);
  }
  return out;
}

}  // namespace

std::vector<Measurement> read_measurements(const fs::path& path, const Dataset* d) {
  return measurements_from(path, nullptr, d);
}

std::vector<TrajectoryPoint> read_trajectory(const fs::path& path, const Dataset* d) {
  return trajectory_from(path, nullptr, d);
}

const DatasetFile* Dataset::source(std::string_view name) const {
  if (!sources) return nullptr;
  const auto it = sources->find(name);
  return it == sources->end() ? nullptr : &it->second;
}

const std::vector<std::pair<std::string, double>>& plate_quantities() {
  static const std::vector<std::pair<std::string, double>> q = {
      {"plate_pressure_Pa", 1.0},
      {"plate_shear_stress_Pa", 1.0},
      {"wear_depth_um", 1e6},
      {"wear_rate_um_per_h", 1e6 * 3600.0},
  };
  return q;
}

namespace {

// The reader of both: `file(name)` gives a file as read (nullptr: not there), in the order the
// checks need them, so a folder's files are read, each once, in the order they always were.
using FileOf = std::function<const DatasetFile*(const char* name)>;

// A value without an uncertainty has no E/u_val and no weight in chi^2 or the diagnosis: it drops
// out of the statistics, which the user must hear of rather than find in the counts. One line a
// value; past the first ten of a file, how many more.
void warn_unstated_uncertainties(const Dataset& d) {
  constexpr int kShown = 10;
  std::map<std::string, int> count;
  auto say = [&](const SourceLine& where, const std::string& what) {
    if (++count[where.file] <= kShown)
      warn(fmt::format("{}:{}: {} has no uncertainty: it is left out of E/u_val and the statistics (give one "
                       "standard deviation in the uncertainty column)",
                       where.file, where.line, what));
  };
  for (const auto& m : d.measurements)
    if (!m.uncertainty) say(m.where, fmt::format("{} of {}", name(m.quantity), shown(m.condition)));
  for (const auto& p : d.trajectory)
    if (!p.uncertainty)
      say(p.where, fmt::format("the {} edge of {} at x = {:g} mm", name(p.boundary), shown(p.condition), p.x * 1e3));
  for (const auto& p : d.plate_map)
    if (!p.uncertainty) say(p.where, fmt::format("{} of {}", p.quantity, shown(p.condition)));
  for (const auto& [file, n] : count)
    if (n > kShown) warn(fmt::format("{}: and {} more values without uncertainty", file, n - kShown));
}

Dataset read_files(const FileOf& file, const fs::path& dir, MeasurementsRequired need,
                   std::shared_ptr<const DatasetTexts> kept) {
  Dataset d;
  d.dir = dir;
  InputUncertainties setup_uncertainty;
  const DatasetFile* setup = file("setup.toml");
  d.setup = setup_from(setup->shown, setup, &setup_uncertainty);
  const DatasetFile* conditions = file("conditions.csv");
  d.stations = conditions_from(conditions->shown, conditions, d.setup, &d.station_lines, &d.input_uncertainty,
                               setup_uncertainty);
  if (const DatasetFile* meas = file("measurements.csv"))
    d.measurements = measurements_from(meas->shown, meas, &d);
  else if (need == MeasurementsRequired::yes)
    throw InputError((dir / "measurements.csv").string(), 0, "",
                     "file not found (a dataset to validate needs measurements)");
  if (const DatasetFile* traj = file("trajectory.csv")) d.trajectory = trajectory_from(traj->shown, traj, &d);
  if (const DatasetFile* plate = file("plate_map.csv")) d.plate_map = plate_map_from(plate->shown, plate, d);
  file("tolerances.toml");  // kept for validate (it is read there, with the other options)
  warn_unstated_uncertainties(d);
  d.sources = std::move(kept);
  return d;
}

}  // namespace

Dataset read_dataset(const fs::path& dir, MeasurementsRequired need) {
  std::error_code ec;
  const auto st = fs::status(dir, ec);
  if (ec && ec != std::errc::no_such_file_or_directory)
    throw InputError(dir.string(), 0, "", fmt::format("cannot read the dataset folder: {}", ec.message()));
  if (!fs::exists(st)) throw InputError(dir.string(), 0, "", "dataset folder not found");
  if (!fs::is_directory(st)) throw InputError(dir.string(), 0, "", "is a file; give the dataset folder");
  fs::directory_iterator probe(dir, ec);  // an unreadable folder fails here, not half-way
  if (ec) throw InputError(dir.string(), 0, "", fmt::format("cannot read the dataset folder: {}", ec.message()));
  auto files = std::make_shared<DatasetTexts>();
  const FileOf read = [&](const char* name) -> const DatasetFile* {
    const fs::path p = dir / name;
    const std::string_view n(name);
    if (n != "setup.toml" && n != "conditions.csv" && !fs::exists(fs::symlink_status(p, ec))) return nullptr;
    const std::size_t max = n.ends_with(".toml") ? kTomlMaxBytes : kTextFileMaxBytes;
    if (n == "tolerances.toml") try {
        return &((*files)[name] = DatasetFile{p.string(), read_text_file(p.string(), max)});
      } catch (const InputError&) {
        return &((*files)[name] = DatasetFile{p.string(), {}, true});
      }
    return &((*files)[name] = DatasetFile{p.string(), read_text_file(p.string(), max)});
  };
  return read_files(read, dir, need, files);
}

Dataset read_dataset(const DatasetTexts& files, const fs::path& dir, MeasurementsRequired need) {
  const FileOf find = [&](const char* name) -> const DatasetFile* {
    const auto it = files.find(name);
    if (it != files.end()) return &it->second;
    const std::string_view n(name);
    if (n == "setup.toml" || n == "conditions.csv") throw InputError((dir / name).string(), 0, "", "file not found");
    return nullptr;
  };
  return read_files(find, dir, need, std::make_shared<const DatasetTexts>(files));
}

}  // namespace chutelab::validation
