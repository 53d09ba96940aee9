#include "api/sweep.h"

#include <algorithm>
#include <cmath>
#include <tuple>
#include <fmt/format.h>

#include "analytical/impact_zone.h"
#include "core/csv_field.h"
#include "core/input_error.h"
#include "core/number.h"
#include "reports/design.h"
#include "validation/dataset.h"

namespace chutelab::api {
namespace {
using analytical::Streamline;

// A designer's table, each point milliseconds: more points than this is a typo in STEP.
constexpr std::size_t kMaxPoints = 2000;

struct ConditionInput {
  std::string_view name, column, label;
  bool positive;
};
constexpr std::array<ConditionInput, 5> kConditionInputs = {{
    {"belt_speed", "belt_speed_mps", "belt speed (m/s)", true},
    {"mass_flow", "mass_flow_tph", "mass flow (t/h)", true},
    {"plate_distance", "plate_distance_mm", "plate distance (mm)", true},
    {"plate_top", "plate_top_mm", "plate top (mm)", false},
    {"stream_thickness", "stream_thickness_mm", "stream thickness (mm)", true},
}};

constexpr std::array<std::string_view, 5> kUnitSuffixes = {"_mm", "_deg", "_kgm3", "_Pa", "_mps2"};

std::string known_names() {
  std::vector<std::string> n;
  for (const auto& c : kConditionInputs) n.emplace_back(c.name);
  for (const auto& f : rig_fields())
    if (!f.column.empty()) n.emplace_back(f.column);
  for (const auto& e : effects::library()) n.push_back(e.name);
  return fmt::format("{}", fmt::join(n, ", "));
}

double number(std::string_view text, std::string_view what, const std::string& spec) {
  const auto v = parse_number(text);
  if (!v || !std::isfinite(*v))
    throw InputError("", 0, "sweep",
                     fmt::format("{} '{}' in '{}' is not a finite number (expected NAME=FROM:TO:STEP)", what, text, spec));
  return *v;
}

std::string unit_label(std::string_view column) {
  for (auto suffix : kUnitSuffixes)
    if (column.ends_with(suffix)) {
      std::string stem(column.substr(0, column.size() - suffix.size()));
      std::replace(stem.begin(), stem.end(), '_', ' ');
      const std::string_view u = suffix.substr(1);
      return fmt::format("{} ({})", stem, u == "kgm3" ? "kg/m^3" : u == "mps2" ? "m/s^2" : u);
    }
  std::string s(column);
  std::replace(s.begin(), s.end(), '_', ' ');
  return s;
}

// The one CSV writer's cells (core/csv_field.h): quoted text, numbers that read back exactly.
std::string csv_cell(const std::string& s) { return csv_field(s); }
std::string number_cell(double v) { return csv_number(v); }

}  // namespace

std::vector<double> SweepSpec::values() const {
  const std::size_t n = step == 0.0 ? 1 : static_cast<std::size_t>(std::floor((to - from) / step + 1e-9)) + 1;
  std::vector<double> v;
  // From the index, not by accumulation: 0.1 steps land on the decimals the user typed.
  for (std::size_t i = 0; i < n; ++i) v.push_back(from + static_cast<double>(i) * step);
  return v;
}

SweepSpec parse_sweep(const std::string& text) {
  const auto eq = text.find('=');
  if (eq == std::string::npos || eq == 0)
    throw InputError("", 0, "sweep", fmt::format("'{}' is not NAME=FROM:TO:STEP", text));
  std::string name = text.substr(0, eq);
  std::replace(name.begin(), name.end(), '-', '_');
  const std::string range = text.substr(eq + 1);
  const auto c1 = range.find(':');
  const auto c2 = c1 == std::string::npos ? std::string::npos : range.find(':', c1 + 1);
  if (c2 == std::string::npos || range.find(':', c2 + 1) != std::string::npos)
    throw InputError("", 0, "sweep", fmt::format("'{}' is not NAME=FROM:TO:STEP (three numbers after '=')", text));

  SweepSpec s;
  s.from = number(range.substr(0, c1), "FROM", text);
  s.to = number(range.substr(c1 + 1, c2 - c1 - 1), "TO", text);
  s.step = number(range.substr(c2 + 1), "STEP", text);

  bool found = false;
  for (const auto& c : kConditionInputs)
    if (name == c.name || name == c.column) {
      s.kind = SweepSpec::Kind::condition;
      s.column = c.column;
      s.option = c.name;
      s.label = c.label;
      found = true;
      if (c.positive && !(s.from > 0.0 && s.to > 0.0))
        throw InputError("", 0, "sweep", fmt::format("{} must stay positive, got {} to {}", c.name, s.from, s.to));
      for (double v : {s.from, s.to}) validation::check_operating_input(c.column, v, "sweep");
    }
  if (!found)
    for (const auto& f : rig_fields()) {
      if (f.column.empty()) continue;
      bool match = name == f.column;
      for (auto suffix : kUnitSuffixes) match = match || name + std::string(suffix) == f.column;
      if (!match) continue;
      s.kind = SweepSpec::Kind::rig;
      s.field = &f;
      s.column = f.column;
      s.label = unit_label(f.column);
      found = true;
      for (double v : {s.from, s.to})
        if (v < f.min || v > f.max)
          throw InputError("", 0, "sweep", fmt::format("{} = {} is outside its physical range [{}, {}]", f.column, v, f.min, f.max));
    }
  if (!found)
    if (const auto* e = effects::find(name)) {
      s.kind = SweepSpec::Kind::effect;
      s.effect = e;
      s.column = e->unit.empty() ? e->name : fmt::format("{}_{}", e->name, e->unit);
      s.label = fmt::format("{} {}{}", e->name, e->parameter, e->unit.empty() ? "" : " (" + e->unit + ")");
      found = true;
      for (double v : {s.from, s.to})
        if (v < e->lower || v > e->upper)
          throw InputError("", 0, "sweep", fmt::format("{} = {} is outside its range [{}, {}]", e->name, v, e->lower, e->upper));
    }
  if (!found)
    throw InputError("", 0, "sweep", fmt::format("unknown input '{}' (known: {})", name, known_names()));

  if (s.from == s.to) {
    s.step = 0.0;
  } else {
    if (s.step == 0.0 || (s.to - s.from) * s.step < 0.0)
      throw InputError("", 0, "sweep",
                       fmt::format("STEP {} never gets from {} to {}", range.substr(c2 + 1), s.from, s.to));
    if ((s.to - s.from) / s.step + 1.0 > static_cast<double>(kMaxPoints))
      throw InputError("", 0, "sweep",
                       fmt::format("{:.3g} points from {} to {} in steps of {}: at most {} (a larger STEP?)",
                                   (s.to - s.from) / s.step + 1.0, s.from, s.to, s.step, kMaxPoints));
    // Every point a different number: a STEP below the resolution of a double near FROM would give
    // rows of one value under different labels.
    const auto v = s.values();
    for (std::size_t i = 1; i < v.size(); ++i)
      if (v[i] == v[i - 1])
        throw InputError("", 0, "sweep",
                         fmt::format("STEP {} is below the resolution of a number near {} (points {} and {} are the "
                                     "same number)",
                                     s.step, v[i], i, i + 1));
  }
  return s;
}

void apply_sweep_value(const SweepSpec& s, double value, Station& st) {
  if (s.kind != SweepSpec::Kind::rig) return;
  Setup setup;
  setup.belt = st.belt;
  setup.plate = st.plate;
  setup.material = st.material;
  setup.gravity = st.gravity;
  s.field->ref(setup) = value * s.field->to_si;
  st.belt = setup.belt;
  st.plate = setup.plate;
  st.material = setup.material;
  st.gravity = setup.gravity;
}

std::string sweep_csv(const SweepSpec& s, const std::vector<SweepRow>& rows, const FieldNames& names) {
  // Columns: the swept value, every scalar any point has (first-seen order), the flags, each
  // model's quantities, and a note; a point without an answer leaves its cells empty.
  std::vector<std::string> scalar_cols;
  std::vector<std::pair<std::string, Quantity>> model_cols;
  for (const auto& r : rows) {
    if (!r.point) continue;
    for (const auto& [n, v] : estimate_scalars(r.point->analysis))
      if (n != s.column && std::find(scalar_cols.begin(), scalar_cols.end(), n) == scalar_cols.end())
        scalar_cols.push_back(n);
    for (const auto& [m, vals] : r.point->models)
      for (Quantity q : kAllQuantities)
        if (vals[q] && std::find(model_cols.begin(), model_cols.end(), std::pair{m, q}) == model_cols.end())
          model_cols.emplace_back(m, q);
  }
  std::string o = s.column;
  for (const auto& c : scalar_cols) o += "," + c;
  o += ",stationary_flow,discharge_high_speed,stream_thickness_from_continuity";
  for (const auto& [m, q] : model_cols) o += fmt::format(",{}_{}", m, name(q));
  o += ",note\n";
  for (const auto& r : rows) {
    o += number_cell(r.value);
    if (!r.point) {
      o += std::string(scalar_cols.size() + 3 + model_cols.size(), ',') + "," + csv_cell(said_text(r.note, names)) + "\n";
      continue;
    }
    const auto& a = r.point->analysis;
    const auto sc = estimate_scalars(a);
    for (const auto& c : scalar_cols) {
      const auto it = std::find_if(sc.begin(), sc.end(), [&](const auto& p) { return p.first == c; });
      o += "," + (it == sc.end() ? std::string() : number_cell(it->second));
    }
    o += fmt::format(",{},{},{}", a.korzen.stationary_flow ? 1 : 0,
                     a.line(Streamline::cema_centroid).release.high_speed ? 1 : 0, a.thickness_from_continuity ? 1 : 0);
    for (const auto& [m, q] : model_cols) {
      std::string cell;
      for (const auto& [mm, vals] : r.point->models)
        if (mm == m && vals[q]) cell = number_cell(*vals[q] * info(q).to_boundary);
      o += "," + cell;
    }
    o += "," + csv_cell(said_text(r.note, names)) + "\n";
  }
  return o;
}

std::string sweep_json(const SweepSpec& s, const std::vector<SweepRow>& rows,
                       const std::vector<effects::EffectSetting>& settings, const FieldNames& names) {
  std::string o = fmt::format(
      "{{\n  \"sweep\": {{\"name\": {}, \"from\": {}, \"to\": {}, \"step\": {}, \"points\": {}}},\n  \"rows\": [",
      json_string(s.column), json_number(s.from), json_number(s.to), json_number(s.step), rows.size());
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const auto& r = rows[i];
    o += fmt::format("{}\n    {{{}: {}, ", i ? "," : "", json_string(s.column), json_number(r.value));
    if (!r.point) {
      o += fmt::format("\"error\": {}}}", json_string(said_text(r.note, names)));
      continue;
    }
    auto fx = settings;
    if (s.kind == SweepSpec::Kind::effect) fx.push_back({s.effect, r.value});
    std::string e = estimate_json(r.point->analysis, r.point->models, fx);
    while (!e.empty() && e.back() == '\n') e.pop_back();
    std::string indented;
    for (char c : e) indented += c == '\n' ? std::string("\n    ") : std::string(1, c);
    o += "\"estimate\": " + indented + "}";
  }
  o += "\n  ]\n}\n";
  return o;
}

