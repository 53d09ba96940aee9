// One design as a designer sees it on a trajectory calculator: the head pulley with the belt and its
// load, the four streamlines from the belt over the pulley to the plate, the plate, the impact
// points, the analytical impact zone on the plate face, and the Korzen readout beside it. Equal
// aspect, so angles and distances look as they are.
#include <algorithm>
#include <cmath>
#include <fmt/format.h>

#include "analytical/impact_zone.h"
#include "reports/design.h"
#include "reports/svg.h"

namespace chutelab::reports {
namespace {
using analytical::Streamline;
constexpr double kDeg = 180.0 / 3.14159265358979323846;

struct LineStyle {
  std::string_view cls, label, colour, dash;
};

LineStyle style(Streamline s) {
  switch (s) {
    case Streamline::upper: return {"upper", "upper limit (e = h_b)", "#1f77b4", ""};
    case Streamline::lower: return {"lower", "lower limit (e = 0)", "#d62728", ""};
    case Streamline::cema_centroid: return {"cema-centroid", "CEMA centroid (e = a1)", "#2ca02c", "8 4"};
    case Streamline::korzen_centroid: return {"korzen-centroid", "Korzen centroid (e = h_b/2)", "#9467bd", "2 3"};
  }
  return {};
}

using Pt = Eigen::Vector2d;

// The path of a streamline in mm: along the belt at height e, round the pulley to the release
// point (low-speed discharge), then its flight to the plate (or 1 s when it never gets there).
std::vector<Pt> streamline_path(const analytical::TransferAnalysis& a, const analytical::StreamlineFlight& l,
                                double approach /* mm */) {
  const double gamma = a.station.belt.incline;
  const double r = a.station.belt.belt_radius() + l.height_above_belt;
  const Pt tangent = r * Pt(-std::sin(gamma), std::cos(gamma));
  std::vector<Pt> p = {tangent - approach * 1e-3 * Pt(std::cos(gamma), std::sin(gamma)), tangent};
  const double theta = l.release.theta;
  if (theta > -gamma + 1e-9)
    for (int k = 1; k <= 24; ++k) {
      const double phi = -gamma + (theta + gamma) * k / 24.0;
      p.push_back(r * Pt(std::sin(phi), std::cos(phi)));
    }
  const double t_end = l.hit ? l.hit->point.t : 1.0;
  for (const auto& f : l.trajectory.sample(t_end, 64)) p.push_back(f.position);
  for (auto& q : p) q *= 1e3;
  return p;
}

std::string num(double v, int decimals) { return fixed(v, decimals); }

}  // namespace

std::string design_svg(const analytical::TransferAnalysis& a, const QuantityValues& korzen,
                       std::string_view id) {
  const auto& st = a.station;
  const double rb = st.belt.belt_radius() * 1e3, rp = 0.5 * st.belt.pulley_diameter * 1e3;
  const double approach = std::max(1.5 * rb, 0.35 * st.plate_distance * 1e3);
  const Pt plate_top(st.plate_distance * 1e3, st.plate_top * 1e3);
  const Pt plate_bottom = plate_top + st.plate.height * 1e3 * Pt(std::sin(st.plate.angle), -std::cos(st.plate.angle));

  std::array<std::vector<Pt>, 4> paths;
  for (std::size_t i = 0; i < paths.size(); ++i) paths[i] = streamline_path(a, a.streamlines[i], approach);

  // Extent: the belt, the pulley, the plate and every streamline that reaches the plate; a stream
  // that misses it is cut at the picture's edge rather than stretching the picture.
  double x0 = -rb - approach, x1 = std::max(plate_top.x(), plate_bottom.x());
  double y0 = std::min({-rb, plate_bottom.y(), plate_top.y()}), y1 = std::max(rb + a.load.height * 1e3, plate_top.y());
  for (std::size_t i = 0; i < paths.size(); ++i)
    if (a.streamlines[i].hit)
      for (const auto& q : paths[i]) {
        x0 = std::min(x0, q.x()); x1 = std::max(x1, q.x());
        y0 = std::min(y0, q.y()); y1 = std::max(y1, q.y());
      }
  const double pad = 0.06 * std::max(x1 - x0, y1 - y0);
  x0 -= pad; x1 += pad; y0 -= pad; y1 += pad;

  const double W = 980.0, H = 520.0, side = 300.0;
  const Frame f{14.0, 34.0, W - side - 28.0, H - 48.0};
  const double s = std::min(f.width / (x1 - x0), f.height / (y1 - y0));
  const double cx = f.left + 0.5 * (f.width - s * (x1 - x0)), cy = f.top + 0.5 * (f.height - s * (y1 - y0));
  auto X = [&](double x) { return cx + (x - x0) * s; };
  auto Y = [&](double y) { return cy + (y1 - y) * s; };

  Svg svg(W, H, "design-picture", id, "transfer station: streamlines, plate and impact point");
  // A design typed on the command line has no condition name of its own ("cli").
  svg.title(fmt::format("{}V_b = {} m/s, m_s = {} t/h, plate at x = {} mm",
                        st.condition == "cli" ? std::string() : st.condition + ": ", num(st.belt_speed, 2),
                        num(st.mass_flow * 3.6, 1), num(st.plate_distance * 1e3, 0)));
  const std::string clip = svg.clip(f);
  svg.rect(f.left, f.top, f.width, f.height, "fill=\"#fbfbfb\" stroke=\"#ccc\"");
  svg.raw(fmt::format("<g clip-path=\"url(#{})\">\n", clip));

  // Axes through the pulley centre, with a 100 mm scale bar: the designer reads distances off it.
  svg.line(f.left, Y(0), f.right(), Y(0), "stroke=\"#e0e0e0\"");
  svg.line(X(0), f.top, X(0), f.bottom(), "stroke=\"#e0e0e0\"");

  // Belt (top strand towards the pulley) and the load on it, then the pulley and its lagging.
  const double gamma = st.belt.incline;
  const Pt dir(std::cos(gamma), std::sin(gamma)), tan_b = rb * Pt(-std::sin(gamma), std::cos(gamma));
  const Pt belt_start = tan_b - approach * dir;
  const Pt load_top = (rb + a.load.height * 1e3) * Pt(-std::sin(gamma), std::cos(gamma));
  svg.raw(fmt::format("<polygon class=\"load\" points=\"{},{} {},{} {},{} {},{}\" fill=\"#e8d9b0\" stroke=\"none\"/>\n",
                      px(X(belt_start.x())), px(Y(belt_start.y())), px(X(tan_b.x())), px(Y(tan_b.y())),
                      px(X(load_top.x())), px(Y(load_top.y())), px(X((load_top - approach * dir).x())),
                      px(Y((load_top - approach * dir).y()))));
  svg.line(X(belt_start.x()), Y(belt_start.y()), X(tan_b.x()), Y(tan_b.y()),
           "class=\"belt\" stroke=\"#333\" stroke-width=\"3\"");
  svg.line(X(belt_start.x()), Y(-rb), X(0), Y(-rb), "stroke=\"#333\" stroke-width=\"3\"");
  svg.raw(fmt::format("<circle class=\"pulley\" cx=\"{}\" cy=\"{}\" r=\"{}\" fill=\"#bbb\" stroke=\"#333\" stroke-width=\"3\">"
                      "<title>head pulley, {} mm diameter, belt radius R_b = {} mm</title></circle>\n",
                      px(X(0)), px(Y(0)), px(rb * s), num(2 * rp, 0), num(rb, 1)));
  svg.raw(fmt::format("<circle cx=\"{}\" cy=\"{}\" r=\"{}\" fill=\"#999\"/>\n", px(X(0)), px(Y(0)), px(0.06 * rb * s)));

  // The plate, its face towards the pulley.
  svg.raw(fmt::format("<line class=\"plate\" x1=\"{}\" y1=\"{}\" x2=\"{}\" y2=\"{}\" stroke=\"#555\" stroke-width=\"6\" "
                      "stroke-linecap=\"butt\"><title>plate: face at x = {} mm, top y = {} mm, {} mm high, {} deg from vertical</title></line>\n",
                      px(X(plate_top.x()) + 3), px(Y(plate_top.y())), px(X(plate_bottom.x()) + 3), px(Y(plate_bottom.y())),
                      num(plate_top.x(), 0), num(plate_top.y(), 0), num(st.plate.height * 1e3, 0),
                      num(st.plate.angle * kDeg, 1)));

  // The analytical impact zone (analytical/impact_zone.h): the band of the face between the hits of
  // Booth's outer streamlines, with Korzen's R_n spread over it; drawn on the face, in front of the
  // plate, so a designer sees where the wear will be before any DEM map exists.
  const analytical::ImpactZone zone = analytical::impact_zone(a);
  {
    const Pt down(std::sin(st.plate.angle), -std::cos(st.plate.angle));
    const Pt z0 = plate_top + zone.top_along * 1e3 * down, z1 = plate_top + zone.bottom_along * 1e3 * down;
    svg.raw(fmt::format("<line class=\"impact-zone\" x1=\"{}\" y1=\"{}\" x2=\"{}\" y2=\"{}\" stroke=\"#ff7f0e\" "
                        "stroke-opacity=\"0.55\" stroke-width=\"12\" stroke-linecap=\"butt\"><title>analytical impact zone: y = "
                        "{} to {} mm on the face, {} mm wide; mean pressure {} Pa, mean shear stress {} Pa (Korzen R_n, R_s "
                        "spread over it){}</title></line>\n",
                        px(X(z0.x()) - 3), px(Y(z0.y())), px(X(z1.x()) - 3), px(Y(z1.y())), num(zone.top_y * 1e3, 1),
                        num(zone.bottom_y * 1e3, 1), num(zone.width * 1e3, 0), num(zone.mean_pressure, 0),
                        num(zone.mean_shear_stress, 0),
                        zone.top_clipped || zone.bottom_clipped ? "; part of the stream misses the plate" : ""));
  }

  for (Streamline which : analytical::kAllStreamlines) {
    const auto i = static_cast<std::size_t>(which);
    const auto sty = style(which);
    std::vector<std::pair<double, double>> pts;
    for (const auto& q : paths[i]) pts.emplace_back(X(q.x()), Y(q.y()));
    svg.polyline(pts, fmt::format("class=\"streamline {}\" stroke=\"{}\" stroke-width=\"2\"{}", sty.cls,
                                  sty.colour, sty.dash.empty() ? "" : fmt::format(" stroke-dasharray=\"{}\"", sty.dash)));
    const auto& l = a.streamlines[i];
    svg.marker(Shape::circle, X(l.release.position.x() * 1e3), Y(l.release.position.y() * 1e3), 5, sty.colour, true,
               fmt::format("{} leaves the pulley at x = {} mm, y = {} mm", sty.label,
                           num(l.release.position.x() * 1e3, 1), num(l.release.position.y() * 1e3, 1)));
  }
  // Impact points: where each centroid meets the plate; the Korzen one carries the readout.
  for (Streamline which : {Streamline::cema_centroid, Streamline::korzen_centroid}) {
    const auto& l = a.line(which);
    if (!l.hit) continue;
    const Pt p = l.hit->point.position * 1e3;
    svg.raw(fmt::format("<g class=\"impact-point {}\">", style(which).cls));
    svg.marker(which == Streamline::korzen_centroid ? Shape::diamond : Shape::square, X(p.x()), Y(p.y()), 11,
               style(which).colour, which == Streamline::korzen_centroid,
               fmt::format("{} meets the plate at y = {} mm{}", style(which).label, num(p.y(), 1),
                           l.hit->on_plate ? "" : " (off the plate)"));
    svg.raw("</g>\n");
  }
  svg.raw("</g>\n");

  // 100 mm scale bar, bottom left.
  const double bar = 100.0 * s;
  svg.line(f.left + 12, f.bottom() - 12, f.left + 12 + bar, f.bottom() - 12, "stroke=\"#333\" stroke-width=\"2\"");
  svg.text(f.left + 12 + bar / 2, f.bottom() - 17, "100 mm", "middle", "font-size=\"11\" fill=\"#333\"");

  // Legend and readout, right of the drawing.
  double ty = f.top + 6;
  const double tx = f.right() + 16;
  for (Streamline which : {Streamline::upper, Streamline::cema_centroid, Streamline::korzen_centroid, Streamline::lower}) {
    const auto sty = style(which);
    svg.line(tx, ty + 5, tx + 26, ty + 5, fmt::format("stroke=\"{}\" stroke-width=\"2\"{}", sty.colour,
                                                      sty.dash.empty() ? "" : fmt::format(" stroke-dasharray=\"{}\"", sty.dash)));
    svg.text(tx + 32, ty + 9, sty.label, "start", "font-size=\"12\"");
    ty += 18;
  }
  svg.line(tx, ty + 5, tx + 26, ty + 5, "stroke=\"#ff7f0e\" stroke-opacity=\"0.55\" stroke-width=\"10\"");
  svg.text(tx + 32, ty + 9, "impact zone (Booth limits)", "start", "font-size=\"12\"");
  ty += 18;
  ty += 10;
  const auto& kc = *a.line(Streamline::korzen_centroid).hit;
  const auto& k = a.korzen;
  const double incidence = kc.alpha + st.plate.angle;
  auto row = [&](std::string_view markup, const std::string& cls) {
    svg.raw(fmt::format("<text class=\"readout {}\" x=\"{}\" y=\"{}\" font-size=\"13\">{}</text>\n", cls, px(tx),
                        px(ty + 12), markup));
    ty += 20;
  };
  auto val = [&](Quantity q, int dec) {
    return korzen[q] ? num(*korzen[q] * info(q).to_boundary, dec) + " " + std::string(info(q).unit) : std::string("-");
  };
  const auto& rel = a.line(Streamline::cema_centroid).release;
  row(fmt::format("h{} = {} mm ({})", "<tspan baseline-shift=\"sub\" font-size=\"75%\">b</tspan>",
                  num(a.load.height * 1e3, 1), a.thickness_from_continuity ? "continuity" : "given"), "hb");
  row(esc(fmt::format("discharge: {}, K = {}", rel.high_speed ? "high-speed" : "low-speed", num(rel.ratio, 2))), "discharge");
  row(symbol_svg("V_p") + " = " + esc(val(Quantity::impact_velocity, 2)), "vp");
  row(fmt::format("α{} = {}°", "<tspan baseline-shift=\"sub\" font-size=\"75%\">p</tspan>", num(kc.alpha * kDeg, 1)), "alpha");
  row(k.stationary_flow ? "stationary flow: yes (Eq 3)" : "stationary flow: no (Eq 3)",
      k.stationary_flow ? "verdict stationary" : "verdict none");
  row(esc(fmt::format("  α_p+β = {}° {} atan μ_pw = {}°", num(incidence * kDeg, 1), k.stationary_flow ? ">" : "≤",
                      num(std::atan(a.plate_interaction.friction) * kDeg, 1))),
      "criterion");
  row(symbol_svg("V_a") + " = " + esc(korzen[Quantity::exit_velocity] ? val(Quantity::exit_velocity, 2) : "none (Eq 4)"), "va");
  row(symbol_svg("R_n") + " = " + esc(val(Quantity::normal_force, 2)), "rn");
  row(symbol_svg("R_s") + " = " + esc(val(Quantity::shear_force, 2) + " (" + std::string(name(k.shear_equation)) + ")"), "rs");
  row("R = " + esc(val(Quantity::resultant_force, 2)), "r");
  row(esc("impact y = " + val(Quantity::impact_point_y, 1) + (kc.on_plate ? "" : " (off the plate)")), "impact");
  row(esc(fmt::format("zone y = {} to {} mm", num(zone.bottom_y * 1e3, 1), num(zone.top_y * 1e3, 1)) +
          (zone.top_clipped || zone.bottom_clipped ? " (clipped)" : "")),
      "zone");
  row(esc(fmt::format("mean pressure = {} Pa", num(zone.mean_pressure, 0))), "zone-pressure");
  return svg.finish();
}

}  // namespace chutelab::reports
