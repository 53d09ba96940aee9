// The slump-test calibration chart (reference study Table 3 as pictures): pile height and bulk density against
// rolling friction, one line per (particle, solid density), targets dashed.
#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "reports/studies.h"

namespace chutelab::reports {

std::string calibration_chart(const std::vector<studies::CalibrationPoint>& points, const CalibrationTargetsView& targets,
                              std::string_view id) {
  const std::vector<std::string> palette = {"#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#8c564b"};
  struct Series {
    std::string grain;
    double density;
    std::string label, colour;
    Shape shape;
    std::vector<std::pair<double, double>> height, bulk;
  };
  // Series in the order their first point appears (the calibrate command's Table 3 order).
  std::vector<Series> series;
  for (const auto& p : points) {
    auto it = std::find_if(series.begin(), series.end(),
                           [&](const Series& s) { return s.grain == p.grain && s.density == p.solid_density; });
    if (it == series.end()) {
      series.push_back({p.grain, p.solid_density, fmt::format("{}, rho_s {:g}", p.grain, p.solid_density),
                        palette[series.size() % palette.size()], p.shape == "clump" ? Shape::square : Shape::circle,
                        {}, {}});
      it = series.end() - 1;
    }
    it->height.emplace_back(p.rolling_friction, p.pile_height * 1e3);
    it->bulk.emplace_back(p.rolling_friction, p.bulk_density);
  }
  for (auto& s : series) {
    std::sort(s.height.begin(), s.height.end());
    std::sort(s.bulk.begin(), s.bulk.end());
  }
  double rlo = 1e300, rhi = -1e300, hmax = 0, blo = 1e300, bhi = -1e300;
  for (const auto& p : points) {
    rlo = std::min(rlo, p.rolling_friction);
    rhi = std::max(rhi, p.rolling_friction);
    hmax = std::max(hmax, p.pile_height * 1e3);
    blo = std::min(blo, p.bulk_density);
    bhi = std::max(bhi, p.bulk_density);
  }
  if (points.empty()) rlo = 0.0, rhi = 0.1, hmax = 1.0, blo = 0.0, bhi = 1.0;
  if (targets.pile_height) hmax = std::max(hmax, *targets.pile_height * 1e3);
  if (targets.bulk_density) {
    blo = std::min(blo, *targets.bulk_density);
    bhi = std::max(bhi, *targets.bulk_density);
  }
  if (rhi <= rlo) rhi = rlo + 0.1;
  std::vector<LegendEntry> legend;
  for (const auto& se : series) legend.push_back({LegendEntry::Kind::marker, se.label, se.colour, "", se.shape});
  if (targets.bulk_density || targets.pile_height)
    legend.push_back({LegendEntry::Kind::line, "target (measured)", "#000", "5,4"});
  const double W = 960, lh = legend_height(W - 40, legend);
  Svg svg(W, 80 + lh + 300, "plot calibration", id, "Pile height and bulk density against rolling friction");
  svg.title("Slump tests: pile height and loose-poured bulk density against rolling friction");
  svg.legend(20, 28, W - 40, legend);
  auto panel = [&](double left, const std::string& ylabel, double ylo, double yhi, bool height,
                   std::optional<double> target) {
    Frame f{left, 40 + lh + 10, 380, 250};
    const Ticks xt = nice_ticks(rlo, rhi, 5), yt = nice_ticks(ylo, yhi, 6);
    const Scale x{xt.lo, xt.hi, f.left, f.right()}, y{yt.lo, yt.hi, f.bottom(), f.top};
    svg.axes(f, x, xt, y, yt, "rolling friction mu_r", ylabel);
    if (target) svg.line(f.left, y(*target), f.right(), y(*target), "stroke=\"#000\" stroke-dasharray=\"5,4\"");
    for (const auto& se : series) {
      const auto& pts = height ? se.height : se.bulk;
      std::vector<std::pair<double, double>> line;
      for (const auto& [a, b] : pts) line.emplace_back(x(a), y(b));
      svg.polyline(line, fmt::format("fill=\"none\" stroke=\"{}\" stroke-width=\"1.5\"", se.colour));
      for (const auto& [a, b] : pts)
        svg.marker(se.shape, x(a), y(b), 7, se.colour, true,
                   fmt::format("{}: mu_r {:g}, {} {:.1f}", se.label, a, height ? "pile height (mm)" : "bulk density (kg/m^3)", b));
    }
  };
  panel(80, "pile height (mm)", 0.0, hmax * 1.1, true,
        targets.pile_height ? std::optional<double>(*targets.pile_height * 1e3) : std::nullopt);
  panel(560, "bulk density (kg/m^3)", blo - 0.03 * blo, bhi + 0.03 * bhi, false, targets.bulk_density);
  return svg.finish();
}

}  // namespace chutelab::reports