std::string sweep_table(const SweepSpec& s, const std::vector<SweepRow>& rows, const FieldNames& names) {
  std::string o = fmt::format("chutelab estimate: sweep of {} from {} to {} ({} points; analytical models)\n\n",
                              s.column, s.from, s.to, rows.size());
  o += fmt::format("  {:>14} {:>8} {:>9} {:>10} {:>8} {:>9} {:>9} {:>9} {:>12} {:>12}\n", s.column, "V_p_mps",
                   "alpha_deg", "stationary", "V_a_mps", "R_n_N", "R_s_N", "R_N", "y_korzen_mm", "y_cema_mm");
  // Enough digits that neighbouring points differ (a sweep in steps of 1e-13 from 300 shows them),
  // at least the 6 a designer reads.
  int digits = 6;
  if (s.step != 0.0)
    digits = std::clamp(static_cast<int>(std::ceil(std::log10(std::max(std::abs(s.from), std::abs(s.to)) /
                                                                std::abs(s.step)))) +
                            2,
                        6, 17);
  for (const auto& r : rows) {
    o += fmt::format("  {:>14.{}g} ", r.value, digits);
    if (!r.point) {
      o += said_text(r.note, names) + "\n";
      continue;
    }
    const auto& a = r.point->analysis;
    QuantityValues k;
    for (const auto& [m, vals] : r.point->models)
      if (m == "korzen") k = vals;
    auto cell = [](const std::optional<double>& v, double scale, int w, int d) {
      return v ? fmt::format("{:>{}.{}f}", *v * scale, w, d) : fmt::format("{:>{}}", "-", w);
    };
    const auto& kc = a.line(Streamline::korzen_centroid).hit;
    const auto& cc = a.line(Streamline::cema_centroid).hit;
    o += fmt::format("{} {:>9.2f} {:>10} {} {} {} {} {} {}", cell(k[Quantity::impact_velocity], 1.0, 8, 3),
                     kc->alpha * 180.0 / 3.14159265358979323846, a.korzen.stationary_flow ? "yes" : "no",
                     cell(k[Quantity::exit_velocity], 1.0, 8, 3), cell(k[Quantity::normal_force], 1.0, 9, 2),
                     cell(k[Quantity::shear_force], 1.0, 9, 2), cell(k[Quantity::resultant_force], 1.0, 9, 2),
                     cell(k[Quantity::impact_point_y], 1e3, 12, 1),
                     cell(cc ? std::optional<double>(cc->point.position.y()) : std::nullopt, 1e3, 12, 1));
    if (!r.note.empty()) o += "  " + said_text(r.note, names);
    o += "\n";
  }
  return o;
}

