// The report's tables: the reference study's Table 4 (forces) and Table 5 (velocities, impact point) as
// measured vs each model, the per-quantity summary, before/after, and the diagnosis ranking.
// Each table is a list of columns, each column a header and a function from a condition to a cell,
// so the two layouts of the reference study (grouped by source, grouped by quantity) share every cell maker.
#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <functional>

#include "reports/common.h"

namespace chutelab::reports {
namespace {

using validation::ValidationResult;

struct Col {
  Column head;
  std::function<Cell(const ConditionRow&)> cell;
};

Table build(std::string_view id, std::string caption, const Context& c, const std::vector<Col>& cols) {
  Table t;
  t.id = std::string(id);
  t.caption = std::move(caption);
  for (const auto& col : cols) t.columns.push_back(col.head);
  for (const auto& row : c.conditions) {
    std::vector<Cell> cells;
    for (const auto& col : cols) cells.push_back(col.cell(row));
    t.rows.push_back(std::move(cells));
  }
  return t;
}

std::string unit_suffix(std::string_view unit) { return unit.empty() ? "" : fmt::format(" ({})", unit); }

std::string header_html(const QuantityName& qn) {
  return symbol_html(qn.symbol) + esc(unit_suffix(qn.unit));
}

Column quantity_column(const QuantityName& qn, std::string group) {
  return {std::move(group), qn.symbol + unit_suffix(qn.unit), header_html(qn), false};
}

// An error column is only worth its width when the model was compared on that quantity somewhere.
bool compared(const ValidationResult& r, const std::string& model, Quantity q) {
  for (const auto& c : r.comparisons)
    if (c.model == model && c.q == q && c.predicted) return true;
  return false;
}

bool model_predicts(const ValidationResult& r, const std::string& model, Quantity q) {
  for (const auto& p : r.predictions)
    if (p.model == model && p.prediction.values[q]) return true;
  return false;
}

// Display decimals of a quantity: one choice for the whole table, measured and predicted alike,
// so columns line up and equal numbers look equal. Where the measurements state uncertainties,
// the smallest one sets the precision: more digits would be noise, fewer would hide what the
// measurement resolves.
int quantity_decimals(const Context& c, const ValidationResult& r, Quantity q) {
  const double s = info(q).to_boundary;
  double m = 0.0, u_min = 0.0;
  for (const auto& meas : c.in.dataset->measurements)
    if (meas.quantity == q) {
      m = std::max(m, std::abs(meas.value * s));
      if (meas.uncertainty && *meas.uncertainty > 0.0)
        u_min = u_min > 0.0 ? std::min(u_min, *meas.uncertainty * s) : *meas.uncertainty * s;
    }
  if (u_min > 0.0) {
    // One significant digit of the uncertainty, two when it starts with 1 or 2 (0.15 is not 0.2).
    const int first = static_cast<int>(std::floor(std::log10(u_min) + 1e-9));
    const double lead = u_min / std::pow(10.0, first);
    return std::clamp(-first + (lead < 3.0 ? 1 : 0), 0, 4);
  }
  for (const auto& p : r.predictions)
    if (p.prediction.values[q]) m = std::max(m, std::abs(*p.prediction.values[q] * s));
  return decimals_for(m, 4);
}

std::string uncertainty_text(double u, int decimals) {
  // An uncertainty that rounds to zero at the value's precision still gets one significant digit.
  int d = decimals;
  while (d < 6 && u > 0.0 && fixed(u, d).find_first_not_of("0.") == std::string::npos) ++d;
  return fixed(u, d);
}

Col measured_col(const Context& c, Quantity q, int dec, std::string group, bool symbol_header = true) {
  const auto qn = quantity_name(name(q));
  Column head = symbol_header ? quantity_column(qn, std::move(group)) : Column{std::move(group), "measured", "", false};
  return {head, [&c, q, dec, qn](const ConditionRow& row) {
            Cell cell;
            const auto* m = find_measurement(*c.in.dataset, row.name, q);
            if (!m) { cell.text = std::string(kDash); return cell; }
            cell.text = fixed(m->value * qn.scale, dec);
            cell.html = esc(cell.text);
            if (m->uncertainty) {
              const std::string u = uncertainty_text(*m->uncertainty * qn.scale, dec);
              cell.text += " ± " + u;
              cell.html += fmt::format(" <span class=\"u\">± {}</span>", esc(u));
            }
            return cell;
          }};
}

// The tip of a predicted cell says how far off it is; a failing cell says which limit it broke.
void annotate(Cell& cell, const validation::Comparison* cmp, const QuantityName& qn) {
  if (!cmp || !cmp->predicted) return;
  std::string tip = fmt::format("error {:+.3g} {}", cmp->error() * qn.scale, qn.unit);
  if (auto z = cmp->normalised_error()) {
    tip += fmt::format(", E/u_val {:+.2f}", *z);
    cell.beyond = std::abs(*z) > 2.0;
  }
  if (cmp->verdict.checked && !cmp->verdict.passed) {
    cell.fail = true;
    tip = fmt::format("outside tolerance: {} ({})", cmp->verdict.limit, tip);
  }
  cell.tip = tip;
}

Col predicted_col(const Context& c, const ValidationResult& r, const Lookup& look, Quantity q,
                  const std::string& model, int dec, std::string group, bool symbol_header = true) {
  const auto qn = quantity_name(name(q));
  Column head = symbol_header ? quantity_column(qn, std::move(group)) : Column{std::move(group), model, "", false};
  return {head, [&c, &r, &look, q, model, dec, qn](const ConditionRow& row) {
            Cell cell;
            const auto* p = r.prediction(row.name, model);
            if (!p || !p->prediction.values[q]) { cell.text = std::string(kDash); return cell; }
            cell.text = fixed(*p->prediction.values[q] * qn.scale, dec);
            if (p->prediction.uncertainty[q])
              cell.text += " ± " + uncertainty_text(*p->prediction.uncertainty[q] * qn.scale, dec);
            annotate(cell, look.one(row.name, model, qn.name), qn);
            (void)c;
            return cell;
          }};
}

enum class ErrorKind { relative_percent, absolute };

Col error_col(const Lookup& look, Quantity q, const std::string& model, ErrorKind kind, std::string group,
              int dec = 1) {
  const auto qn = quantity_name(name(q));
  return {{std::move(group), model, "", false}, [&look, q, model, kind, qn, dec](const ConditionRow& row) {
            Cell cell;
            const auto* cmp = look.one(row.name, model, std::string(name(q)));
            if (!cmp || !cmp->predicted) { cell.text = std::string(kDash); return cell; }
            if (kind == ErrorKind::relative_percent) {
              const auto rel = cmp->relative_error();
              cell.text = rel ? fmt::format("{:+.1f}", 100.0 * *rel) : std::string(kDash);
            } else {
              const double e = cmp->error() * qn.scale;
              cell.text = fmt::format("{:+.{}f}", e, dec);
              if (cell.text.find_first_not_of("+-0.") == std::string::npos) cell.text = fixed(0.0, dec);
            }
            annotate(cell, cmp, qn);
            return cell;
          }};
}

std::vector<Col> condition_cols() {
  std::vector<Col> cols = {
      {{"condition", "condition", "", true}, [](const ConditionRow& r) { return Cell{r.name, "", false, "", true}; }},
      {{"condition", "V_b (m/s)", "V<sub>b</sub> (m/s)", false},
       [](const ConditionRow& r) {
         return Cell{r.station ? fmt::format("{:.4g}", r.station->belt_speed) : std::string(kDash)};
       }},
      {{"condition", "ṁ (t/h)", "ṁ (t/h)", false},
       [](const ConditionRow& r) {
         return Cell{r.station ? fmt::format("{:.4g}", r.station->mass_flow * 3.6) : std::string(kDash)};
       }},
  };
  for (auto& c : cols) c.head.group_in_markdown = false;
  return cols;
}

std::vector<std::string> models_predicting(const Context& c, const ValidationResult& r,
                                           const std::vector<Quantity>& qs, std::vector<std::string>* left_out) {
  std::vector<std::string> out;
  for (const auto& m : r.models) {
    bool any = false;
    for (Quantity q : qs) any = any || model_predicts(r, m, q);
    if (any) out.push_back(m);
    else if (left_out) left_out->push_back(m);
  }
  (void)c;
  return out;
}

std::string symbols(const std::vector<Quantity>& qs) {
  std::vector<std::string> s;
  for (Quantity q : qs) s.emplace_back(info(q).symbol);
  return fmt::format("{}", fmt::join(s, ", "));
}

}  // namespace

// The reference study's Table 4: plate forces, measured vs each model, with the relative error of R.
Table force_table(const Context& c, const ValidationResult& r, std::string_view id) {
  const Lookup look(r);
  const std::vector<Quantity> qs = {Quantity::normal_force, Quantity::shear_force,
                                                  Quantity::resultant_force};
  std::vector<std::string> left_out;
  const auto models = models_predicting(c, r, qs, &left_out);
  auto cols = condition_cols();
  for (Quantity q : qs) cols.push_back(measured_col(c, q, quantity_decimals(c, r, q), "measured"));
  for (const auto& m : models)
    for (Quantity q : qs) cols.push_back(predicted_col(c, r, look, q, m, quantity_decimals(c, r, q), m));
  for (const auto& m : models)
    if (compared(r, m, Quantity::resultant_force))
      cols.push_back(error_col(look, Quantity::resultant_force, m, ErrorKind::relative_percent, "error of R (%)"));
  Table t = build(id, "Plate forces: measured and predicted (cf. the reference study's Table 4)", c, cols);
  if (!left_out.empty())
    t.notes.push_back(fmt::format("Not shown: {} (predicts none of {}).", fmt::join(left_out, ", "), symbols(qs)));
  t.notes.push_back(fmt::format("Measured values ± one standard deviation. {} = not predicted or not "
                                "measured. Error = (predicted − measured) / |measured|.",
                                kDash));
  return t;
}

// The reference study's Table 5: plate position, stream thickness, velocities and the impact point.
Table velocity_table(const Context& c, const ValidationResult& r, std::string_view id) {
  const Lookup look(r);
  const std::vector<Quantity> qs = {Quantity::impact_velocity, Quantity::exit_velocity,
                                                  Quantity::impact_point_y};
  std::vector<std::string> left_out;
  models_predicting(c, r, qs, &left_out);
  auto cols = condition_cols();
  auto geometry = [&](std::string text, std::string html, std::function<std::string(const Station&)> f) {
    cols.push_back({{"plate and stream", std::move(text), std::move(html), false, {}, false},
                    [f](const ConditionRow& row) {
                      return Cell{row.station ? f(*row.station) : std::string(kDash)};
                    }});
  };
  geometry("Z (mm)", "Z (mm)", [](const Station& s) { return fixed(s.plate_distance * 1e3, 1); });
  geometry("top (mm)", "top (mm)", [](const Station& s) { return fixed(s.plate_top * 1e3, 1); });
  const bool tilted = std::any_of(c.conditions.begin(), c.conditions.end(), [](const ConditionRow& row) {
    return row.station && row.station->plate.angle != 0.0;
  });
  if (tilted)
    geometry("β (deg)", "β (°)", [](const Station& s) { return fixed(s.plate.angle * 180.0 / M_PI, 1); });
  bool continuity = false;
  for (const auto& row : c.conditions) continuity = continuity || (row.station && !row.station->stream_thickness);
  geometry("h_b (mm)", "h<sub>b</sub> (mm)", [](const Station& s) {
    return s.stream_thickness ? fixed(*s.stream_thickness * 1e3, 1) : std::string(kDash);
  });
  for (Quantity q : qs) {
    const auto qn = quantity_name(name(q));
    const std::string group = qn.symbol + unit_suffix(qn.unit);
    const int dec = quantity_decimals(c, r, q);
    cols.push_back(measured_col(c, q, dec, group, false));
    for (const auto& m : r.models)
      if (model_predicts(r, m, q)) cols.push_back(predicted_col(c, r, look, q, m, dec, group, false));
    for (auto& col : cols)
      if (col.head.group == group) col.head.group_html = header_html(qn);
  }
  for (const auto& m : r.models)
    if (compared(r, m, Quantity::impact_point_y)) {
      cols.push_back(error_col(look, Quantity::impact_point_y, m, ErrorKind::absolute, "error of y_R (mm)",
                               quantity_decimals(c, r, Quantity::impact_point_y)));
      cols.back().head.group_html = "error of y<sub>R</sub> (mm)";
    }
  Table t = build(id, "Stream velocities and impact point: measured and predicted (cf. the reference study's Table 5)", c, cols);
  for (const auto& m : r.models)
    for (Quantity q : qs)
      if (!model_predicts(r, m, q))
        t.notes.push_back(fmt::format("{} predicts no {} ({}).", m, info(q).symbol, info(q).label));
  if (continuity) t.notes.push_back(fmt::format("h_b {} = not given; the models take it from continuity.", kDash));
  t.notes.push_back(fmt::format("Z = plate distance from the pulley centre, top = height of its top edge; y_R = height of the point of "
                                "application of R_n; error = predicted − measured; {} = no value.",
                                kDash));
  return t;
}

Table summary_table(const ValidationResult& r, std::string_view id) {
  Table t;
  t.id = std::string(id);
  t.caption = "Summary per model and quantity";
  t.key_columns = 2;
  t.columns = {{"", "model", "", true},
               {"", "quantity", "", true},
               {"", "n", "", false},
               {"", "RMS error", "", false},
               {"", "RMS E/u_val", "RMS <i>E</i>/<i>u</i><sub>val</sub>", false},
               {"", "worst |relative error| (%)", "", false},
               {"", "within tolerance", "", false}};
  for (const auto& s : r.summary) {
    const auto qn = quantity_name(s.quantity);
    std::vector<Cell> row;
    row.push_back({s.model, "", false, "", true});
    row.push_back({fmt::format("{} {}", qn.symbol, qn.label), symbol_html(qn.symbol) + " " + esc(qn.label), false, "", true});
    row.push_back({fmt::format("{}", s.n)});
    row.push_back({std::isfinite(s.rms_error) ? fmt::format("{} {}", fixed(s.rms_error, decimals_for(s.rms_error, 3)), qn.unit)
                                              : std::string(kDash)});
    row.push_back({s.rms_normalised_error ? fixed(*s.rms_normalised_error, decimals_for(*s.rms_normalised_error, 3))
                                          : std::string(kDash)});
    row.push_back({s.max_abs_relative_error && !validation::is_height(s.quantity)
                       ? fixed(100.0 * *s.max_abs_relative_error, 1)
                       : std::string(kDash)});
    Cell tol{s.within_tolerance ? (*s.within_tolerance ? "yes" : "no") : std::string(kDash)};
    if (s.within_tolerance && !*s.within_tolerance) {
      tol.fail = true;
      tol.tip = "at least one value outside its tolerance";
    }
    row.push_back(tol);
    t.rows.push_back(std::move(row));
  }
  t.notes.push_back("E = predicted − measured, u_val = the V&V 20 validation uncertainty (the measurement's, the "
                    "model's numerical and the inputs' combined); |E/u_val| > 2 is more than they explain.");
  if (std::any_of(r.summary.begin(), r.summary.end(), [](const auto& s) { return validation::is_height(s.quantity); }))
    t.notes.push_back("Heights (y_R, the stream boundaries) have no relative error: their zero is the pulley's "
                      "centre, so a per cent of them means nothing; their error is in mm.");
  if (!r.acceptance_checked) t.notes.push_back("No tolerances were set, so no value was checked for acceptance.");
  return t;
}

Table rms_change_table(const Context& c, const ValidationResult& before, const ValidationResult& after) {
  Table t;
  t.id = "rms-change";
  t.caption = "RMS normalised error before and after adding the effects";
  t.columns = {{"", "model", "", true},
               {"", "quantity", "", true},
               {"", "models as they are", "", false},
               {"", "with effects", "", false},
               {"", "change (%)", "", false}};
  auto add = [&](const std::string& model, std::string qtext, std::string qhtml, std::optional<double> b,
                 std::optional<double> a, bool strong) {
    std::vector<Cell> row;
    row.push_back({model, "", false, "", true, strong});
    row.push_back({std::move(qtext), std::move(qhtml), false, "", true, strong});
    row.push_back({b ? fixed(*b, 2) : std::string(kDash), "", false, "", false, strong});
    row.push_back({a ? fixed(*a, 2) : std::string(kDash), "", false, "", false, strong});
    row.push_back({b && a && *b > 0 ? fmt::format("{:+.0f}", 100.0 * (*a / *b - 1.0)) : std::string(kDash), "",
                   false, "", false, strong});
    t.rows.push_back(std::move(row));
  };
  for (const auto& m : c.models) {
    add(m, "all values", "", before.overall_rms_normalised(m), after.overall_rms_normalised(m), true);
    for (const auto& s : before.summary) {
      if (s.model != m) continue;
      std::optional<double> a;
      for (const auto& s2 : after.summary)
        if (s2.model == m && s2.quantity == s.quantity) a = s2.rms_normalised_error;
      const auto qn = quantity_name(s.quantity);
      add(m, fmt::format("{} {}", qn.symbol, qn.label), symbol_html(qn.symbol) + " " + esc(qn.label),
          s.rms_normalised_error, a, false);
    }
  }
  t.notes.push_back("RMS of E/u_val over every compared value with an uncertainty; 1 is what the stated uncertainties alone give.");
  return t;
}

Table effects_table(const std::vector<EffectDescription>& effects) {
  Table t;
  t.id = "effects";
  t.caption = "Effects added to the models";
  t.columns = {{"", "effect", "", true}, {"", "parameter", "", true}, {"", "value", "", false}, {"", "how", "", true}};
  for (const auto& e : effects) {
    std::string v = fmt::format("{:.4g}", e.value);
    if (e.uncertainty) v += fmt::format(" ± {:.2g}", *e.uncertainty);
    if (!e.unit.empty()) v += " " + e.unit;
    t.rows.push_back({{e.name, "", false, "", true, true},
                      {e.parameter, "", false, "", true},
                      {v},
                      {e.fitted ? "fitted to this dataset" : "given", "", false, "", true}});
  }
  return t;
}

// The candidates in engineering words: what each one's fitted strength is, how much of the misfit it
// explains and whether that is beyond chance; the statistics are statistics_table's.
Table ranking_table(const validation::DiagnosisResult& d, bool records) {
  Table t;
  t.id = records ? "ranking-records" : "ranking";
  t.caption = records ? "Recorded inputs as candidates, ranked among all candidates" : "Candidate effects, ranked";
  t.columns = {{"", "rank", "", false},
               {"", records ? "recorded input" : "effect", "", true},
               {"", records ? "error (truth − record) ± sd" : "estimate ± sd", "", true},
               {"", "misfit explained (%)", "", false},
               {"", "beyond chance", "", false}};
  if (records) t.columns.insert(t.columns.begin() + 3, {"", "plausible errors off", "", false});
  auto add = [&](const validation::EffectFit& f, std::string rank) {
    std::vector<std::string> est, off;
    for (std::size_t i = 0; i < f.estimate.size() && i < f.parameters.size(); ++i) {
      est.push_back(fmt::format("{} = {:.4g} ± {}", f.parameters[i], f.estimate[i],
                                i < f.uncertainty.size() && std::isfinite(f.uncertainty[i])
                                    ? fmt::format("{:.2g}", f.uncertainty[i])
                                    : std::string("unconstrained")));
      if (i < f.prior_width.size() && f.prior_width[i] > 0.0)
        off.push_back(fmt::format("{:.1f} ({} {:.3g})", std::abs(f.estimate[i]) / f.prior_width[i],
                                  f.prior_stated[i] ? "stated" : "default", f.prior_width[i]));
    }
    std::vector<Cell> row = {{std::move(rank)},
                             {f.label(), "", false, "", true, f.significant},
                             {fmt::format("{}", fmt::join(est, "; ")), "", false, "", true},
                             {fixed(100.0 * f.explained_fraction, 0)},
                             {f.significant ? "yes" : "no", "", false, "", false, f.significant}};
    if (records) row.insert(row.begin() + 3, Cell{fmt::format("{}", fmt::join(off, "; "))});
    t.rows.push_back(std::move(row));
  };
  for (const auto& f : d.singles)
    if (f.is_record() == records) add(f, fmt::format("{}", f.rank));
  for (const auto& f : d.pairs)
    if (f.is_record() == records) add(f, "pair");
  t.notes.push_back("Misfit explained: the share of the models' misfit beyond what the stated uncertainties allow "
                    "that the candidate removes when fitted. Beyond chance: more than noise would explain, allowing "
                    "for the number of candidates tried (the statistics: \"How sure is this?\").");
  if (records)
    t.notes.push_back("Plausible errors off: the fitted error over the input's plausible error, which is the dataset's "
                      "stated uncertainty of that input or, where none is stated, the input's default.");
  return t;
}

// The statistics behind the ranking, for whoever asks how sure it is: every candidate's chi-square
// after the fit, its fall, delta BIC and the adjusted p.
Table statistics_table(const validation::DiagnosisResult& d) {
  Table t;
  t.id = "ranking-statistics";
  t.caption = "The ranking's statistics";
  t.columns = {{"", "rank", "", false},     {"", "candidate", "", true}, {"", "χ² after", "", false},
               {"", "Δχ²", "", false},      {"", "ΔBIC", "", false},     {"", "explained (%)", "", false},
               {"", "p (adjusted)", "", false}, {"", "significant", "", false}};
  bool any_record = false;
  auto add = [&](const validation::EffectFit& f, std::string rank) {
    any_record = any_record || f.is_record();
    t.rows.push_back({{std::move(rank)},
                      {f.label(), "", false, "", true, f.significant},
                      {fixed(f.chi2_after, 1)},
                      {fixed(f.chi2_before - f.chi2_after, 1)},
                      {fixed(f.delta_bic, 1)},
                      {fixed(100.0 * f.explained_fraction, 0)},
                      {fmt::format("{:.2g}", f.p_adjusted)},
                      {f.significant ? "yes" : "no", "", false, "", false, f.significant}});
  };
  for (const auto& f : d.singles) add(f, fmt::format("{}", f.rank));
  for (const auto& f : d.pairs) add(f, "pair");
  t.notes.push_back("Δχ² = χ² of the models as they are minus χ² with the candidate fitted; explained = Δχ² over the "
                    "misfit beyond noise (χ² as they are minus the smaller of χ² after and its degrees of freedom); "
                    "ΔBIC < 0 favours the candidate; significance after correcting for the number of candidates tried.");
  if (any_record)
    t.notes.push_back("A recorded input's error is charged its implausibility, 2 ln(1 + (error / plausible error)²), "
                      "in ΔBIC and in the test.");
  return t;
}

Table model_notes_table(const Context& c, const ValidationResult& r, std::string_view id) {
  Table t;
  t.id = std::string(id);
  t.caption = "How each model obtained its numbers";
  t.columns.push_back({"", "condition", "", true});
  std::vector<std::string> with_notes;
  for (const auto& m : r.models)
    for (const auto& p : r.predictions)
      if (p.model == m && !p.prediction.notes.empty()) {
        with_notes.push_back(m);
        break;
      }
  for (const auto& m : with_notes) t.columns.push_back({"", m, "", true});
  if (with_notes.empty()) return t;
  for (const auto& row : c.conditions) {
    std::vector<Cell> cells{{row.name, "", false, "", true}};
    for (const auto& m : with_notes) {
      const auto* p = r.prediction(row.name, m);
      cells.push_back({p && !p->prediction.notes.empty() ? fmt::format("{}", fmt::join(p->prediction.notes, "; "))
                                                         : std::string(kDash),
                       "", false, "", true});
    }
    t.rows.push_back(std::move(cells));
  }
  return t;
}

}  // namespace chutelab::reports
