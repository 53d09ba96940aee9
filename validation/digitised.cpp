#include "validation/digitised.h"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <fstream>
#include <functional>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <toml++/toml.h>

#include "core/input_error.h"
#include "core/text_file.h"
#include "core/toml_file.h"
#include "core/number.h"
#include "core/units.h"
#include "validation/json_reader.h"

namespace chutelab::validation {
namespace fs = std::filesystem;

namespace {

// ---- WebPlotDigitizer CSV export -------------------------------------------------------------

std::string trim(std::string s) {
  const auto b = s.find_first_not_of(" \t\r\"");
  const auto e = s.find_last_not_of(" \t\r\"");
  return b == std::string::npos ? std::string() : s.substr(b, e - b + 1);
}

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> cells;
  std::string cell;
  bool quoted = false;
  for (char c : line) {
    if (c == '"') quoted = !quoted;
    if (c == ',' && !quoted) {
      cells.push_back(trim(cell));
      cell.clear();
    } else {
      cell += c;
    }
  }
  cells.push_back(trim(cell));
  return cells;
}

bool numeric(const std::string& s) { return parse_number(s).has_value(); }

std::vector<DigitisedCurve> read_wpd_csv(const fs::path& path) {
  const std::string file = path.string();
  std::istringstream in(read_text_file(file, std::size_t{1} << 28));
  std::vector<std::pair<long, std::vector<std::string>>> rows;
  std::string line;
  for (long n = 1; std::getline(in, line); ++n) {
    if (n == 1 && line.rfind("\xEF\xBB\xBF", 0) == 0) line.erase(0, 3);  // a spreadsheet's byte-order mark
    if (!trim(line).empty()) rows.emplace_back(n, split(line));
  }
  if (rows.empty()) throw InputError(file, 0, "", "no data in the file");

  std::size_t width = 0;
  for (const auto& [n, cells] : rows) width = std::max(width, cells.size());
  // A trailing comma leaves an empty last column; WebPlotDigitizer writes pairs.
  if (width % 2 == 1) {
    bool last_empty = true;
    for (const auto& [n, cells] : rows) last_empty = last_empty && (cells.size() < width || cells.back().empty());
    if (last_empty) --width;
    else throw InputError(file, rows.front().first, "", fmt::format("{} columns: expected x,y pairs", width));
  }
  std::vector<DigitisedCurve> curves(width / 2);
  std::size_t first = 0;
  auto is_header = [](const std::vector<std::string>& cells) {
    for (const auto& c : cells)
      if (!c.empty() && !numeric(c)) return true;
    return false;
  };
  // Up to two header rows: dataset names, then axis labels.
  for (int h = 0; h < 2 && first < rows.size() && is_header(rows[first].second); ++h, ++first) {
    const auto& cells = rows[first].second;
    auto cell = [&](std::size_t i) { return i < cells.size() ? cells[i] : std::string(); };
    bool labels = true;  // "X,Y" (or "x,y") in every pair
    for (std::size_t k = 0; k < curves.size(); ++k) {
      std::string a = cell(2 * k), b = cell(2 * k + 1);
      std::transform(a.begin(), a.end(), a.begin(), ::tolower);
      std::transform(b.begin(), b.end(), b.begin(), ::tolower);
      labels = labels && a == "x" && b == "y";
    }
    if (labels) continue;
    for (std::size_t k = 0; k < curves.size(); ++k) {
      curves[k].name = cell(2 * k);
      curves[k].where = {file, rows[first].first};
      // WebPlotDigitizer writes the name over the x column only ("Red,,Green,"); the name over
      // both columns ("Red,Red,Green,Green") reads the same.
      if (!cell(2 * k + 1).empty() && cell(2 * k + 1) != cell(2 * k))
        throw InputError(file, rows[first].first, fmt::format("column {}", 2 * k + 2),
                         fmt::format("'{}' over a y column: a dataset name sits over its x column", cell(2 * k + 1)));
    }
  }
  for (std::size_t k = 0; k < curves.size(); ++k) {
    if (curves[k].name.empty()) {
      if (curves.size() > 1)
        throw InputError(file, first < rows.size() ? rows[0].first : 0, fmt::format("column {}", 2 * k + 1),
                         "several x,y pairs without a row of dataset names: which curve is which?");
      curves[k].name = path.stem().string();
      curves[k].where = {file, 1};
    }
  }
  for (std::size_t r = first; r < rows.size(); ++r) {
    const auto& [n, cells] = rows[r];
    if (is_header(cells))
      throw InputError(file, n, "", "text among the data rows (one export a file; header rows first)");
    for (std::size_t k = 0; k < curves.size(); ++k) {
      const std::string x = 2 * k < cells.size() ? cells[2 * k] : "";
      const std::string y = 2 * k + 1 < cells.size() ? cells[2 * k + 1] : "";
      if (x.empty() && y.empty()) continue;  // this dataset has fewer points
      const std::string field = curves[k].name + (x.empty() ? ".x" : ".y");
      if (x.empty() || y.empty()) throw InputError(file, n, field, "a point needs both x and y");
      const double xv = *parse_number(x), yv = *parse_number(y);
      if (!std::isfinite(xv) || !std::isfinite(yv))
        throw InputError(file, n, curves[k].name, "coordinates must be finite numbers");
      curves[k].points.push_back({xv, yv, {file, n}, curves[k].name});
    }
  }
  return curves;
}

// ---- WebPlotDigitizer project JSON -------------------------------------------------------------

// XYAxes calibration: four points, the first two on the x axis, the last two on the y axis, each
// with pixel position (px, py) and the value typed for it (dx, dy as text).
std::optional<PixelScale> y_scale(const JsonValue& axes) {
  const JsonValue* cal = axes.member("calibrationPoints");
  if (!cal || !cal->array() || cal->array()->size() != 4) return std::nullopt;
  auto num = [](const JsonValue* v) -> std::optional<double> {
    if (!v) return std::nullopt;
    if (v->is_number()) return std::get<double>(v->value);
    if (v->is_string()) return parse_number(std::get<std::string>(v->value));
    return std::nullopt;
  };
  const JsonValue& a = (*cal->array())[2];
  const JsonValue& b = (*cal->array())[3];
  const auto pxa = num(a.member("px")), pya = num(a.member("py")), ya = num(a.member("dy"));
  const auto pxb = num(b.member("px")), pyb = num(b.member("py")), yb = num(b.member("dy"));
  if (!pxa || !pya || !ya || !pxb || !pyb || !yb) return std::nullopt;
  const double pixels = std::hypot(*pxb - *pxa, *pyb - *pya);
  PixelScale s;
  const JsonValue* log = axes.member("isLogY");
  s.log = log && std::holds_alternative<bool>(log->value) && std::get<bool>(log->value);
  if (s.log && !(*ya > 0.0 && *yb > 0.0)) return std::nullopt;
  const double span = s.log ? std::abs(std::log10(*yb / *ya)) : std::abs(*yb - *ya);
  if (!(pixels > 0.0) || !(span > 0.0) || !std::isfinite(span)) return std::nullopt;
  s.per_px = span / pixels;
  return s;
}

std::vector<DigitisedCurve> read_wpd_json(const fs::path& path) {
  const std::string file = path.string();
  const JsonValue doc = read_json(path);
  const JsonValue* coll = doc.member("datasetColl");
  if (!coll || !coll->array())
    throw InputError(file, doc.line, "datasetColl", "not a WebPlotDigitizer project (no datasetColl array)");
  std::map<std::string, std::string> axes_type;  // axes name -> type
  std::map<std::string, std::optional<PixelScale>> axes_scale;
  if (const JsonValue* axes = doc.member("axesColl"); axes && axes->array())
    for (const auto& a : *axes->array()) {
      const JsonValue* n = a.member("name");
      const JsonValue* t = a.member("type");
      if (n && n->is_string() && t && t->is_string()) {
        const std::string& an = std::get<std::string>(n->value);
        axes_type[an] = std::get<std::string>(t->value);
        if (axes_type[an] == "XYAxes") axes_scale[an] = y_scale(a);
      }
    }
  std::vector<DigitisedCurve> curves;
  for (std::size_t i = 0; i < coll->array()->size(); ++i) {
    const JsonValue& ds = (*coll->array())[i];
    const std::string at = fmt::format("datasetColl[{}]", i);
    const JsonValue* name = ds.member("name");
    if (!name || !name->is_string()) throw InputError(file, ds.line, at + ".name", "a dataset needs a name");
    DigitisedCurve c;
    c.name = std::get<std::string>(name->value);
    c.where = {file, name->line};
    if (const JsonValue* an = ds.member("axesName"); an && an->is_string()) {
      const auto it = axes_type.find(std::get<std::string>(an->value));
      if (it != axes_type.end() && it->second != "XYAxes")
        throw InputError(file, an->line, at + ".axesName",
                         fmt::format("dataset '{}' is on {} axes; only calibrated x-y axes (XYAxes) give "
                                     "data units",
                                     c.name, it->second));
      if (auto sc = axes_scale.find(std::get<std::string>(an->value)); sc != axes_scale.end()) c.pixel = sc->second;
    }
    const JsonValue* data = ds.member("data");
    if (!data || !data->array()) throw InputError(file, ds.line, at + ".data", "a dataset needs a data array");
    for (std::size_t j = 0; j < data->array()->size(); ++j) {
      const JsonValue& p = (*data->array())[j];
      const std::string field = fmt::format("{}.data[{}].value", at, j);
      const JsonValue* v = p.member("value");
      const JsonArray* xy = v ? v->array() : nullptr;
      if (!xy || xy->size() != 2 || !(*xy)[0].is_number() || !(*xy)[1].is_number())
        throw InputError(file, v ? v->line : p.line, field, "expected [x, y] numbers");
      const double x = std::get<double>((*xy)[0].value), y = std::get<double>((*xy)[1].value);
      if (!std::isfinite(x) || !std::isfinite(y)) throw InputError(file, v->line, field, "coordinates must be finite");
      c.points.push_back({x, y, {file, v->line}, field});
    }
    curves.push_back(std::move(c));
  }
  return curves;
}

// ---- units ---------------------------------------------------------------------------------------

enum class Dimension { length, force, speed, mass_flow };

std::string_view dimension_name(Dimension d) {
  switch (d) {
    case Dimension::length: return "a length";
    case Dimension::force: return "a force";
    case Dimension::speed: return "a speed";
    case Dimension::mass_flow: return "a mass flow";
  }
  return "";
}

struct Unit {
  std::string_view name;
  Dimension dimension;
  double to_si;
};

const std::vector<Unit>& unit_table() {
  static const std::vector<Unit> t = {
      {"mm", Dimension::length, 1e-3},     {"cm", Dimension::length, 1e-2},
      {"m", Dimension::length, 1.0},       {"in", Dimension::length, 0.0254},
      {"inch", Dimension::length, 0.0254}, {"ft", Dimension::length, 0.3048},
      {"N", Dimension::force, 1.0},        {"kN", Dimension::force, 1e3},
      {"lbf", Dimension::force, 4.4482216152605},  {"kgf", Dimension::force, 9.80665},
      {"m/s", Dimension::speed, 1.0},      {"ft/s", Dimension::speed, 0.3048},
      {"ft/min", Dimension::speed, 0.3048 / 60.0}, {"km/h", Dimension::speed, 1.0 / 3.6},
      {"t/h", Dimension::mass_flow, units::tph},   {"kg/s", Dimension::mass_flow, 1.0},
  };
  return t;
}

std::string unit_list(Dimension d) {
  std::vector<std::string> n;
  for (const auto& u : unit_table())
    if (u.dimension == d) n.emplace_back(u.name);
  return fmt::format("{}", fmt::join(n, ", "));
}

Dimension quantity_dimension(Quantity q) {
  const std::string_view u = info(q).unit;
  if (u == "N") return Dimension::force;
  if (u == "m/s") return Dimension::speed;
  if (u == "t/h") return Dimension::mass_flow;
  return Dimension::length;
}

// The conditions.csv columns a curve's x axis can be, with their SI value per condition.
struct ConditionColumn {
  std::string_view name;
  Dimension dimension;
  double to_boundary;
  std::function<std::optional<double>(const Station&)> value;
};

const std::vector<ConditionColumn>& condition_columns() {
  static const std::vector<ConditionColumn> c = {
      {"belt_speed_mps", Dimension::speed, 1.0, [](const Station& s) { return std::optional(s.belt_speed); }},
      {"mass_flow_tph", Dimension::mass_flow, 1.0 / units::tph,
       [](const Station& s) { return std::optional(s.mass_flow); }},
      {"plate_distance_mm", Dimension::length, 1e3, [](const Station& s) { return std::optional(s.plate_distance); }},
      {"plate_top_mm", Dimension::length, 1e3, [](const Station& s) { return std::optional(s.plate_top); }},
      {"stream_thickness_mm", Dimension::length, 1e3, [](const Station& s) { return s.stream_thickness; }},
  };
  return c;
}

// ---- mapping -------------------------------------------------------------------------------------

class Mapping {
 public:
  Mapping(std::string file, const toml::table& t, std::string prefix, const toml::table* defaults)
      : file_(std::move(file)), t_(t), prefix_(std::move(prefix)), defaults_(defaults) {}

