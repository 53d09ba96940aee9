#include <algorithm>
#include <cmath>
#include <fmt/format.h>

#include "reports/log_chart.h"
#include "reports/svg.h"

namespace chutelab::reports {
namespace {

std::string one_chart(const LogChart& c, const std::string& id) {
  constexpr double W = 320.0, H = 218.0;
  Svg svg(W, H, "plot log-chart", id, "The log of " + c.condition);
  svg.title(c.condition);
  const Frame f{52.0, 26.0, W - 64.0, H - 92.0};  // room below for the time axis's title and the legend
  double lo = 0.0, hi = 1.0;
  if (!c.v.empty()) {
    lo = *std::min_element(c.v.begin(), c.v.end());
    hi = *std::max_element(c.v.begin(), c.v.end());
  }
  lo = std::min({lo, c.zero_v0, c.zero_v1});
  hi = std::max({hi, c.zero_v0, c.zero_v1});
  if (hi - lo < 1e-9) hi = lo + 1.0;
  const double t0 = c.t.empty() ? 0.0 : c.t.front(), t1 = c.t.empty() ? 1.0 : std::max(c.t.back(), t0 + 1e-9);
  const Ticks xt = nice_ticks(t0, t1, 5), yt = nice_ticks(lo, hi, 4);
  const Scale X{xt.lo, xt.hi, f.left, f.right()}, Y{yt.lo, yt.hi, f.bottom(), f.top};
  svg.axes(f, X, xt, Y, yt, "time (s)", c.y_label);
  const std::string clip = svg.clip(f);
  svg.rect(X(c.window_start), f.top, X(c.window_end) - X(c.window_start), f.height,
           fmt::format("class=\"log-window\" fill=\"{}\" fill-opacity=\"0.15\" stroke=\"none\"",
                       c.steady ? "#009E73" : "#D55E00"),
           fmt::format("{} window {:.1f}-{:.1f} s", c.steady ? "steady" : "not steady: the averaged", c.window_start,
                       c.window_end));
  std::vector<std::pair<double, double>> pts;
  pts.reserve(c.t.size());
  for (std::size_t k = 0; k < c.t.size() && k < c.v.size(); ++k) pts.emplace_back(X(c.t[k]), Y(c.v[k]));
  svg.polyline(pts, fmt::format("class=\"log-series\" clip-path=\"url(#{})\" stroke=\"#0072B2\" stroke-width=\"0.8\"", clip));
  svg.line(X(c.zero_t0), Y(c.zero_v0), X(c.zero_t1), Y(c.zero_v1),
           "class=\"log-zero\" stroke=\"#444\" stroke-width=\"1.2\" stroke-dasharray=\"4 3\"");
  svg.line(X(c.trend_t0), Y(c.trend_v0), X(c.trend_t1), Y(c.trend_v1),
           "class=\"log-trend\" stroke=\"#CC3311\" stroke-width=\"1.8\"");
  svg.legend(10.0, H - 24.0, W - 20.0,
             {{LegendEntry::Kind::box, "window", c.steady ? "#009E73" : "#D55E00", "", Shape::circle, true, 0.3},
              {LegendEntry::Kind::line, "zero", "#444", "4 3"},
              {LegendEntry::Kind::line, "trend", "#CC3311"}});
  return svg.finish();
}

}  // namespace

std::string log_charts_html(const std::vector<LogChart>& charts, const std::string& id) {
  if (charts.empty()) return {};
  std::string o = fmt::format("<figure id=\"{}\">\n<div class=\"traj-grid\">\n", esc(id));
  for (std::size_t i = 0; i < charts.size(); ++i) o += one_chart(charts[i], fmt::format("{}-{}", id, i));
  o += "</div>\n<figcaption>The plate's load as logged, per condition: the steady window it was averaged over "
       "(shaded; orange where no steady state was found), the zero from the unloaded parts before and after "
       "(dashed) and the trend through the window (red).</figcaption>\n</figure>\n";
  return o;
}

}  // namespace chutelab::reports
