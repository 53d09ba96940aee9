// "Plate loading and wear": the pressure and wear maps a model gives of the plate face (the DEM's,
// per triangle of the plate mesh) as heat maps, one panel per condition on one colour scale per
// quantity, with the analytical impact zone (another model's PlateZone) drawn on top, and a table
// of peak and mean values per condition. The report knows no physics: it draws what the
// predictions carry.
#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "reports/common.h"

namespace chutelab::reports {
namespace {

using validation::PlateZone;
using validation::SurfaceMap;

constexpr double kUmPerHour = 1e6 * 3600.0;
constexpr double kKpa = 1e-3;  // Pa -> kPa: a plate's pressures are kPa, which "4.26e+03 Pa" hides

// A colour bar's label: three significant digits of the bar's top, fixed notation ("4.26", "0.0312").
std::string bar_label(double v, double top) {
  const int mag = top > 0.0 && std::isfinite(top) ? static_cast<int>(std::floor(std::log10(top))) : 0;
  return fixed(v, std::clamp(2 - mag, 0, 8));
}

struct Panel {
  std::string condition, model;
  const SurfaceMap* map = nullptr;
  std::optional<PlateZone> zone;
  std::string zone_model;
  std::optional<double> impact_point;  // the map's model's own y_R, m
};

std::size_t bin(double v, double hi) {
  const double t = hi > 0.0 ? v / hi : 0.0;
  return static_cast<std::size_t>(std::clamp(t * kRamp.size(), 0.0, kRamp.size() - 1.0));
}

std::string heat_map(const std::vector<Panel>& panels, bool wear, std::string_view id, double width) {
  double hi = 0.0;
  double z0 = 1e9, z1 = -1e9, y0 = 1e9, y1 = -1e9;
  for (const auto& p : panels) {
    const auto& v = wear ? p.map->wear_rate : p.map->pressure;
    for (double x : v) hi = std::max(hi, x);
    for (const auto& c : p.map->cells)
      for (const auto& q : c) z0 = std::min(z0, q.x()), z1 = std::max(z1, q.x()), y0 = std::min(y0, q.y()), y1 = std::max(y1, q.y());
  }
  if (!(z1 > z0) || !(y1 > y0)) return {};
  const int cols = std::min<int>(4, static_cast<int>(panels.size()));
  const int rows = (static_cast<int>(panels.size()) + cols - 1) / cols;
  // Each panel has its own mm axes (y up the face on the left, z across it below).
  const double gap = 18.0, left = 46.0, below = 26.0, pw = (width - gap * (cols + 1) - left * cols) / cols;
  const double k = pw / (z1 - z0), ph = (y1 - y0) * k;  // equal scales: the plate face as it is
  const double head = 20.0, bar = 50.0, cell_h = ph + head + below + gap;
  const Ticks zt = inner_ticks(z0 * 1e3, z1 * 1e3, std::max(2, static_cast<int>(pw / 60.0)));
  const Ticks yt = inner_ticks(y0 * 1e3, y1 * 1e3, std::max(2, static_cast<int>(ph / 40.0)));
  Svg svg(width, rows * cell_h + bar + gap, "plate-map", id,
          wear ? "wear rate maps of the plate" : "pressure maps of the plate");
  for (std::size_t n = 0; n < panels.size(); ++n) {
    const Panel& p = panels[n];
    const double ox = gap + left + static_cast<double>(n % cols) * (pw + gap + left);
    const double oy = gap + static_cast<double>(n / cols) * cell_h + head;
    auto X = [&](double z) { return ox + (z - z0) * k; };
    auto Y = [&](double y) { return oy + (y1 - y) * k; };
    svg.text(ox - left, oy - 6, p.condition + " (" + p.model + ")", "start", "font-size=\"12\"");
    svg.rect(ox, oy, pw, ph, "fill=\"#440154\" stroke=\"none\"");
    const auto& v = wear ? p.map->wear_rate : p.map->pressure;
    std::array<std::string, kRamp.size()> paths;
    for (std::size_t i = 0; i < p.map->cells.size(); ++i) {
      const auto& c = p.map->cells[i];
      // The two triangles of one grid cell (dem/station/plate_map.h) with one value: drawn as the cell.
      if (i + 1 < p.map->cells.size() && v[i + 1] == v[i] && p.map->cells[i + 1][0] == c[0] &&
          p.map->cells[i + 1][1] == c[2]) {
        const auto& d = p.map->cells[i + 1][2];
        paths[bin(v[i], hi)] += fmt::format("M{} {}L{} {}L{} {}L{} {}Z", px(X(c[0].x())), px(Y(c[0].y())),
                                            px(X(c[1].x())), px(Y(c[1].y())), px(X(c[2].x())), px(Y(c[2].y())),
                                            px(X(d.x())), px(Y(d.y())));
        ++i;
        continue;
      }
      paths[bin(v[i], hi)] += fmt::format("M{} {}L{} {}L{} {}Z", px(X(c[0].x())), px(Y(c[0].y())), px(X(c[1].x())),
                                          px(Y(c[1].y())), px(X(c[2].x())), px(Y(c[2].y())));
    }
    for (double t : yt.values) {
      svg.line(ox - 4, Y(t * 1e-3), ox, Y(t * 1e-3), "class=\"tick\" stroke=\"#333\"");
      svg.text(ox - 6, Y(t * 1e-3) + 3.5, yt.label(t), "end", "font-size=\"10\"");
    }
    for (double t : zt.values) {
      svg.line(X(t * 1e-3), oy + ph, X(t * 1e-3), oy + ph + 4, "class=\"tick\" stroke=\"#333\"");
      svg.text(X(t * 1e-3), oy + ph + 14, zt.label(t), "middle", "font-size=\"10\"");
    }
    svg.text(ox - left + 8, oy + 0.5 * ph, "y (mm)", "middle",
             fmt::format("font-size=\"10\" fill=\"#555\" transform=\"rotate(-90 {} {})\"", px(ox - left + 8), px(oy + 0.5 * ph)));
    svg.text(ox + pw, oy + ph + 24, "z across (mm)", "end", "font-size=\"10\" fill=\"#555\"");
    for (std::size_t b = 0; b < paths.size(); ++b)
      if (!paths[b].empty())
        svg.raw(fmt::format("<path d=\"{}\" fill=\"{}\" stroke=\"{}\" stroke-width=\"0.3\"/>\n", paths[b], kRamp[b], kRamp[b]));
    if (p.zone) {
      const PlateZone& z = *p.zone;
      svg.rect(X(-0.5 * z.width), Y(z.top_y), z.width * k, (z.top_y - z.bottom_y) * k,
               "fill=\"none\" stroke=\"#ffffff\" stroke-width=\"1.6\" stroke-dasharray=\"5 3\"",
               fmt::format("{} impact zone: y = {:.0f} to {:.0f} mm, mean pressure {} kPa", p.zone_model,
                           z.top_y * 1e3, z.bottom_y * 1e3, bar_label(z.mean_pressure * kKpa, z.mean_pressure * kKpa)));
      svg.line(X(-0.5 * z.width), Y(z.centroid_y), X(0.5 * z.width), Y(z.centroid_y),
               "stroke=\"#ffffff\" stroke-width=\"0.8\" stroke-dasharray=\"2 2\"");
    }
    if (!wear && std::isfinite(p.map->peak_pressure_y)) {
      svg.line(ox - 6, Y(p.map->peak_pressure_y), ox, Y(p.map->peak_pressure_y), "stroke=\"#d62728\" stroke-width=\"2\"");
      svg.line(ox + pw, Y(p.map->peak_pressure_y), ox + pw + 6, Y(p.map->peak_pressure_y), "stroke=\"#d62728\" stroke-width=\"2\"");
    }
    if (!wear && p.impact_point) {
      svg.marker(Shape::triangle_up, ox + pw + 3, Y(*p.impact_point), 7, "#111111", true,
                 fmt::format("{} impact point y_R = {:.1f} mm", p.model, *p.impact_point * 1e3));
    }
  }
  // Colour bar: one scale for every panel, labelled at its ends and middle.
  const double by = rows * cell_h + gap, bw = 40.0;
  const std::string what = wear ? "wear rate (µm/h)" : "normal pressure (kPa)";
  svg.text(gap, by + 10, what, "start", "font-size=\"12\"");
  const double x = gap + text_width(what, 12) + 10;
  for (std::size_t b = 0; b < kRamp.size(); ++b)
    svg.raw(fmt::format("<rect x=\"{}\" y=\"{}\" width=\"{}\" height=\"10\" fill=\"{}\"/>\n", px(x + b * bw), px(by),
                        px(bw), kRamp[b]));
  const double top = hi * (wear ? kUmPerHour : kKpa);
  for (int j = 0; j <= 2; ++j)
    svg.text(x + j * 0.5 * kRamp.size() * bw, by + 24, bar_label(top * 0.5 * j, top), "middle", "font-size=\"10\"");
  if (!wear)
    svg.text(gap, by + 40,
             "dashed: analytical impact zone and centroid; red ticks: peak of the map's pressure profile; "
             "triangle: the model's impact point y_R",
             "start", "font-size=\"11\"");
  return svg.finish();
}

}  // namespace

PlateSection plate_section(const Context& c, const validation::ValidationResult& r, std::string_view id, double width) {
  PlateSection out;
  std::vector<Panel> panels;
  for (const auto& row : c.conditions)
    for (const auto& m : r.models) {
      const auto* cr = r.prediction(row.name, m);
      if (!cr || cr->prediction.maps.empty() || cr->prediction.maps.front().cells.empty()) continue;
      Panel p;
      p.condition = row.name;
      p.model = m;
      p.map = &cr->prediction.maps.front();
      p.impact_point = cr->prediction.values[Quantity::impact_point_y];
      for (const auto& other : r.models) {
        const auto* o = r.prediction(row.name, other);
        if (o && o->prediction.plate_zone) {
          p.zone = o->prediction.plate_zone;
          p.zone_model = other;
          break;
        }
      }
      panels.push_back(p);
    }
  if (panels.empty()) return out;
  out.pressure_svg = heat_map(panels, false, std::string(id) + "-pressure", width);
  out.wear_svg = heat_map(panels, true, std::string(id) + "-wear", width);
  Table& t = out.table;
  t.id = std::string(id) + "-table";
  t.caption = "Plate loading and wear per condition (steady-window means)";
  t.key_columns = 2;
  t.columns = {{"", "condition", "", true}, {"", "model", "", true},
               {"map", "peak pressure (kPa)"}, {"map", "peak wear (µm/h)"}, {"map", "mean wear (µm/h)"},
               {"map", "peak-pressure y (mm)"}, {"map", "centre of pressure y (mm)"}, {"", "y_R (mm)"},
               {"peak − y_R", "mm"}, {"analytical zone", "y (mm)"}, {"analytical zone", "mean pressure (kPa)"}};
  for (const auto& p : panels) {
    double peak_p = 0.0, peak_w = 0.0, sum_w = 0.0, area = 0.0;
    for (std::size_t i = 0; i < p.map->cells.size(); ++i) {
      const auto& q = p.map->cells[i];
      const double a = 0.5 * std::abs((q[1] - q[0]).x() * (q[2] - q[0]).y() - (q[1] - q[0]).y() * (q[2] - q[0]).x());
      peak_p = std::max(peak_p, p.map->pressure[i]);
      peak_w = std::max(peak_w, p.map->wear_rate[i]);
      sum_w += p.map->wear_rate[i] * a;
      area += a;
    }
    auto num = [](double v, int d) { return std::isfinite(v) ? Cell{fixed(v, d)} : Cell{std::string(kDash)}; };
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const double yr = p.impact_point ? *p.impact_point : nan;
    t.rows.push_back({Cell{p.condition, "", false, "", true}, Cell{p.model, "", false, "", true}, num(peak_p * kKpa, decimals_for(peak_p * kKpa, 3)),
                      num(peak_w * kUmPerHour, decimals_for(peak_w * kUmPerHour, 3)),
                      num(area > 0.0 ? sum_w / area * kUmPerHour : nan, decimals_for(peak_w * kUmPerHour, 3)),
                      num(p.map->peak_pressure_y * 1e3, 1), num(p.map->pressure_centre_y * 1e3, 1), num(yr * 1e3, 1),
                      num((p.map->peak_pressure_y - yr) * 1e3, 1),
                      p.zone ? Cell{fmt::format("{:.0f} … {:.0f}", p.zone->top_y * 1e3, p.zone->bottom_y * 1e3)}
                             : Cell{std::string(kDash)},
                      p.zone ? num(p.zone->mean_pressure * kKpa, decimals_for(p.zone->mean_pressure * kKpa, 3))
                             : Cell{std::string(kDash)}});
  }
  t.notes.push_back("Peak and mean wear: Archard sliding + Finnie impact wear, depth per hour of operation, with the "
                    "wear inputs of the run (setup.toml [dem.wear]); mean over the whole plate face.");
  t.notes.push_back("Peak-pressure y: the peak of the pressure profile across the plate (rows of the plate mesh); "
                    "y_R: the load cell's impact point (moment / R_n).");
  return out;
}

}  // namespace chutelab::reports
