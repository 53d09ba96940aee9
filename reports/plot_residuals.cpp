// Normalised errors E/u per condition and quantity, with the band that measurement noise explains
// (|E/u| <= 2), so a reader sees which model fails where, and whether the failure follows belt
// speed or mass flow (conditions run left to right in that order). The trend table puts a number
// on the second question.
#include <algorithm>
#include <cmath>
#include <fmt/format.h>

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
  for (std::size_t i = 0; i < c.conditions.size(); ++i)
    if (c.conditions[i].name == condition) return i;
  return c.conditions.size();
}

}  // namespace

std::string residual_chart(const Context& c, const validation::ValidationResult& r, std::string_view id) {
  // Panels: every quantity with at least one normalised error.
  struct Panel {
    QuantityName qn;
    std::vector<Point> points;
  };
  std::vector<Panel> panels;
  double worst = 0.0;
  bool any_fail = false;
  for (const auto& qname : compared_quantities(r)) {
    Panel p{quantity_name(qname), {}};
    for (const auto& cmp : r.comparisons) {
      if (cmp.quantity != qname) continue;
      const auto z = cmp.normalised_error();
      const std::size_t slot = slot_of(c, cmp.condition);
      if (!z || slot >= c.conditions.size()) continue;
      std::string tip = fmt::format("{}, {}, {}", cmp.condition, cmp.model, p.qn.symbol);
      if (cmp.boundary) tip += fmt::format(" at x = {:.0f} mm", cmp.x * 1e3);
      tip += fmt::format(": E/u = {:+.2f} (E = {:+.3g} {})", *z, cmp.error() * p.qn.scale, p.qn.unit);
      const bool fail = cmp.verdict.checked && !cmp.verdict.passed;
      if (fail) tip += "; outside tolerance: " + cmp.verdict.limit;
      any_fail = any_fail || fail;
      p.points.push_back({slot, cmp.model, *z, tip, fail});
      worst = std::max(worst, std::abs(*z));
    }
    if (!p.points.empty()) panels.push_back(std::move(p));
  }
  if (panels.empty()) return {};

  // One y range for all panels so that their heights compare; beyond +-10 a value is off the
  // chart whatever it is (the tooltip and the label give it).
  const double L = worst <= 2.8 ? 3.0 : worst <= 4.6 ? 5.0 : 10.0;

  std::vector<std::string> models;
  for (const auto& m : c.models)
    for (const auto& p : panels)
      if (std::any_of(p.points.begin(), p.points.end(), [&](const Point& pt) { return pt.model == m; })) {
        models.push_back(m);
        break;
      }
  std::vector<LegendEntry> legend;
  for (const auto& m : models) legend.push_back({LegendEntry::Kind::marker, m, c.colour(m), "", c.shape(m), true});
  legend.push_back({LegendEntry::Kind::box, "|E/u| ≤ 2 (measurement noise)", std::string(kBandColour)});
  if (worst > L)
    legend.push_back({LegendEntry::Kind::marker, fmt::format("beyond ±{:.0f}: drawn at the edge, value printed", L),
                      "#666", "", Shape::triangle_up, false});
  if (any_fail) legend.push_back({LegendEntry::Kind::marker, "outside tolerance (red ring)", std::string(kFail), "",
                                  Shape::circle, false});

  const double W = 980.0;
  const int cols = panels.size() == 1 ? 1 : 2;
  const double pw = (W - 20.0) / cols;
  const double lh = legend_height(W - 40, legend);
  const double head = 30.0 + lh + 8.0;
  const double ph = 24.0 + 170.0 + 66.0;  // title, plot, three label lines and the axis title
  const std::size_t rows = (panels.size() + cols - 1) / cols;
  const double H = head + ph * static_cast<double>(rows) + 6.0;
  Svg svg(W, H, "plot residual-chart", id, "Normalised errors per condition and quantity");
  svg.title("Normalised error E/u per condition and quantity (E = predicted − measured, u = 1 sd of the measurement)");
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
    svg.y_axis(f, y, yt, "E/u (–)");
    svg.line(f.left, y(0.0), f.right(), y(0.0), "stroke=\"#777\" stroke-width=\"1\"");
    svg.rect(f.left, f.top, f.width, f.height, "fill=\"none\" stroke=\"#444\"");

    const double sw = f.width / static_cast<double>(n);
    const double step = std::min(12.0, 0.7 * sw / static_cast<double>(std::max<std::size_t>(1, models.size())));
    for (std::size_t i = 0; i < n; ++i) {
      const double cx = f.left + sw * (static_cast<double>(i) + 0.5);
      if (i > 0) svg.line(f.left + sw * i, f.bottom(), f.left + sw * i, f.bottom() + 4, "stroke=\"#444\"");
      const auto& row = c.conditions[i];
      const std::size_t fit = static_cast<std::size_t>(std::max(4.0, sw / 6.0));
      svg.text(cx, f.bottom() + 14, shorten(row.name, fit), "middle", "font-size=\"10\" font-weight=\"600\"");
      svg.text(cx, f.bottom() + 26, row.speed_label(), "middle", "font-size=\"10\" fill=\"#333\"");
      svg.text(cx, f.bottom() + 38, row.flow_label(), "middle", "font-size=\"10\" fill=\"#333\"");
    }
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

Table trend_table(const Context& c, const validation::ValidationResult& r, std::string_view id) {
  Table t;
  t.id = std::string(id);
  t.caption = "Does the misfit follow belt speed or mass flow?";
  t.columns = {{"", "model", "", true},
               {"", "quantity", "", true},
               {"", "n", "", false},
               {"", "mean E/u", "mean <i>E</i>/<i>u</i>", false},
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
        else reading.push_back(fmt::format("E/u {} with {}", *rr > 0 ? "rises" : "falls", driver));
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
  t.notes.push_back(fmt::format("r = Pearson correlation of E/u with the operating variable over the "
                                "compared values; |r| ≥ {:.1f} is named, as growing or shrinking when |E/u| follows it too "
                                "(a hint with few conditions, not a test).",
                                kStrong));
  if (const auto rvf = pearson(v, f); rvf && std::abs(*rvf) > 0.5)
    t.notes.push_back(fmt::format("Belt speed and mass flow are correlated in this dataset (r = {:+.2f}): a trend "
                                  "with one may be a trend with the other.",
                                  *rvf));
  return t;
}

}  // namespace chutelab::reports