  long line(std::string_view key) const {
    if (auto n = t_.get(key)) return static_cast<long>(n->source().begin.line);
    if (defaults_)
      if (auto n = defaults_->get(key)) return static_cast<long>(n->source().begin.line);
    return static_cast<long>(t_.source().begin.line);
  }
  std::string field(std::string_view key) const {
    return prefix_.empty() ? std::string(key) : fmt::format("{}.{}", prefix_, key);
  }
  [[noreturn]] void fail(std::string_view key, const std::string& why) const {
    throw InputError(file_, line(key), field(key), why);
  }
  const toml::node* node(std::string_view key) const {
    if (auto n = t_.get(key)) return n;
    return defaults_ ? defaults_->get(key) : nullptr;
  }
  std::optional<std::string> text(std::string_view key) const {
    const toml::node* n = node(key);
    if (!n) return std::nullopt;
    if (!n->is_string()) fail(key, "must be a string");
    return n->value<std::string>();
  }
  std::optional<double> number(std::string_view key) const {
    const toml::node* n = node(key);
    if (!n) return std::nullopt;
    const auto v = n->value<double>();
    if (!n->is_number() || !v || !std::isfinite(*v)) fail(key, "must be a finite number");
    return v;
  }
  const Unit& unit(std::string_view key, Dimension d) const {
    const auto name = text(key);
    if (!name) fail(key, fmt::format("is required: the unit of this axis ({}: {})", dimension_name(d), unit_list(d)));
    for (const auto& u : unit_table())
      if (u.name == *name) {
        if (u.dimension != d)
          fail(key, fmt::format("'{}' is not {} (use {})", *name, dimension_name(d), unit_list(d)));
        return u;
      }
    fail(key, fmt::format("unknown unit '{}' (use {})", *name, unit_list(d)));
  }
  void only(std::initializer_list<std::string_view> keys) const {
    for (const auto& [k, n] : t_)
      if (std::find(keys.begin(), keys.end(), k.str()) == keys.end())
        throw InputError(file_, static_cast<long>(k.source().begin.line), field(k.str()),
                         fmt::format("unknown key (known: {})", fmt::join(keys, ", ")));
  }
  const toml::table& table() const { return t_; }

