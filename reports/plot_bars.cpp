// Bar charts: R per condition (the reference study's Fig. 6), the RMS normalised error before/after adding
// effects, and the diagnosis ranking of candidate effects.
#include <algorithm>
#include <cmath>
#include <fmt/format.h>

#include "reports/common.h"

namespace chutelab::reports {
namespace {

constexpr std::string_view kFail = "#c62828";
constexpr std::string_view kBefore = "#a0a0a0";

struct Bar {
  std::optional<double> value, sd;  // boundary unit
  std::string tip;
  bool fail = false;
};

struct Series {
  std::string label, colour;
  std::vector<Bar> bars;  // one per condition
};

// The measurement, then every model that predicts R anywhere.
std::vector<Series> force_series(const Context& c, const validation::ValidationResult& r) {
  const Quantity q = Quantity::resultant_force;
  const auto qn = quantity_name(name(q));
  const Lookup look(r);
  std::vector<Series> series;
  Series meas{"measured (± 1 sd)", std::string(kMeasuredColour), {}};
  bool any_measured = false;
  for (const auto& row : c.conditions) {
    Bar b;
    if (const auto* m = find_measurement(*c.in.dataset, row.name, q)) {
      b.value = m->value * qn.scale;
      if (m->uncertainty) b.sd = *m->uncertainty * qn.scale;
      b.tip = fmt::format("{}: measured R = {:.4g}{} {}", row.name, *b.value,
                          b.sd ? fmt::format(" ± {:.2g}", *b.sd) : "", qn.unit);
      any_measured = true;
    }
    meas.bars.push_back(b);
  }
  if (any_measured) series.push_back(std::move(meas));
  for (const auto& model : r.models) {
    Series s{model, c.colour(model), {}};
    bool any = false;
    for (const auto& row : c.conditions) {
      Bar b;
      const auto* p = r.prediction(row.name, model);
      if (p && p->prediction.values[q]) {
        any = true;
        b.value = *p->prediction.values[q] * qn.scale;
        if (p->prediction.uncertainty[q]) b.sd = *p->prediction.uncertainty[q] * qn.scale;
        b.tip = fmt::format("{}: {} R = {:.4g} {}", row.name, model, *b.value, qn.unit);
        if (const auto* cmp = look.one(row.name, model, qn.name); cmp && cmp->predicted) {
          if (auto rel = cmp->relative_error()) b.tip += fmt::format(" (error {:+.1f} %)", 100.0 * *rel);
          if (cmp->verdict.checked && !cmp->verdict.passed) {
            b.fail = true;
            b.tip += "; outside tolerance: " + cmp->verdict.limit;
          }
        }
      }
      s.bars.push_back(b);
    }
    if (any) series.push_back(std::move(s));
  }
  return series;
}

double series_top(const std::vector<Series>& series) {
  double top = 0.0;
  for (const auto& s : series)
    for (const auto& b : s.bars)
      if (b.value) top = std::max(top, *b.value + b.sd.value_or(0.0));
  return top;
}

}  // namespace

std::string force_bar_chart(const Context& c, const validation::ValidationResult& r, std::string_view id,
                            double width, const validation::ValidationResult* other) {
  const auto qn = quantity_name(name(Quantity::resultant_force));
  const std::vector<Series> series = force_series(c, r);
  if (series.empty() || c.conditions.empty()) return {};

  bool any_fail = false;
  for (const auto& s : series)
    for (const auto& b : s.bars) any_fail = any_fail || b.fail;
  // A pair shares the force axis: equal bars are equal forces in both.
  const double top = std::max(series_top(series), other ? series_top(force_series(c, *other)) : 0.0);

  std::vector<LegendEntry> legend;
  for (const auto& s : series) legend.push_back({LegendEntry::Kind::box, s.label, s.colour});
  if (any_fail)
    legend.push_back({LegendEntry::Kind::marker, "outside tolerance", std::string(kFail), "", Shape::cross});

  const double W = width;
  const double lh = legend_height(W - 140, legend);
  Frame f{78.0, 30.0 + lh + 10.0, W - 78.0 - 16.0, 260.0};
  const double H = f.bottom() + 72.0;
  Svg svg(W, H, "plot bar-chart", id, "Resultant plate force per condition");
  svg.title(fmt::format("Resultant plate force R per condition: measured and predicted"));
  svg.legend(f.left, 28.0, W - 140, legend);

  const Ticks yt = nice_ticks(0.0, top > 0.0 ? top * 1.04 : 1.0, 6);
  const Scale y{0.0, yt.hi, f.bottom(), f.top};
  svg.y_axis(f, y, yt, fmt::format("{} {} ({})", qn.label, qn.symbol, qn.unit));
  svg.line(f.left, f.bottom(), f.right(), f.bottom(), "stroke=\"#444\"");

  const double gw = f.width / static_cast<double>(c.conditions.size());
  const double bw = std::min(28.0, 0.8 * gw / static_cast<double>(series.size()));
  for (std::size_t i = 0; i < c.conditions.size(); ++i) {
    const double x0 = f.left + gw * (static_cast<double>(i) + 0.5) - bw * series.size() / 2.0;
    for (std::size_t k = 0; k < series.size(); ++k) {
      const Bar& b = series[k].bars[i];
      const double bx = x0 + bw * static_cast<double>(k);
      if (!b.value) {
        svg.text(bx + bw / 2, f.bottom() - 4, kDash, "middle", "font-size=\"10\" fill=\"#888\"");
        continue;
      }
      const double yv = y(std::max(0.0, *b.value));
      svg.rect(bx + 1, yv, bw - 2, f.bottom() - yv,
               fmt::format("fill=\"{}\" class=\"bar\"", series[k].colour), b.tip);
      if (b.sd && *b.sd > 0.0) {
        const double y1 = y(*b.value + *b.sd), y2 = y(std::max(0.0, *b.value - *b.sd));
        const double cx = bx + bw / 2;
        const std::string st = "stroke=\"#000\" stroke-width=\"1.2\"";
        svg.line(cx, y1, cx, y2, st);
        svg.line(cx - 4, y1, cx + 4, y1, st);
        svg.line(cx - 4, y2, cx + 4, y2, st);
      }
      if (b.fail) svg.marker(Shape::cross, bx + bw / 2, yv - 8, 7, kFail, true, b.tip);
    }
    // Two or three label lines: the condition's name, its belt speed and mass flow.
    const auto& row = c.conditions[i];
    const double cx = f.left + gw * (static_cast<double>(i) + 0.5);
    const std::size_t fit = static_cast<std::size_t>(std::max(4.0, gw / 6.6));
    svg.text(cx, f.bottom() + 15, shorten(row.name, fit), "middle", "font-size=\"11\" font-weight=\"600\"");
    svg.text(cx, f.bottom() + 28, row.speed_label(), "middle", "font-size=\"11\" fill=\"#333\"");
    svg.text(cx, f.bottom() + 41, row.flow_label(), "middle", "font-size=\"11\" fill=\"#333\"");
  }
  svg.text(f.left + f.width / 2, f.bottom() + 62, "condition (belt speed V_b, mass flow ṁ)", "middle",
           "class=\"axis-label\" font-size=\"12\"");
  return svg.finish();
}

std::string rms_bar_chart(const Context& c, const validation::ValidationResult& before,
                          const validation::ValidationResult& after, std::string_view id) {
  struct Pair {
    std::string model;
    std::optional<double> b, a;
  };
  std::vector<Pair> pairs;
  double lo = 1e300, hi = 0.0;
  for (const auto& m : c.models) {
    Pair p{m, before.overall_rms_normalised(m), after.overall_rms_normalised(m)};
    if (!p.b && !p.a) continue;
    for (auto v : {p.b, p.a})
      if (v && *v > 0.0) { lo = std::min(lo, *v); hi = std::max(hi, *v); }
    pairs.push_back(p);
  }
  if (pairs.empty() || hi <= 0.0) return {};
  // A fall by more than a factor of 20 would leave the "after" bar invisible on a linear axis.
  const bool log = hi / lo > 20.0;

  std::vector<LegendEntry> legend{{LegendEntry::Kind::box, "models as they are", std::string(kBefore)},
                                  {LegendEntry::Kind::box, "with effects (model colour)", c.colour(pairs.front().model)},
                                  {LegendEntry::Kind::line, "noise level (RMS E/u_val = 1)", "#444", "5 3"}};
  const double W = 620.0;
  const double lh = legend_height(W - 100, legend);
  Frame f{78.0, 30.0 + lh + 10.0, W - 78.0 - 16.0, 220.0};
  const double H = f.bottom() + 56.0;
  Svg svg(W, H, "plot rms-chart", id, "RMS normalised error before and after adding effects");
  svg.title("RMS normalised error per model, before and after");
  svg.legend(f.left, 28.0, W - 100, legend);
  Ticks yt = log ? log_ticks(std::min(lo, 1.0) * 0.9, hi * 1.1) : nice_ticks(0.0, std::max(hi, 1.0) * 1.08, 6);
  const Scale y{log ? yt.lo : 0.0, yt.hi, f.bottom(), f.top, log};
  svg.y_axis(f, y, yt, log ? "RMS E/u_val (–), log scale" : "RMS E/u_val (–)");
  svg.line(f.left, f.bottom(), f.right(), f.bottom(), "stroke=\"#444\"");
  svg.line(f.left, y(1.0), f.right(), y(1.0), "stroke=\"#444\" stroke-dasharray=\"5 3\"");
  const double gw = f.width / static_cast<double>(pairs.size());
  const double bw = std::min(46.0, 0.35 * gw);
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    const double cx = f.left + gw * (static_cast<double>(i) + 0.5);
    auto bar = [&](std::optional<double> v, double x, std::string_view colour, std::string_view what) {
      if (!v) {
        svg.text(x + bw / 2, f.bottom() - 4, kDash, "middle", "font-size=\"10\" fill=\"#888\"");
        return;
      }
      const double yv = y(std::max(*v, log ? yt.lo : 0.0));
      svg.rect(x, yv, bw, f.bottom() - yv, fmt::format("fill=\"{}\" class=\"bar\"", colour),
               fmt::format("{} {}: RMS E/u_val = {:.3g}", pairs[i].model, what, *v));
      svg.text(x + bw / 2, yv - 4, fixed(*v, *v >= 100 ? 0 : 2), "middle", "font-size=\"11\"");
    };
    bar(pairs[i].b, cx - bw - 2, kBefore, "as they are");
    bar(pairs[i].a, cx + 2, c.colour(pairs[i].model), "with effects");
    svg.text(cx, f.bottom() + 16, pairs[i].model, "middle", "font-size=\"12\" font-weight=\"600\"");
  }
  svg.text(f.left + f.width / 2, f.bottom() + 40, "model", "middle", "class=\"axis-label\" font-size=\"12\"");
  return svg.finish();
}