std::string sweep_chart(const SweepSpec& s, const std::vector<SweepRow>& rows, const FieldNames& names) {
  reports::SweepChart c;
  c.x_label = s.label;
  struct Line { Streamline which; const char* label; const char* colour; const char* dash; };
  const Line lines[] = {{Streamline::upper, "upper limit", "#1f77b4", ""},
                        {Streamline::cema_centroid, "CEMA centroid (booth-cema impact point)", "#2ca02c", "8 4"},
                        {Streamline::korzen_centroid, "Korzen centroid (korzen impact point)", "#9467bd", "2 3"},
                        {Streamline::lower, "lower limit", "#d62728", ""}};
  for (const auto& l : lines) c.impact_mm.push_back({l.label, l.colour, l.dash, {}});
  const std::pair<Quantity, const char*> forces[] = {{Quantity::normal_force, "#1f77b4"},
                                                     {Quantity::shear_force, "#ff7f0e"},
                                                     {Quantity::resultant_force, "#333333"}};
  for (const auto& [q, colour] : forces)
    c.forces_N.push_back({fmt::format("{} (korzen)", info(q).symbol), colour, "", {}});
  for (const auto& r : rows) {
    c.x.push_back(r.value);
    c.plate_top_mm.push_back(r.plate_top_mm);
    c.plate_bottom_mm.push_back(r.plate_bottom_mm);
    // What the reason is about: the mass flow (continuity) means the load no longer fits the belt.
    c.gap_label.push_back(r.point ? ""
                          : r.why == "mass_flow_tph" || r.why == "stream_thickness_mm" ? "belt overfilled"
                          : r.why == "plate_distance_mm" || r.why == "plate_top_mm"    ? "stream misses the plate"
                                                                                       : "no answer");
    c.gap_reason.push_back(r.point ? "" : said_text(r.note, names));
    // A point with an answer and a note: the plate does not take the whole stream there.
    std::string partial;
    if (r.point && !r.note.empty()) {
      const auto caught = analytical::impact_zone(r.point->analysis).caught;
      partial = caught.over_top > 0.0 && caught.past_foot > 0.0 ? "part misses the plate"
                : caught.over_top > 0.0                         ? "part over the top edge"
                : caught.past_foot > 0.0                        ? "part past the foot"
                                                                : "centroid off the plate";
    }
    c.partial_label.push_back(partial);
    c.partial_reason.push_back(partial.empty() ? "" : fmt::format("{} = {:g}: {}", s.column, r.value, said_text(r.note, names)));
    for (std::size_t i = 0; i < std::size(lines); ++i) {
      std::optional<double> y;
      if (r.point)
        if (const auto& h = r.point->analysis.line(lines[i].which).hit) y = h->point.position.y() * 1e3;
      c.impact_mm[i].y.push_back(y);
    }
    for (std::size_t i = 0; i < std::size(forces); ++i) {
      std::optional<double> f;
      if (r.point)
        for (const auto& [m, vals] : r.point->models)
          if (m == "korzen" && vals[forces[i].first]) f = *vals[forces[i].first];
      c.forces_N[i].y.push_back(f);
    }
  }
  return reports::sweep_svg(c);
}