 private:
  std::string file_;
  const toml::table& t_;
  std::string prefix_;
  const toml::table* defaults_;
};

}  // namespace

double PixelScale::y_units(double y, double pixels) const {
  // On a log axis a pixel is a fixed ratio: dy = y ln(10) d(log10 y).
  return log ? std::abs(y) * std::log(10.0) * per_px * pixels : per_px * pixels;
}

std::vector<DigitisedCurve> read_digitised(const fs::path& file) {
  if (!fs::exists(file)) throw InputError(file.string(), 0, "", "file not found");
  std::string ext = file.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), ::tolower);
  return ext == ".json" ? read_wpd_json(file) : read_wpd_csv(file);
}

namespace {

// The mapping's top level: only source, [defaults] and [[curve]]. Returns [defaults] (null if none).
const toml::table* checked_top_level(const std::string& mfile, toml::table& doc) {
  const toml::table* defaults = doc["defaults"].as_table();
  Mapping top(mfile, doc, "", nullptr);
  for (const auto& [k, n] : doc)
    if (k != "source" && k != "defaults" && k != "curve")
      throw InputError(mfile, static_cast<long>(k.source().begin.line), std::string(k.str()),
                       "unknown key (known: source, [defaults], [[curve]])");
  if (doc.contains("defaults") && !defaults) top.fail("defaults", "must be a table: [defaults]");
  if (defaults)
    Mapping(mfile, *defaults, "defaults", nullptr)
        .only({"x_unit", "y_unit", "uncertainty", "uncertainty_px", "x_offset_mm", "y_offset_mm",
               "match_tolerance"});
  return defaults;
}

// Curves by name; a name twice in the inputs would make the mapping ambiguous.
std::map<std::string, const DigitisedCurve*> curves_by_name(const std::vector<DigitisedCurve>& curves) {
  std::map<std::string, const DigitisedCurve*> by_name;
  for (const auto& c : curves)
    if (auto [it, fresh] = by_name.emplace(c.name, &c); !fresh)
      throw InputError(c.where.file, c.where.line, c.name,
                       fmt::format("a second curve named '{}' (first in {}:{})", c.name, it->second->where.file,
                                   it->second->where.line));
  return by_name;
}

// What the dataset and the curves mapped so far hold, so that nothing is given twice.
struct Taken {
  std::set<std::pair<std::string, Quantity>> quantities;
  std::set<std::tuple<std::string, Boundary, double>> trajectory;
  std::set<std::string> curves;  // the names of the curves mapped
};

// One [[curve]] table with its digitised curve and its digitising uncertainty.
struct MappedCurve {
  const toml::table& table;
  const Mapping& m;
  const DigitisedCurve& curve;
  std::string name;
  std::optional<double> u_given, u_px;
  // One standard deviation of a digitised y in y_unit; both kinds given add in quadrature.
  double uncertainty_at(double y) const {
    const double a = u_given.value_or(0.0), b = u_px ? curve.pixel->y_units(y, *u_px) : 0.0;
    return std::sqrt(a * a + b * b);
  }
};

const std::string& known_condition(const Dataset& d, const Mapping& m, std::string_view key, const std::string& c) {
  if (!d.station(c)) m.fail(key, fmt::format("condition '{}' is not in conditions.csv", c));
  return c;
}

// The curve table k names, and its uncertainty.
MappedCurve mapped_curve(const std::string& mfile, const toml::table& ct, std::size_t k, const Mapping& m,
                         const std::map<std::string, const DigitisedCurve*>& by_name, Taken& taken) {
  const auto name = m.text("name");
  if (!name) m.fail("name", "is required: the curve's dataset name in the digitiser's export");
  const auto it = by_name.find(*name);
  if (it == by_name.end()) {
    std::vector<std::string> known;
    for (const auto& [n, c] : by_name) known.push_back("'" + n + "'");
    m.fail("name", fmt::format("no curve named '{}' in the inputs (found: {})", *name, fmt::join(known, ", ")));
  }
  if (!taken.curves.insert(*name).second) m.fail("name", fmt::format("curve '{}' is mapped twice", *name));
  const DigitisedCurve& curve = *it->second;
  if (curve.points.empty()) m.fail("name", fmt::format("curve '{}' has no points", *name));
  // A curve that states its own uncertainty (either kind) replaces the defaults' (both kinds):
  // mixing one from [defaults] with another from the curve would add a different figure's.
  const bool own_u = ct.contains("uncertainty") || ct.contains("uncertainty_px");
  const Mapping own(mfile, ct, fmt::format("curve[{}]", k), nullptr);
  const Mapping& um = own_u ? own : m;
  MappedCurve c{ct, m, curve, *name, um.number("uncertainty"), um.number("uncertainty_px")};
  if (!c.u_given && !c.u_px)
    m.fail("uncertainty", "is required: the digitising uncertainty (one standard deviation of y, in y_unit, "
                          "0 = unknown; or uncertainty_px in pixels)");
  if (c.u_given && *c.u_given < 0.0) m.fail("uncertainty", "cannot be negative");
  if (c.u_px && *c.u_px < 0.0) m.fail("uncertainty_px", "cannot be negative");
  if (c.u_px && !curve.pixel)
    m.fail("uncertainty_px", fmt::format("curve '{}' has no pixel calibration (only a project JSON on XY axes "
                                         "has one); give uncertainty in y_unit",
                                         *name));
  return c;
}

// A stream boundary's curve: its points into trajectory.csv.
void map_trajectory_curve(const Dataset& d, const MappedCurve& c, Taken& taken, DigitisedImport& out) {
  const Mapping& m = c.m;
  for (const char* key : {"condition_by", "conditions", "match_tolerance"})
    if (c.table.contains(key)) m.fail(key, "applies to quantity curves only");
  const auto cond = m.text("condition");
  if (!cond) m.fail("condition", "is required for a stream boundary");
  known_condition(d, m, "condition", *cond);
  const auto b = parse_boundary(*m.text("boundary"));
  if (!b) m.fail("boundary", fmt::format("unknown boundary '{}' (upper, lower, centre)", *m.text("boundary")));
  const Unit& ux = m.unit("x_unit", Dimension::length);
  const Unit& uy = m.unit("y_unit", Dimension::length);
  const double x0 = m.number("x_offset_mm").value_or(0.0) * units::mm;
  const double y0 = m.number("y_offset_mm").value_or(0.0) * units::mm;
  for (const auto& p : c.curve.points) {
    TrajectoryPoint t;
    t.condition = *cond;
    t.boundary = *b;
    // Rounded as trajectory.csv will hold it, so that duplicates are found as the reader finds them.
    t.x = std::round((p.x * ux.to_si + x0) * 1e9) / 1e9;
    t.y = p.y * uy.to_si + y0;
    if (const double u = c.uncertainty_at(p.y); u > 0.0) t.uncertainty = u * uy.to_si;
    t.where = p.where;
    if (!taken.trajectory.insert({t.condition, t.boundary, t.x}).second)
      throw InputError(p.where.file, p.where.line, p.field,
                       fmt::format("a second {} point of '{}' at x = {} mm", chutelab::name(*b), *cond, t.x * 1e3));
    out.trajectory.push_back(t);
  }
  out.summary.push_back(fmt::format("{} ({}:{}): {} points -> trajectory {} {}", c.name, c.curve.where.file,
                                    c.curve.where.line, c.curve.points.size(), *cond, chutelab::name(*b)));
}

// The condition whose condition_by column is each point's x (among the listed conditions, or all).
std::vector<std::string> conditions_by_column(const Dataset& d, const MappedCurve& c) {
  const Mapping& m = c.m;
  const auto by = m.text("condition_by");
  if (!by) m.fail("condition_by", "is required: which conditions.csv column the x axis is (or condition = ...)");
  const ConditionColumn* col = nullptr;
  for (const auto& cc : condition_columns())
    if (cc.name == *by) col = &cc;
  if (!col) {
    std::vector<std::string> known;
    for (const auto& cc : condition_columns()) known.emplace_back(cc.name);
    m.fail("condition_by", fmt::format("'{}' is not a column a figure's x axis can be (use {})", *by,
                                       fmt::join(known, ", ")));
  }
  const Unit& ux = m.unit("x_unit", col->dimension);
  std::vector<const Station*> candidates;
  if (const toml::node* cl = m.node("conditions")) {
    const toml::array* a = cl->as_array();
    if (!a) m.fail("conditions", "must be a list of condition names");
    for (const auto& e : *a) {
      const auto s = e.value<std::string>();
      if (!s) m.fail("conditions", "must be a list of condition names");
      candidates.push_back(d.station(known_condition(d, m, "conditions", *s)));
    }
  } else {
    for (const auto& s : d.stations) candidates.push_back(&s);
  }
  const auto tol = m.number("match_tolerance");
  if (tol && !(*tol > 0.0)) m.fail("match_tolerance", "must be positive");
  std::vector<std::string> cond_of(c.curve.points.size());
  for (std::size_t i = 0; i < c.curve.points.size(); ++i) {
    const auto& p = c.curve.points[i];
    const double x = p.x * ux.to_si * col->to_boundary;  // in the column's unit
    std::vector<std::pair<double, const Station*>> near;
    for (const Station* s : candidates) {
      const auto v = col->value(*s);
      if (!v) continue;
      const double vb = *v * col->to_boundary;
      const double limit = tol ? *tol : 0.05 * std::abs(vb);
      if (std::abs(x - vb) <= limit) near.emplace_back(std::abs(x - vb), s);
    }
    if (near.empty())
      throw InputError(p.where.file, p.where.line, p.field,
                       fmt::format("x = {} {} is no condition's {} (within {})", p.x, ux.name, col->name,
                                   tol ? fmt::format("{}", *tol) : std::string("5 %")));
    if (near.size() > 1) {
      std::vector<std::string> names;
      for (const auto& [dist, s] : near) names.push_back(s->condition);
      throw InputError(p.where.file, p.where.line, p.field,
                       fmt::format("x = {} {} matches {} by {}: list the curve's conditions in the mapping",
                                   p.x, ux.name, fmt::join(names, " and "), col->name));
    }
    cond_of[i] = near.front().second->condition;
  }
  return cond_of;
}

// A quantity's curve: its points into measurements.csv, each at its condition.
void map_quantity_curve(const Dataset& d, const MappedCurve& c, Taken& taken, DigitisedImport& out) {
  const Mapping& m = c.m;
  for (const char* key : {"x_offset_mm", "y_offset_mm"})
    if (c.table.contains(key)) m.fail(key, "applies to stream boundaries only");
  const auto q = parse_quantity(*m.text("quantity"));
  if (!q) {
    std::vector<std::string> known;
    for (Quantity x : kAllQuantities) known.emplace_back(chutelab::name(x));
    m.fail("quantity", fmt::format("unknown quantity '{}' (known: {})", *m.text("quantity"), fmt::join(known, ", ")));
  }
  const Unit& uy = m.unit("y_unit", quantity_dimension(*q));
  const double to_b = info(*q).to_boundary;
  // Which condition each point is.
  std::vector<std::string> cond_of;
  if (const auto one = m.text("condition")) {
    for (const char* key : {"condition_by", "conditions"})
      if (c.table.contains(key)) m.fail(key, "give condition (one point) or condition_by, not both");
    if (c.curve.points.size() != 1)
      m.fail("condition", fmt::format("curve '{}' has {} points; one condition takes one point (use condition_by)",
                                      c.name, c.curve.points.size()));
    cond_of = {known_condition(d, m, "condition", *one)};
  } else {
    cond_of = conditions_by_column(d, c);
  }
  std::vector<std::string> got;
  for (std::size_t i = 0; i < c.curve.points.size(); ++i) {
    const auto& p = c.curve.points[i];
    Measurement meas;
    meas.condition = cond_of[i];
    meas.quantity = *q;
    meas.value = p.y * uy.to_si;
    if (const double u = c.uncertainty_at(p.y); u > 0.0) meas.uncertainty = u * uy.to_si;
    meas.where = p.where;
    if (info(*q).magnitude && meas.value < 0.0)
      throw InputError(p.where.file, p.where.line, p.field,
                       fmt::format("{} is a magnitude and cannot be negative, got {} {}", chutelab::name(*q), p.y,
                                   uy.name));
    if (!taken.quantities.insert({meas.condition, meas.quantity}).second)
      throw InputError(p.where.file, p.where.line, p.field,
                       fmt::format("{} of condition '{}' is already in the dataset or another curve",
                                   chutelab::name(*q), meas.condition));
    got.push_back(fmt::format("{} {:.4g}", meas.condition, meas.value * to_b));
    out.measurements.push_back(meas);
  }
  out.summary.push_back(fmt::format("{} ({}:{}): {} points -> {}: {}", c.name, c.curve.where.file, c.curve.where.line,
                                    c.curve.points.size(), chutelab::name(*q), fmt::join(got, ", ")));
}

}  // namespace

