#include "logs/layout.h"

#include <cmath>
#include <fmt/format.h>
#include <set>
#include <sstream>

#include "core/csv_field.h"
#include "core/input_error.h"
#include "core/message.h"
#include "core/toml_file.h"

namespace chutelab::logs {

std::string_view name(Role r) {
  switch (r) {
    case Role::normal: return "normal";
    case Role::shear: return "shear";
    case Role::belt_speed: return "belt_speed";
    case Role::mass_flow: return "mass_flow";
  }
  return "";
}

std::string_view unit(Role r) {
  switch (r) {
    case Role::normal:
    case Role::shear: return "N";
    case Role::belt_speed: return "m/s";
    case Role::mass_flow: return "t/h";
  }
  return "";
}

bool Layout::has(Role r) const {
  for (const auto& c : channels)
    if (c.role == r) return true;
  return false;
}

bool Layout::gives_impact_point() const {
  std::set<double> ys;
  for (const auto& c : channels) {
    if (c.role != Role::normal) continue;
    if (!c.y) return false;
    ys.insert(*c.y);
  }
  return ys.size() >= 2;
}

namespace {

long line_of(const toml::node& n) { return static_cast<long>(n.source().begin.line); }

double number(const toml::node& n, const std::string& file, const std::string& key) {
  const auto v = n.value<double>();
  if (!v || !std::isfinite(*v)) throw InputError(file, line_of(n), key, "must be a finite number");
  return *v;
}

std::string text(const toml::node& n, const std::string& file, const std::string& key) {
  const auto v = n.value<std::string>();
  if (!v) throw InputError(file, line_of(n), key, "must be a string");
  return *v;
}

Channel read_channel(const toml::table& t, const std::string& file, long line) {
  Channel c;
  c.line = line;
  bool has_column = false, has_role = false, has_gain = false;
  for (const auto& [k, n] : t) {
    const std::string key(k.str());
    const std::string field = "channel." + key;
    if (key == "column") {
      c.column = text(n, file, field);
      has_column = true;
      const auto us = c.column.rfind('_');
      if (us == std::string::npos || us == 0 || us + 1 == c.column.size())
        throw InputError(file, line_of(n), field,
                         fmt::format("column {} names no unit: end it with the channel's unit (cell_upper_mV, "
                                     "tacho_Hz)",
                                     shown(c.column)));
      c.unit = c.column.substr(us + 1);
    } else if (key == "role") {
      const std::string r = text(n, file, field);
      has_role = true;
      if (r == "normal") c.role = Role::normal;
      else if (r == "shear") c.role = Role::shear;
      else if (r == "belt_speed") c.role = Role::belt_speed;
      else if (r == "mass_flow") c.role = Role::mass_flow;
      else
        throw InputError(file, line_of(n), field,
                         fmt::format("unknown role {}; one of normal, shear, belt_speed, mass_flow", shown(r)));
    } else if (key == "gain") {
      c.gain = number(n, file, field);
      has_gain = true;
      if (c.gain == 0.0) throw InputError(file, line_of(n), field, "a gain of 0 reads nothing");
    } else if (key == "zero") {
      c.zero = number(n, file, field);
    } else if (key == "gain_uncertainty_percent") {
      c.gain_u = number(n, file, field) / 100.0;
      if (c.gain_u < 0.0 || c.gain_u >= 1.0)
        throw InputError(file, line_of(n), field, "must be at least 0 and below 100 (%)");
    } else if (key == "resolution") {
      c.resolution = number(n, file, field);
      if (c.resolution < 0.0) throw InputError(file, line_of(n), field, "cannot be negative");
    } else if (key == "y_mm") {
      const double y = number(n, file, field);
      if (std::abs(y) > 1e5) throw InputError(file, line_of(n), field, "beyond any rig (at most 1e5 mm)");
      c.y = y * 1e-3;
    } else {
      warn(fmt::format("{}:{}: unknown key {} ignored", file, line_of(n), shown(field)));
    }
  }
  if (!has_column) throw InputError(file, line, "channel.column", "required key is missing");
  if (!has_role) throw InputError(file, line, "channel.role", "required key is missing");
  if (!has_gain) throw InputError(file, line, "channel.gain", "required key is missing");
  if (c.y && c.role != Role::normal)
    throw InputError(file, line, "channel.y_mm", "only a normal cell's height places the impact point");
  return c;
}

}  // namespace

Layout read_layout(const std::filesystem::path& path) {
  const std::string file = path.string();
  const toml::table doc = read_toml_file(file);
  Layout l;
  l.file = path;
  bool any = false;
  std::set<std::string> columns;
  for (const auto& [k, n] : doc) {
    const std::string key(k.str());
    if (key == "time_column") {
      l.time_column = text(n, file, key);
      if (!l.time_column.ends_with("_s"))
        throw InputError(file, line_of(n), key, "the time column's unit must be seconds (a name ending in _s)");
    } else if (key == "channel") {
      const toml::array* a = n.as_array();
      if (!a) throw InputError(file, line_of(n), key, "must be an array of tables ([[channel]])");
      for (const auto& e : *a) {
        const toml::table* t = e.as_table();
        if (!t) throw InputError(file, line_of(e), key, "must be an array of tables ([[channel]])");
        Channel c = read_channel(*t, file, line_of(e));
        if (!columns.insert(c.column).second)
          throw InputError(file, c.line, "channel.column", fmt::format("column {} given twice", shown(c.column)));
        l.channels.push_back(std::move(c));
        any = true;
      }
    } else {
      warn(fmt::format("{}:{}: unknown key {} ignored", file, line_of(n), shown(key)));
    }
  }
  if (!any) throw InputError(file, 0, "channel", "no [[channel]]: the layout names no channel");
  if (!l.has(Role::normal) && !l.has(Role::shear))
    throw InputError(file, 0, "channel.role", "no plate channel (role normal or shear): nothing to measure");
  if (columns.count(l.time_column))
    throw InputError(file, 0, "time_column", "the time column is also a channel");
  return l;
}

std::string layout_toml(const Layout& l) {
  std::ostringstream o;
  o << "# The layout of this folder's logs, one <condition>.csv a condition (docs/datasets.md, \"Logs\").\n";
  o << "time_column = \"" << l.time_column << "\"\n";
  for (const auto& c : l.channels) {
    o << "\n[[channel]]\n";
    o << "column = \"" << c.column << "\"\n";
    o << "role = \"" << name(c.role) << "\"\n";
    o << "gain = " << csv_number(c.gain) << "  # " << unit(c.role) << " per " << c.unit << "\n";
    o << "zero = " << csv_number(c.zero) << "  # " << c.unit << "\n";
    if (c.gain_u > 0.0) o << "gain_uncertainty_percent = " << csv_number(c.gain_u * 100.0) << "\n";
    if (c.resolution > 0.0) o << "resolution = " << csv_number(c.resolution) << "  # " << c.unit << "\n";
    if (c.y) o << "y_mm = " << csv_number(*c.y * 1e3) << "\n";
  }
  return o.str();
}

}  // namespace chutelab::logs