std::string SweepResult::table(const FieldNames& names) const { return sweep_table(spec, rows, names); }
std::string SweepResult::csv(const FieldNames& names) const { return sweep_csv(spec, rows, names); }
std::string SweepResult::json(const FieldNames& names) const { return sweep_json(spec, rows, settings, names); }
std::string SweepResult::svg(const FieldNames& names) const {
  return reports::standalone_svg(sweep_chart(spec, rows, names));
}

SweepResult sweep(const SweepOptions& o) {
  SweepResult res;
  for (const auto& e : o.effects) res.settings.push_back(effects::parse_setting(e, false));
  const analytical::EffectList fixed = effects::instantiate(res.settings);
  const SweepSpec spec = parse_sweep(o.sweep);
  res.spec = spec;
  // The swept input given as well: which one holds is not clear.
  if (spec.kind == SweepSpec::Kind::condition) {
    const bool given = (spec.option == "belt_speed" && o.belt_speed) || (spec.option == "mass_flow" && o.mass_flow) ||
                       (spec.option == "plate_distance" && o.plate_distance) ||
                       (spec.option == "plate_top" && o.plate_top) ||
                       (spec.option == "stream_thickness" && o.stream_thickness);
    if (given)
      throw InputError("", 0, "sweep", fmt::format("{} is swept; leave out {}", spec.column, mention(spec.option)));
  }
  if (spec.kind == SweepSpec::Kind::rig)
    for (const auto& [value, column, option] :
         {std::tuple{&o.pulley_diameter, "pulley_diameter_mm", "pulley_diameter"},
          std::tuple{&o.belt_width, "belt_width_mm", "belt_width"},
          std::tuple{&o.bulk_density, "bulk_density_kgm3", "bulk_density"}})
      if (*value && spec.column == column)
        throw InputError("", 0, "sweep", fmt::format("{} is swept; leave out {}", spec.column, mention(option)));
  if (spec.kind == SweepSpec::Kind::effect)
    for (const auto& s : res.settings)
      if (s.info == spec.effect)
        throw InputError("", 0, "sweep", fmt::format("{} is swept; leave out {} {}=...", spec.effect->name,
                                                     mention("effect"), spec.effect->name));
  for (double v : spec.values()) {
    EstimateOptions at = o;
    if (spec.kind == SweepSpec::Kind::condition) {
      std::optional<double>* slot = spec.option == "belt_speed"       ? &at.belt_speed
                                    : spec.option == "mass_flow"      ? &at.mass_flow
                                    : spec.option == "plate_distance" ? &at.plate_distance
                                    : spec.option == "plate_top"      ? &at.plate_top
                                                                      : &at.stream_thickness;
      *slot = v;
    }
    // Inputs that are wrong at every point (a missing option, a bad file) stop the sweep.
    Station st = resolve_station(at);
    apply_sweep_value(spec, v, st);
    analytical::EffectList fx = fixed;
    if (spec.kind == SweepSpec::Kind::effect) fx.push_back(spec.effect->make(v));
    SweepRow row{v, std::nullopt, {}, {}, st.plate_top * 1e3,
                 (st.plate_top - st.plate.height * std::cos(st.plate.angle)) * 1e3};
    try {
      // A design with no answer at this point (the stream misses the plate, the load no longer
      // fits the belt) is a result of the sweep, not bad input: the row says why.
      row.point = estimate_point(st, fx);
      if (!row.point->analysis.line(Streamline::korzen_centroid).hit->on_plate)
        row.note = "the centroid meets the plate line off the plate";
      else  // a stream partly over the top edge (or past the foot) loads the plate with less
        row.note = stream_miss_note(analytical::impact_zone(row.point->analysis).caught);
    } catch (const InputError& e) {
      row.note = e.problem();
      row.why = e.field();
    }
    res.rows.push_back(std::move(row));
  }
  if (std::none_of(res.rows.begin(), res.rows.end(), [](const SweepRow& r) { return r.point.has_value(); }))
    throw InputError("", 0, "sweep", fmt::format("no point of the sweep has an answer: {}", res.rows.front().note));
  return res;
}

}  // namespace chutelab::api
