// A sweep over one input: where the stream meets the plate (top panel) and the plate forces
// (bottom panel) against the swept value, on a shared x axis, with the current design marked.
#include <algorithm>
#include <cmath>
#include <fmt/format.h>

#include "reports/design.h"
#include "reports/svg.h"

namespace chutelab::reports {
namespace {

// The top panel shows the plate's extent, the bottom one starts at 0 N (a force near zero must look
// near zero, not like the bottom of the chart).
void panel(Svg& svg, const Frame& f, const SweepChart& c, const std::vector<SweepSeries>& series,
           std::string_view ylabel, std::string_view cls, bool x_labels, bool forces) {
  double lo = 1e300, hi = -1e300;
  for (const auto& s : series)
    for (const auto& y : s.y)
      if (y && std::isfinite(*y)) { lo = std::min(lo, *y); hi = std::max(hi, *y); }
  if (lo > hi) { lo = 0.0; hi = 1.0; }
  if (forces) lo = std::min(lo, 0.0), hi = std::max(hi, 0.0);
  if (!forces) {
    // The plate in view, with a margin of a tenth of the impact points' spread.
    const double pad = 0.1 * (hi - lo);
    for (std::size_t i = 0; i < c.x.size(); ++i) {
      if (i < c.plate_top_mm.size() && c.plate_top_mm[i]) hi = std::max(hi, std::min(*c.plate_top_mm[i], hi + pad + 1.0));
      if (i < c.plate_bottom_mm.size() && c.plate_bottom_mm[i])
        lo = std::min(lo, std::max(*c.plate_bottom_mm[i], lo - pad - 1.0));
    }
  }
  if (hi - lo < 1e-9 * std::max(1.0, std::abs(hi))) { lo -= 1.0; hi += 1.0; }
  const Ticks xt = nice_ticks(c.x.front(), c.x.back() == c.x.front() ? c.x.front() + 1.0 : c.x.back());
  const Ticks yt = nice_ticks(lo, hi, 5);
  const Scale X{xt.lo, xt.hi, f.left, f.right()}, Y{yt.lo, yt.hi, f.bottom(), f.top};
  svg.axes(f, X, xt, Y, yt, x_labels ? std::string_view(c.x_label) : std::string_view(), ylabel);
  // The x scale for a page that marks its current design on the chart.
  svg.raw(fmt::format("<g class=\"x-scale\" data-d0=\"{}\" data-d1=\"{}\" data-r0=\"{}\" data-r1=\"{}\" "
                      "data-top=\"{}\" data-bottom=\"{}\" data-y0=\"{}\" data-y1=\"{}\"></g>\n",
                      xt.lo, xt.hi, px(f.left), px(f.right()), px(f.top), px(f.bottom()), yt.lo, yt.hi));
  const std::string clip = svg.clip(f);
  if (!forces && c.plate_top_mm.size() == c.x.size()) {
    // The plate face as a shaded band between its edges (a polygon: a swept plate_top moves it).
    std::string upper, lower;
    for (std::size_t i = 0; i < c.x.size(); ++i)
      if (c.plate_top_mm[i] && c.plate_bottom_mm[i]) {
        upper += fmt::format("{},{} ", px(X(c.x[i])), px(Y(*c.plate_top_mm[i])));
        lower = fmt::format("{},{} ", px(X(c.x[i])), px(Y(*c.plate_bottom_mm[i]))) + lower;
      }
    if (!upper.empty())
      svg.raw(fmt::format("<polygon class=\"plate-extent\" clip-path=\"url(#{})\" points=\"{}{}\" fill=\"#888\" "
                          "fill-opacity=\"0.13\" stroke=\"#888\" stroke-dasharray=\"3 3\"><title>the plate face, top to "
                          "bottom edge</title></polygon>\n",
                          clip, upper, lower));
    svg.text(f.right() - 6, f.top + 14, "shaded: the plate face", "end", "font-size=\"11\" fill=\"#555\"");
  }
  // Runs of points without an answer, and of points where part of the stream misses the plate: one
  // band each, from half a step before to half a step after.
  auto bands = [&](const std::vector<std::string>& label, const std::vector<std::string>& reason,
                   std::string_view cls, std::string_view fill, std::string_view opacity, std::string_view ink) {
    if (label.size() != c.x.size()) return;
    for (std::size_t i = 0; i < c.x.size();) {
      if (label[i].empty()) { ++i; continue; }
      std::size_t j = i;
      while (j + 1 < c.x.size() && label[j + 1] == label[i]) ++j;
      const double half = c.x.size() > 1 ? 0.5 * std::abs(c.x[1] - c.x[0]) : 0.5;
      const double a = std::max(X(std::min(c.x[i], c.x[j]) - half), f.left);
      const double b = std::min(X(std::max(c.x[i], c.x[j]) + half), f.right());
      // A run's tooltip: its first point's reason, and the last's when they differ.
      std::string tip = reason.size() > i ? reason[i] : std::string();
      if (j != i && reason.size() > j && reason[j] != reason[i]) tip += " ... " + reason[j];
      svg.rect(a, f.top, b - a, f.height,
               fmt::format("class=\"{}\" fill=\"{}\" fill-opacity=\"{}\" stroke=\"none\"", cls, fill, opacity), tip);
      svg.text(0.5 * (a + b), f.top + 30, label[i], "middle",
               fmt::format("class=\"{}-label\" font-size=\"11\" fill=\"{}\"", cls, ink));
      i = j + 1;
    }
  };
  bands(c.gap_label, c.gap_reason, "no-answer", "#d62728", "0.08", "#a33");
  bands(c.partial_label, c.partial_reason, "overshoot-band", "#f2c230", "0.25", "#7a5c00");
  svg.raw(fmt::format("<g class=\"{}\">\n", cls));
  for (const auto& s : series) {
    // Gaps where a point has no answer: one polyline per run of answered points.
    std::vector<std::pair<double, double>> run;
    auto flush = [&] {
      if (run.size() > 1)
        svg.polyline(run, fmt::format("class=\"series\" stroke=\"{}\" stroke-width=\"2\"{}", s.colour,
                                      s.dash.empty() ? "" : fmt::format(" stroke-dasharray=\"{}\"", s.dash)));
      run.clear();
    };
    for (std::size_t i = 0; i < c.x.size() && i < s.y.size(); ++i) {
      if (!s.y[i] || !std::isfinite(*s.y[i])) { flush(); continue; }
      run.emplace_back(X(c.x[i]), Y(*s.y[i]));
      svg.marker(Shape::circle, X(c.x[i]), Y(*s.y[i]), 4, s.colour, true,
                 fmt::format("{}: {} at {}", s.label, fixed(*s.y[i], decimals_for(std::abs(*s.y[i]))),
                             fixed(c.x[i], decimals_for(std::abs(c.x[i])))));
    }
    flush();
  }
  svg.raw("</g>\n");
}

}  // namespace

std::string sweep_svg(const SweepChart& c, std::string_view id) {
  const double W = 980.0, panel_h = 200.0;
  std::vector<LegendEntry> top, bottom;
  for (const auto& s : c.impact_mm) top.push_back({LegendEntry::Kind::line, s.label, s.colour, s.dash});
  for (const auto& s : c.forces_N) bottom.push_back({LegendEntry::Kind::line, s.label, s.colour, s.dash});
  const double left = 70.0, width = W - left - 20.0;
  const double lt = legend_height(width, top), lb = legend_height(width, bottom);
  const Frame f1{left, 34.0 + lt + 6.0, width, panel_h};
  const Frame f2{left, f1.bottom() + 24.0 + lb + 6.0, width, panel_h};
  const bool partial = std::any_of(c.partial_label.begin(), c.partial_label.end(), [](const auto& l) { return !l.empty(); });
  const double H = f2.bottom() + (partial ? 80.0 : 48.0);
  Svg svg(W, H, "plot sweep-chart", id, "impact point and plate forces against " + c.x_label);
  svg.title("Impact point and plate forces against " + c.x_label);
  if (c.x.empty()) return svg.finish();
  svg.legend(left, 30.0, width, top);
  panel(svg, f1, c, c.impact_mm, "y on the plate (mm)", "impact-series", false, false);
  svg.legend(left, f1.bottom() + 24.0, width, bottom);
  panel(svg, f2, c, c.forces_N, "force on the plate (N)", "force-series", true, true);
  if (partial) {
    svg.text(left, f2.bottom() + 54.0,
             "Banded in yellow: part of the stream passes over the plate's top edge or falls past its foot;", "start",
             "class=\"overshoot-note\" font-size=\"11\" fill=\"#7a5c00\"");
    svg.text(left, f2.bottom() + 68.0,
             "the forces drawn are the whole stream's, the plate takes less there (the band's tooltip says how much).",
             "start", "class=\"overshoot-note\" font-size=\"11\" fill=\"#7a5c00\"");
  }
  return svg.finish();
}

std::string standalone_svg(std::string_view inline_svg) {
  std::string s(inline_svg);
  if (s.starts_with("<svg ")) s.insert(5, "xmlns=\"http://www.w3.org/2000/svg\" ");
  return "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n" + s;
}

}  // namespace chutelab::reports
