// The report's V&V 20 section: per prediction, the comparison error and the parts of the
// validation uncertainty (u_D, u_num's statistical and discretisation parts, u_input), u_val and
// |E|/u_val; and, in words, which parts were not estimated and why.
#include <cmath>
#include <fmt/format.h>
#include <map>
#include <string_view>
#include <tuple>

#include "reports/common.h"

namespace chutelab::reports {

using validation::Comparison;
using validation::ValidationResult;

namespace {

bool any_input_stated(const validation::Dataset& d) {
  for (const auto& u : d.input_uncertainty)
    if (!u.empty()) return true;
  return false;
}

bool is_expensive(const std::string& model) {
  try {
    return validation::make_model(model)->expensive();
  } catch (...) {
    return false;  // a model outside the registry (a test's stand-in): say nothing about it
  }
}

}  // namespace

std::vector<std::string> vv20_not_estimated(const validation::Dataset& d, const ValidationResult& r) {
  std::vector<std::string> out;
  int missing_input = 0, predicted = 0;
  for (const auto& c : r.comparisons)
    if (c.predicted) {
      ++predicted;
      if (!c.u_input) ++missing_input;
    }
  if (!any_input_stated(d))
    out.push_back("u_input not estimated: the dataset states no input uncertainties (conditions.csv "
                  "*_uncertainty_* columns, setup.toml [uncertainty]).");
  else if (missing_input > 0)
    out.push_back(fmt::format("u_input not estimated for {} of {} predicted values (the model notes say why).",
                              missing_input, predicted));
  for (const auto& m : r.models) {
    bool stat = false, disc = false, any = false;
    for (const auto& c : r.comparisons)
      if (c.model == m && c.predicted) {
        any = true;
        stat = stat || c.u_num_stat().has_value();
        disc = disc || c.u_num_disc.has_value();
      }
    if (!any) continue;
    if (!stat && !disc && !is_expensive(m)) {
      out.push_back(fmt::format("{}: u_num taken as 0 (a cheap deterministic model: no sampling error, and "
                                "a numerical error far below the data's).", m));
      continue;
    }
    if (!stat) out.push_back(fmt::format("{}: u_num statistical part not estimated.", m));
    if (!disc) out.push_back(fmt::format("{}: u_num discretisation part not estimated: no ladder runs.", m));
  }
  return out;
}

// One row per predicted value; a condition's trajectory points on one boundary share a row, with
// the RMS of each part over the points (they are many, and alike).
Table vv20_table(const Context& c, const ValidationResult& r, std::string_view id) {
  Table t;
  t.id = std::string(id);
  t.caption = "Validation uncertainty per prediction (ASME V&V 20)";
  t.key_columns = 3;
  t.columns = {{"", "condition", "", true},
               {"", "model", "", true},
               {"", "quantity", "", true},
               {"", "E", "<i>E</i>", false},
               {"", "u_D", "<i>u</i><sub>D</sub>", false},
               {"", "u_num stat", "<i>u</i><sub>num</sub> stat", false},
               {"", "u_num disc", "<i>u</i><sub>num</sub> disc", false},
               {"", "u_input", "<i>u</i><sub>input</sub>", false},
               {"", "u_val", "<i>u</i><sub>val</sub>", false},
               {"", "|E|/u_val", "|<i>E</i>|/<i>u</i><sub>val</sub>", false}};
  std::vector<std::string> quantities;
  for (Quantity q : kAllQuantities) quantities.emplace_back(name(q));
  for (Boundary b : kAllBoundaries) quantities.push_back(trajectory_quantity(b));
  // Grouped in one pass (a scan per row made 10 000 conditions take minutes), shown conditions only.
  std::map<std::tuple<std::string_view, std::string_view, std::string_view>, std::vector<const Comparison*>> groups;
  for (const auto& cmp : r.comparisons)
    if (cmp.predicted && c.slot.count(cmp.condition)) groups[{cmp.condition, cmp.model, cmp.quantity}].push_back(&cmp);
  for (const auto& row : c.conditions)
    for (const auto& m : r.models)
      for (const auto& qname : quantities) {
        const auto git = groups.find({row.name, m, qname});
        if (git == groups.end()) continue;
        const std::vector<const Comparison*>& group = git->second;
        const auto qn = quantity_name(qname);
        // RMS over the group of one part; none when no member has it.
        auto rms = [&](auto part) -> std::optional<double> {
          double sum = 0.0;
          int n = 0;
          for (const auto* g : group)
            if (const std::optional<double> v = part(*g)) {
              sum += *v * *v;
              ++n;
            }
          if (n == 0) return std::nullopt;
          return std::sqrt(sum / n);
        };
        // E keeps its sign for one value; a group of stream points shows its RMS.
        const auto e = group.size() == 1 ? std::optional<double>(group[0]->error())
                                         : rms([](const Comparison& g) { return std::optional<double>(g.error()); });
        const auto ud = rms([](const Comparison& g) { return g.uncertainty; });
        const auto us = rms([](const Comparison& g) { return g.u_num_stat(); });
        const auto un = rms([](const Comparison& g) { return g.u_num_disc; });
        const auto ui = rms([](const Comparison& g) { return g.u_input; });
        const auto uv = rms([](const Comparison& g) { return g.validation_uncertainty(); });
        const auto ratio = rms([](const Comparison& g) { return g.vv20_ratio(); });  // RMS over a group
        const double scale = qn.scale;
        double biggest = 0.0;
        for (const auto& v : {e, ud, us, un, ui, uv})
          if (v) biggest = std::max(biggest, std::abs(*v * scale));
        const int dec = decimals_for(biggest, 3);
        auto cell = [&](const std::optional<double>& v) {
          return Cell{v ? fixed(*v * scale, dec) : std::string(kDash)};
        };
        std::string label = qn.symbol + (qn.unit.empty() ? "" : " (" + qn.unit + ")");
        std::string html = symbol_html(qn.symbol) + esc(qn.unit.empty() ? "" : " (" + qn.unit + ")");
        if (group.size() > 1) {
          label += fmt::format(", RMS of {} points", group.size());
          html += esc(fmt::format(", RMS of {} points", group.size()));
        } else if (group[0]->boundary) {
          label += fmt::format(" at x = {:.0f} mm", group[0]->x * 1e3);
          html += esc(fmt::format(" at x = {:.0f} mm", group[0]->x * 1e3));
        }
        std::vector<Cell> cells{{row.name, "", false, "", true}, {m, "", false, "", true}, {label, html, false, "", true},
                                cell(e), cell(ud), cell(us), cell(un), cell(ui), cell(uv)};
        Cell rc{ratio ? fixed(*ratio, 2) : std::string(kDash)};
        if (ratio && *ratio > 2.0) rc.tip = "|E| more than twice the validation uncertainty";
        cells.push_back(rc);
        t.rows.push_back(std::move(cells));
      }
  t.notes.push_back("E = S − D; u_val = sqrt(u_D² + u_num,stat² + u_num,disc² + u_input²), each a standard "
                    "uncertainty in the quantity's unit; a part not estimated (—) counts as 0.");
  t.notes.push_back("u_input: sensitivity coefficients by central differences at ± each input's uncertainty, "
                    "inputs independent; an expensive model (DEM) takes the cheap models' coefficients — "
                    "absolute for positions, relative (elasticities) for forces and speeds.");
  return t;
}

}  // namespace chutelab::reports
