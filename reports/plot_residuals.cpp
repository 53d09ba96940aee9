// Normalised errors E/u_val per condition and quantity, with the band the stated uncertainties
// explain (|E/u_val| <= 2), so a reader sees which model fails where, and whether the failure follows belt
// speed or mass flow (conditions run left to right in that order). The trend table puts a number
// on the second question.
#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <map>
#include <tuple>

#include "reports/common.h"

namespace chutelab::reports {
namespace {

constexpr std::string_view kFail = "#c62828";

struct Point {
  std::size_t slot;  // condition index in display order
  std::string model;
  double z;
  std::string tip;
  bool fail;
};

std::optional<double> pearson(const std::vector<double>& a, const std::vector<double>& b) {
  const std::size_t n = a.size();
  if (n < 3) return std::nullopt;
  double ma = 0, mb = 0;
  for (std::size_t i = 0; i < n; ++i) { ma += a[i]; mb += b[i]; }
  ma /= static_cast<double>(n);
  mb /= static_cast<double>(n);
  double sab = 0, saa = 0, sbb = 0;
  for (std::size_t i = 0; i < n; ++i) {
    sab += (a[i] - ma) * (b[i] - mb);
    saa += (a[i] - ma) * (a[i] - ma);
    sbb += (b[i] - mb) * (b[i] - mb);
  }
  // No spread in either variable: no correlation to speak of.
  if (saa <= 1e-12 * (1 + ma * ma) * n || sbb <= 1e-12 * (1 + mb * mb) * n) return std::nullopt;
  return sab / std::sqrt(saa * sbb);
}

std::size_t slot_of(const Context& c, const std::string& condition) {
  const auto it = c.slot.find(condition);
  return it == c.slot.end() ? c.conditions.size() : it->second;
}

// At most this many points of one model are drawn at one condition: a stream boundary measured at
// thousands of x values (a million-row trajectory.csv) would otherwise be a million markers and
// hundreds of MB of report. Beyond it the points drawn are spread evenly over the sorted values
// (the extremes and every failing value among them), each tooltip saying how many there are.
constexpr std::size_t kDrawnPerCondition = 40;

// Every normalised error of one quantity in a result, with its tooltip (summarised as above).
std::vector<Point> points_of(const Context& c, const validation::ValidationResult& r, const std::string& qname,
                             const QuantityName& qn) {
  struct Raw {
    std::size_t slot;
    double z;
    bool fail;
    const validation::Comparison* cmp;
  };
  std::map<std::pair<std::size_t, std::string>, std::vector<Raw>> groups;
  for (const auto& cmp : r.comparisons) {
    if (cmp.quantity != qname) continue;
    const auto z = cmp.normalised_error();
    if (!z) continue;
    const std::size_t slot = slot_of(c, cmp.condition);
    if (slot >= c.conditions.size()) continue;
    groups[{slot, cmp.model}].push_back({slot, *z, cmp.verdict.checked && !cmp.verdict.passed, &cmp});
  }
  std::vector<Point> out;
  for (auto& [key, raw] : groups) {
    std::vector<const Raw*> kept;
    if (raw.size() <= kDrawnPerCondition) {
      for (const auto& x : raw) kept.push_back(&x);
    } else {
      std::stable_sort(raw.begin(), raw.end(), [](const Raw& a, const Raw& b) { return a.z < b.z; });
      for (std::size_t k = 0; k < kDrawnPerCondition; ++k)
        kept.push_back(&raw[k * (raw.size() - 1) / (kDrawnPerCondition - 1)]);
      std::size_t failing = 0;
      for (const auto& x : raw)
        if (x.fail && failing++ < kDrawnPerCondition) kept.push_back(&x);
    }
    for (const Raw* x : kept) {
      const auto& cmp = *x->cmp;
      std::string tip = fmt::format("{}, {}, {}", cmp.condition, cmp.model, qn.symbol);
      if (cmp.boundary) tip += fmt::format(" at x = {:.0f} mm", cmp.x * 1e3);
      tip += fmt::format(": E/u_val = {:+.2f} (E = {:+.3g} {})", x->z, cmp.error() * qn.scale, qn.unit);
      if (x->fail) tip += "; outside tolerance: " + cmp.verdict.limit;
      if (raw.size() > kDrawnPerCondition)
        tip += fmt::format(" (one of {} values here, {} drawn; all in errors.csv)", raw.size(), kDrawnPerCondition);
      out.push_back({x->slot, cmp.model, x->z, tip, x->fail});
    }
  }
  return out;
}

// What charts of the same results share: panels, range, models and legend entries. Two charts of
// a before/after pair drawn from one scale line up panel by panel and their heights compare.
struct ResidualScale {
  std::vector<std::string> quantities;  // panels, in the vocabulary's order
  std::vector<std::string> models;      // those with a point somewhere, in the report's order
  double limit = 3.0;                   // |E/u| at the plot's edge
  bool beyond = false, any_fail = false;
};

ResidualScale residual_scale(const Context& c, const std::vector<const validation::ValidationResult*>& results) {
  ResidualScale sc;
  double worst = 0.0;
  std::vector<std::string> present;
  for (const auto* r : results) {
    if (!r) continue;
    for (const auto& qname : compared_quantities(*r)) {
      const auto pts = points_of(c, *r, qname, quantity_name(qname));
      if (pts.empty()) continue;
      if (std::find(sc.quantities.begin(), sc.quantities.end(), qname) == sc.quantities.end())
        sc.quantities.push_back(qname);
      for (const auto& pt : pts) {
        worst = std::max(worst, std::abs(pt.z));
        sc.any_fail = sc.any_fail || pt.fail;
        if (std::find(present.begin(), present.end(), pt.model) == present.end()) present.push_back(pt.model);
      }
    }
  }
  // A quantity only the second result has goes where the vocabulary puts it.
  std::vector<std::string> order;
  for (const auto* r : results)
    if (r)
      for (const auto& q : compared_quantities(*r))
        if (std::find(order.begin(), order.end(), q) == order.end()) order.push_back(q);
  std::stable_sort(sc.quantities.begin(), sc.quantities.end(), [&](const std::string& a, const std::string& b) {
    return std::find(order.begin(), order.end(), a) < std::find(order.begin(), order.end(), b);
  });
  for (const auto& m : c.models)
    if (std::find(present.begin(), present.end(), m) != present.end()) sc.models.push_back(m);
  // One y range for all panels so that their heights compare; beyond +-10 a value is off the
  // chart whatever it is (the tooltip and the label give it).
  sc.limit = worst <= 2.8 ? 3.0 : worst <= 4.6 ? 5.0 : 10.0;
  sc.beyond = worst > sc.limit;
  return sc;
}

// Condition labels under a categorical axis: name, then belt speed and mass flow when `lines` > 1.
void condition_labels(Svg& svg, const Context& c, const Frame& f, int lines, double font) {
  const std::size_t n = c.conditions.size();
  const double sw = f.width / static_cast<double>(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double cx = f.left + sw * (static_cast<double>(i) + 0.5);
    if (i > 0) svg.line(f.left + sw * i, f.bottom(), f.left + sw * i, f.bottom() + 4, "stroke=\"#444\"");
    const auto& row = c.conditions[i];
    const std::size_t fit = static_cast<std::size_t>(std::max(4.0, sw / (0.6 * font)));
    const std::string size = fmt::format("font-size=\"{:g}\"", font);
    svg.text(cx, f.bottom() + font + 4, shorten(row.name, fit), "middle", size + " font-weight=\"600\"");
    if (lines > 1) {
      svg.text(cx, f.bottom() + 2 * font + 6, shorten(row.speed_label(), fit), "middle", size + " fill=\"#333\"");
      svg.text(cx, f.bottom() + 3 * font + 8, shorten(row.flow_label(), fit), "middle", size + " fill=\"#333\"");
    }
  }
}

}  // namespace

std::string residual_chart(const Context& c, const validation::ValidationResult& r, std::string_view id,
                           double width, const validation::ValidationResult* other) {
  const ResidualScale sc = residual_scale(c, {&r, other});
  if (sc.quantities.empty()) return {};
  struct Panel {
    QuantityName qn;
    std::vector<Point> points;
  };
  std::vector<Panel> panels;
  for (const auto& qname : sc.quantities) {
    Panel p{quantity_name(qname), {}};
    p.points = points_of(c, r, qname, p.qn);
    panels.push_back(std::move(p));
  }
  const double L = sc.limit;
  const auto& models = sc.models;
  std::vector<LegendEntry> legend;
  for (const auto& m : models) legend.push_back({LegendEntry::Kind::marker, m, c.colour(m), "", c.shape(m), true});
  legend.push_back({LegendEntry::Kind::box, "|E/u_val| ≤ 2 (within the uncertainties)", std::string(kBandColour)});
  if (sc.beyond)
    legend.push_back({LegendEntry::Kind::marker, fmt::format("beyond ±{:.0f}: drawn at the edge, value printed", L),
                      "#666", "", Shape::triangle_up, false});
  if (sc.any_fail) legend.push_back({LegendEntry::Kind::marker, "outside tolerance (red ring)", std::string(kFail), "",
                                     Shape::circle, false});

  const double W = width;
  // Side by side, a column is too narrow for two panels of readable conditions: one a row.
  const int cols = panels.size() == 1 || W < 900.0 ? 1 : 2;
  const double pw = (W - 20.0) / cols;
  const double lh = legend_height(W - 40, legend);
  const double head = 30.0 + lh + 8.0;
  const double ph = 24.0 + 170.0 + 66.0;  // title, plot, three label lines and the axis title
  const std::size_t rows = (panels.size() + cols - 1) / cols;
  const double H = head + ph * static_cast<double>(rows) + 6.0;
  Svg svg(W, H, "plot residual-chart", id, "Normalised errors per condition and quantity");
  svg.title(W < 900.0 ? "Normalised error E/u_val per condition and quantity"
                      : "Normalised error E/u_val per condition and quantity (E = predicted − measured, u_val = V&V 20 uncertainty)");
  svg.legend(20.0, 28.0, W - 40, legend);

  const Ticks yt = inner_ticks(-L, L, L > 5 ? 5 : 7);
  const std::size_t n = c.conditions.size();
  for (std::size_t k = 0; k < panels.size(); ++k) {
    const auto& p = panels[k];
    const double ox = 10.0 + pw * static_cast<double>(k % cols);
    const double oy = head + ph * static_cast<double>(k / cols);
    Frame f{ox + 62.0, oy + 24.0, pw - 62.0 - 12.0, 170.0};
    const Scale y{-L, L, f.bottom(), f.top};
    svg.raw(fmt::format("<g class=\"residual-panel\" data-quantity=\"{}\">\n", esc(p.qn.name)));
    svg.markup(f.left, oy + 16, fmt::format("{} — {} ({})", symbol_svg(p.qn.symbol), esc(p.qn.label), esc(p.qn.unit)),
               "start", "font-size=\"12\" font-weight=\"600\"");
    svg.rect(f.left, y(2.0), f.width, y(-2.0) - y(2.0), fmt::format("fill=\"{}\"", kBandColour));
    svg.y_axis(f, y, yt, "E/u_val (–)");
    svg.line(f.left, y(0.0), f.right(), y(0.0), "stroke=\"#777\" stroke-width=\"1\"");
    svg.rect(f.left, f.top, f.width, f.height, "fill=\"none\" stroke=\"#444\"");
    if (p.points.empty())
      svg.text(f.left + f.width / 2, f.top + 20, "no normalised error here", "middle", "font-size=\"11\" fill=\"#666\"");

    const double sw = f.width / static_cast<double>(n);
    const double step = std::min(12.0, 0.7 * sw / static_cast<double>(std::max<std::size_t>(1, models.size())));
    condition_labels(svg, c, f, 3, 10.0);
    svg.text(f.left + f.width / 2, f.bottom() + 56, "condition (belt speed, mass flow)", "middle",
             "class=\"axis-label\" font-size=\"11\"");

    for (std::size_t mi = 0; mi < models.size(); ++mi) {
      const auto& m = models[mi];
      const double dx = (static_cast<double>(mi) - (static_cast<double>(models.size()) - 1.0) / 2.0) * step;
      for (std::size_t i = 0; i < n; ++i) {
        const double cx = f.left + sw * (static_cast<double>(i) + 0.5) + dx;
        std::optional<double> extreme_hi, extreme_lo;
        for (const auto& pt : p.points) {
          if (pt.model != m || pt.slot != i) continue;
          if (pt.z > L) {
            extreme_hi = std::max(extreme_hi.value_or(pt.z), pt.z);
            svg.marker(Shape::triangle_up, cx, f.top + 6, 8, c.colour(m), false, pt.tip);
          } else if (pt.z < -L) {
            extreme_lo = std::min(extreme_lo.value_or(pt.z), pt.z);
            svg.marker(Shape::triangle_down, cx, f.bottom() - 6, 8, c.colour(m), false, pt.tip);
          } else {
            if (pt.fail) svg.marker(Shape::circle, cx, y(pt.z), 12, kFail, false);
            svg.marker(c.shape(m), cx, y(pt.z), 7, c.colour(m), true, pt.tip);
          }
        }
        // Off-scale values are printed (print has no tooltips); several points: the extreme one.
        // Models' labels sit on separate lines so neighbours never overprint.
        auto label = [&](double v) {
          return std::abs(v) >= 10 ? fmt::format("{:.0f}", v) : fmt::format("{:.1f}", v);
        };
        const double line = 10.0 * static_cast<double>(mi);
        if (extreme_hi)
          svg.text(cx, f.top + 20 + line, label(*extreme_hi), "middle",
                   fmt::format("font-size=\"9\" fill=\"{}\" class=\"clip-label\"", c.colour(m)));
        if (extreme_lo)
          svg.text(cx, f.bottom() - 14 - line, label(*extreme_lo), "middle",
                   fmt::format("font-size=\"9\" fill=\"{}\" class=\"clip-label\"", c.colour(m)));
      }
    }
    svg.raw("</g>\n");
  }
  return svg.finish();
}

// The compact picture of what the effects changed, for "What is missing": every normalised error as
// it was (hollow) and with the effects (filled), joined, in small panels on one shared range.
std::string residual_change_chart(const Context& c, const validation::ValidationResult& before,
                                  const validation::ValidationResult& after, std::string_view id) {
  const ResidualScale sc = residual_scale(c, {&before, &after});
  if (sc.quantities.empty() || c.conditions.empty()) return {};
  const double L = sc.limit;
  // The same compared value before and after: same condition, model, quantity and x.
  using Key = std::tuple<std::string, std::string, std::string, long long>;
  auto key = [](const validation::Comparison& cmp) {
    return Key{cmp.condition, cmp.model, cmp.quantity, std::llround(cmp.x * 1e6)};
  };
  std::map<Key, double> z_after;
  for (const auto& cmp : after.comparisons)
    if (const auto z = cmp.normalised_error()) z_after[key(cmp)] = *z;

  std::vector<LegendEntry> legend;
  for (const auto& m : sc.models) legend.push_back({LegendEntry::Kind::marker, m, c.colour(m), "", c.shape(m), true});
  legend.push_back({LegendEntry::Kind::marker, "hollow: models as they are", "#555", "", Shape::circle, false});
  legend.push_back({LegendEntry::Kind::marker, "filled: with effects", "#555", "", Shape::circle, true});
  legend.push_back({LegendEntry::Kind::box, "|E/u_val| ≤ 2", std::string(kBandColour)});
  if (sc.beyond)
    legend.push_back({LegendEntry::Kind::marker, fmt::format("beyond ±{:.0f}: at the edge", L), "#666", "",
                      Shape::triangle_up, false});

  const double W = 980.0;
  const int cols = static_cast<int>(std::min<std::size_t>(3, sc.quantities.size()));
  const double pw = (W - 20.0) / cols;
  const double lh = legend_height(W - 40, legend);
  const double head = 30.0 + lh + 6.0;
  const double ph = 20.0 + 110.0 + 24.0;  // title, plot, one label line
  const std::size_t rows = (sc.quantities.size() + cols - 1) / cols;
  const double H = head + ph * static_cast<double>(rows) + 24.0;
  Svg svg(W, H, "plot residual-change-chart", id, "Normalised errors before and after adding the effects");
  svg.title("Normalised error E/u_val per condition: as the models are (hollow) and with the effects (filled)");
  svg.legend(20.0, 28.0, W - 40, legend);

  const Ticks yt = inner_ticks(-L, L, 5);
  const std::size_t n = c.conditions.size();
  auto at = [&](const Scale& y, const Frame& f, double z) {
    return z > L ? f.top + 5 : z < -L ? f.bottom() - 5 : y(z);
  };
  for (std::size_t k = 0; k < sc.quantities.size(); ++k) {
    const QuantityName qn = quantity_name(sc.quantities[k]);
    const double ox = 10.0 + pw * static_cast<double>(k % static_cast<std::size_t>(cols));
    const double oy = head + ph * static_cast<double>(k / static_cast<std::size_t>(cols));
    Frame f{ox + 50.0, oy + 20.0, pw - 50.0 - 10.0, 110.0};
    const Scale y{-L, L, f.bottom(), f.top};
    svg.raw(fmt::format("<g class=\"residual-change-panel\" data-quantity=\"{}\">\n", esc(qn.name)));
    svg.markup(f.left, oy + 13, fmt::format("{} — {}", symbol_svg(qn.symbol), esc(shorten(qn.label, 34))), "start",
               "font-size=\"11\" font-weight=\"600\"");
    svg.rect(f.left, y(2.0), f.width, y(-2.0) - y(2.0), fmt::format("fill=\"{}\"", kBandColour));
    svg.y_axis(f, y, yt, "E/u_val (–)");
    svg.line(f.left, y(0.0), f.right(), y(0.0), "stroke=\"#777\" stroke-width=\"1\"");
    svg.rect(f.left, f.top, f.width, f.height, "fill=\"none\" stroke=\"#444\"");
    condition_labels(svg, c, f, 1, 9.0);

    const double sw = f.width / static_cast<double>(n);
    const double step = std::min(8.0, 0.7 * sw / static_cast<double>(std::max<std::size_t>(1, sc.models.size())));
    for (std::size_t mi = 0; mi < sc.models.size(); ++mi) {
      const auto& m = sc.models[mi];
      const double dx = (static_cast<double>(mi) - (static_cast<double>(sc.models.size()) - 1.0) / 2.0) * step;
      for (const auto& cmp : before.comparisons) {
        if (cmp.model != m || cmp.quantity != qn.name) continue;
        const auto zb = cmp.normalised_error();
        const std::size_t slot = slot_of(c, cmp.condition);
        if (!zb || slot >= n) continue;
        const double cx = f.left + sw * (static_cast<double>(slot) + 0.5) + dx;
        const auto it = z_after.find(key(cmp));
        std::string tip = fmt::format("{}, {}, {}", cmp.condition, m, qn.symbol);
        if (cmp.boundary) tip += fmt::format(" at x = {:.0f} mm", cmp.x * 1e3);
        tip += fmt::format(": E/u_val {:+.2f}", *zb);
        if (it != z_after.end()) tip += fmt::format(" → {:+.2f} with effects", it->second);
        const double yb = at(y, f, *zb);
        if (it != z_after.end()) {
          const double ya = at(y, f, it->second);
          svg.line(cx, yb, cx, ya, fmt::format("stroke=\"{}\" stroke-width=\"1.2\" stroke-opacity=\"0.55\"", c.colour(m)));
          svg.marker(std::abs(it->second) > L ? (it->second > 0 ? Shape::triangle_up : Shape::triangle_down) : c.shape(m),
                     cx, ya, 5.5, c.colour(m), true, tip);
        }
        svg.marker(std::abs(*zb) > L ? (*zb > 0 ? Shape::triangle_up : Shape::triangle_down) : c.shape(m), cx, yb, 6.5,
                   c.colour(m), false, tip);
      }
    }
    svg.raw("</g>\n");
  }
  svg.text(W / 2, H - 8, "condition, in the order of the tables (belt speed, then mass flow)", "middle",
           "class=\"axis-label\" font-size=\"11\"");
  return svg.finish();
}

Table trend_table(const Context& c, const validation::ValidationResult& r, std::string_view id) {
  Table t;
  t.id = std::string(id);
  t.caption = "Does the misfit follow belt speed or mass flow?";
  t.key_columns = 2;
  t.columns = {{"", "model", "", true},
               {"", "quantity", "", true},
               {"", "n", "", false},
               {"", "mean E/u_val", "mean <i>E</i>/<i>u</i><sub>val</sub>", false},
               {"", "r (belt speed)", "", false},
               {"", "r (mass flow)", "", false},
               {"", "reading", "", true}};
  constexpr double kStrong = 0.7;  // |r| above which a trend is named
  for (const auto& m : r.models)
    for (const auto& qname : compared_quantities(r)) {
      std::vector<double> z, az, v, f;
      for (const auto& cmp : r.comparisons) {
        if (cmp.model != m || cmp.quantity != qname) continue;
        const auto e = cmp.normalised_error();
        const Station* s = c.in.dataset->station(cmp.condition);
        if (!e || !s) continue;
        z.push_back(*e);
        az.push_back(std::abs(*e));
        v.push_back(s->belt_speed);
        f.push_back(s->mass_flow);
      }
      if (z.empty()) continue;
      double mean = 0.0;
      for (double x : z) mean += x;
      mean /= static_cast<double>(z.size());
      const auto rv = pearson(z, v), rf = pearson(z, f);
      // Whether the misfit itself grows: the size |E/u|, not its sign (E/u may cross zero).
      const auto av = pearson(az, v), af = pearson(az, f);
      const auto qn = quantity_name(qname);
      std::vector<std::string> reading;
      const bool biased = std::abs(mean) > 2.0;
      if (biased) reading.push_back(mean > 0 ? "over-predicts" : "under-predicts");
      auto trend = [&](const std::optional<double>& rr, const std::optional<double>& ra, std::string_view driver) {
        if (!rr || std::abs(*rr) < kStrong || z.size() < 4) return;
        if (ra && std::abs(*ra) >= 0.5)
          reading.push_back(fmt::format("misfit {} with {}", *ra > 0 ? "grows" : "shrinks", driver));
        else reading.push_back(fmt::format("E/u_val {} with {}", *rr > 0 ? "rises" : "falls", driver));
      };
      trend(rv, av, "belt speed");
      trend(rf, af, "mass flow");
      auto rcell = [&](const std::optional<double>& rr) {
        Cell cell{rr ? fmt::format("{:+.2f}", *rr) : std::string(kDash)};
        cell.strong = rr && std::abs(*rr) >= kStrong;
        return cell;
      };
      t.rows.push_back({{m, "", false, "", true},
                        {fmt::format("{} {}", qn.symbol, qn.label), symbol_html(qn.symbol) + " " + esc(qn.label),
                         false, "", true},
                        {fmt::format("{}", z.size())},
                        {fmt::format("{:+.2f}", mean), "", false, "", false, biased},
                        rcell(rv),
                        rcell(rf),
                        {reading.empty() ? std::string(kDash) : fmt::format("{}", fmt::join(reading, "; ")), "",
                         false, "", true}});
    }
  // If belt speed and mass flow move together in this dataset, their correlations cannot be told apart.
  std::vector<double> v, f;
  for (const auto& row : c.conditions)
    if (row.station) {
      v.push_back(row.station->belt_speed);
      f.push_back(row.station->mass_flow);
    }
  t.notes.push_back(fmt::format("r = Pearson correlation of E/u_val with the operating variable over the "
                                "compared values; |r| ≥ {:.1f} is named, as growing or shrinking when |E/u_val| follows it too "
                                "(a hint with few conditions, not a test).",
                                kStrong));
  if (const auto rvf = pearson(v, f); rvf && std::abs(*rvf) > 0.5)
    t.notes.push_back(fmt::format("Belt speed and mass flow are correlated in this dataset (r = {:+.2f}): a trend "
                                  "with one may be a trend with the other.",
                                  *rvf));
  return t;
}

}  // namespace chutelab::reports