// In engineering words: each candidate's bar is the share of the misfit beyond noise it explains
// when fitted (0-100 %), in colour where it is beyond chance; the statistics behind it (chi-square,
// BIC, p) are the report's "How sure is this?" table, not this chart's.
std::string ranking_chart(const validation::DiagnosisResult& d, std::string_view id) {
  std::vector<const validation::EffectFit*> fits;
  for (const auto& f : d.singles) fits.push_back(&f);
  for (const auto& f : d.pairs) fits.push_back(&f);
  if (fits.empty()) return {};
  const auto* best = d.best();
  double label_w = 0.0;
  for (const auto* f : fits) label_w = std::max(label_w, text_width(f->label(), 12));
  std::vector<LegendEntry> legend{{LegendEntry::Kind::box, "beyond chance", "#0072B2"},
                                  {LegendEntry::Kind::box, "could be chance", "#c4c4c4"}};
  if (best) legend.push_back({LegendEntry::Kind::box, "recommended", "#D55E00"});
  const double W = 960.0, row = 24.0;
  const double lh = legend_height(W - 40, legend);
  const double left = std::min(340.0, label_w + 24.0);
  const double value_room = 190.0;  // right of the longest bar: the value text
  Frame f{left, 30.0 + lh + 10.0, W - left - value_room, row * static_cast<double>(fits.size())};
  const double H = f.bottom() + 44.0;
  Svg svg(W, H, "plot ranking-chart", id, "Ranking of candidate effects");
  svg.title("How much of the misfit each candidate effect explains");
  svg.legend(f.left, 28.0, W - 40, legend);
  const Scale x{0.0, 100.0, f.left, f.right()};
  for (double v = 0.0; v <= 100.0; v += 20.0) {
    svg.line(x(v), f.top, x(v), f.bottom(), "stroke=\"#e2e2e2\"");
    svg.line(x(v), f.bottom(), x(v), f.bottom() + 4, "stroke=\"#444\"");
    svg.text(x(v), f.bottom() + 16, fmt::format("{:.0f}", v), "middle", "font-size=\"11\" fill=\"#333\"");
  }
  svg.line(f.left, f.top, f.left, f.bottom(), "stroke=\"#444\"");
  svg.line(f.left, f.bottom(), f.right(), f.bottom(), "stroke=\"#444\"");
  for (std::size_t i = 0; i < fits.size(); ++i) {
    const auto* fit = fits[i];
    const double yy = f.top + row * static_cast<double>(i);
    const double pct = 100.0 * std::clamp(fit->explained_fraction, 0.0, 1.0);
    const std::string colour = fit == best ? "#D55E00" : fit->significant ? "#0072B2" : "#c4c4c4";
    const std::string verdict = fit == best ? "recommended" : fit->significant ? "beyond chance" : "could be chance";
    std::vector<std::string> est;
    for (std::size_t k = 0; k < fit->estimate.size() && k < fit->parameters.size(); ++k)
      est.push_back(fmt::format("{} = {:.3g}", fit->parameters[k], fit->estimate[k]));
    const std::string tip = fmt::format("{}: explains {:.0f} % of the misfit beyond noise ({}){}", fit->label(), pct,
                                        verdict, est.empty() ? "" : fmt::format(", at {}", fmt::join(est, ", ")));
    svg.text(f.left - 8, yy + row / 2 + 4, shorten(fit->label(), 52), "end",
             fit->significant ? "font-size=\"12\" font-weight=\"600\"" : "font-size=\"12\" fill=\"#555\"");
    svg.rect(f.left, yy + 4, x(pct) - f.left, row - 8, fmt::format("fill=\"{}\" class=\"bar\"", colour), tip);
    svg.text(x(pct) + 6, yy + row / 2 + 4, fmt::format("{:.0f} % explained", pct), "start",
             "font-size=\"11\" fill=\"#333\"");
  }
  svg.text(f.left + f.width / 2, f.bottom() + 34, "share of the misfit beyond noise explained with the effect fitted (%)",
           "middle", "class=\"axis-label\" font-size=\"12\"");
  return svg.finish();
}

}  // namespace chutelab::reports