DigitisedImport import_digitised(const Dataset& d, const fs::path& mapping_path,
                                 const std::vector<DigitisedCurve>& curves) {
  const std::string mfile = mapping_path.string();
  toml::table doc = read_toml_file(mfile, "mapping");
  static const toml::table empty;
  const toml::table* defaults = checked_top_level(mfile, doc);
  const toml::array* list = doc["curve"].as_array();
  if (!list || list->empty()) throw InputError(mfile, 0, "curve", "no [[curve]] tables: nothing to import");

  DigitisedImport out;
  if (auto s = doc["source"].value<std::string>()) out.source = *s;
  const auto by_name = curves_by_name(curves);
  Taken taken;
  for (const auto& m : d.measurements) taken.quantities.insert({m.condition, m.quantity});
  for (const auto& p : d.trajectory) taken.trajectory.insert({p.condition, p.boundary, p.x});

  for (std::size_t k = 0; k < list->size(); ++k) {
    const toml::table* ct = (*list)[k].as_table();
    if (!ct) throw InputError(mfile, 0, fmt::format("curve[{}]", k), "must be a table");
    const Mapping m(mfile, *ct, fmt::format("curve[{}]", k), defaults ? defaults : &empty);
    m.only({"name", "condition", "boundary", "quantity", "x_unit", "y_unit", "uncertainty", "uncertainty_px",
            "x_offset_mm",
            "y_offset_mm", "condition_by", "conditions", "match_tolerance"});
    const MappedCurve c = mapped_curve(mfile, *ct, k, m, by_name, taken);
    const bool is_trajectory = ct->contains("boundary");
    if (is_trajectory == ct->contains("quantity"))
      m.fail(is_trajectory ? "quantity" : "boundary",
             "give either boundary (a stream limit, trajectory.csv) or quantity (measurements.csv)");
    if (is_trajectory) map_trajectory_curve(d, c, taken, out);
    else map_quantity_curve(d, c, taken, out);
  }
  for (const auto& c : curves)
    if (!taken.curves.count(c.name)) out.unmapped.push_back(c.name);
  return out;
}

}  // namespace chutelab::validation
