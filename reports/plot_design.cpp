// One design as a designer sees it on a trajectory calculator: the head pulley with the belt and its
// load, the four streamlines from the belt over the pulley to the plate, the plate, the impact
// points, the analytical impact zone on the plate face, and the Korzen readout beside it. Equal
// aspect, so angles and distances look as they are.
#include <algorithm>
#include <cmath>
#include <fmt/format.h>

#include "analytical/impact_zone.h"
#include "analytical/streamline_path.h"
#include "core/units.h"
#include "reports/design.h"
#include "reports/svg.h"

namespace chutelab::reports {
namespace {
using analytical::Streamline;

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

// The path of a streamline in mm as drawn: along the belt at height e, then the exported path
// (analytical/streamline_path.h).
std::vector<Pt> streamline_path(const analytical::TransferAnalysis& a, Streamline which, double approach /* mm */) {
  const double gamma = a.station.belt.incline;
  std::vector<Pt> p;
  for (const auto& q : analytical::streamline_path(a, which)) p.push_back(q * 1e3);
  p.insert(p.begin(), p.front() - approach * Pt(std::cos(gamma), std::sin(gamma)));
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
  for (std::size_t i = 0; i < paths.size(); ++i) paths[i] = streamline_path(a, a.streamlines[i].which, approach);

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
  x1 += 0.1 * std::max(x1 - x0, y1 - y0);  // room right of the plate for its dimensions

  const double W = 980.0, H = 540.0, side = 300.0;
  // Margins for the mm ticks: y on the left, x below.
  const Frame f{52.0, 34.0, W - side - 66.0, H - 72.0};
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

  // Axes through the pulley centre and a light mm grid on the ticks: the designer reads
  // coordinates off the frame's edges and distances off the scale bar and the dimensions.
  const double xv0 = x0 - (cx - f.left) / s, xv1 = xv0 + f.width / s;
  const double yv1 = y1 + (cy - f.top) / s, yv0 = yv1 - f.height / s;
  const Ticks xt = inner_ticks(xv0, xv1, 9), yt = inner_ticks(yv0, yv1, 6);
  for (double t : xt.values) svg.line(X(t), f.top, X(t), f.bottom(), "stroke=\"#f0f0f0\"");
  for (double t : yt.values) svg.line(f.left, Y(t), f.right(), Y(t), "stroke=\"#f0f0f0\"");
  svg.line(f.left, Y(0), f.right(), Y(0), "stroke=\"#d8d8d8\"");
  svg.line(X(0), f.top, X(0), f.bottom(), "stroke=\"#d8d8d8\"");

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
  if (st.belt.trough.troughed()) {
    // The trough's wing edges stand above the belt's centre line: seen from the side, the load lies
    // in the trough below this line (its section is drawn beside the readout).
    const double edge = 0.5 * (st.belt.belt_width - st.belt.trough.centre_roll) * std::sin(st.belt.trough.idler_angle) * 1e3;
    const Pt e0 = belt_start + edge * Pt(-std::sin(gamma), std::cos(gamma)), e1 = tan_b + edge * Pt(-std::sin(gamma), std::cos(gamma));
    svg.raw(fmt::format("<line class=\"trough-edge\" x1=\"{}\" y1=\"{}\" x2=\"{}\" y2=\"{}\" stroke=\"#333\" "
                        "stroke-dasharray=\"6 3\"><title>edge of the troughed belt ({} mm above its centre line)</title></line>\n",
                        px(X(e0.x())), px(Y(e0.y())), px(X(e1.x())), px(Y(e1.y())), num(edge, 0)));
  }
  svg.raw(fmt::format("<circle class=\"pulley\" cx=\"{}\" cy=\"{}\" r=\"{}\" fill=\"#bbb\" stroke=\"#333\" stroke-width=\"3\">"
                      "<title>head pulley, {} mm diameter, belt radius R_b = {} mm</title></circle>\n",
                      px(X(0)), px(Y(0)), px(rb * s), num(2 * rp, 0), num(rb, 1)));
  svg.raw(fmt::format("<circle cx=\"{}\" cy=\"{}\" r=\"{}\" fill=\"#999\"/>\n", px(X(0)), px(Y(0)), px(0.06 * rb * s)));

  // The plate, its face towards the pulley.
  svg.raw(fmt::format("<line class=\"plate\" x1=\"{}\" y1=\"{}\" x2=\"{}\" y2=\"{}\" stroke=\"#555\" stroke-width=\"6\" "
                      "stroke-linecap=\"butt\"><title>plate: face at x = {} mm, top y = {} mm, {} mm high, {} deg from vertical</title></line>\n",
                      px(X(plate_top.x()) + 3), px(Y(plate_top.y())), px(X(plate_bottom.x()) + 3), px(Y(plate_bottom.y())),
                      num(plate_top.x(), 0), num(plate_top.y(), 0), num(st.plate.height * 1e3, 0),
                      num(st.plate.angle * units::deg_per_rad, 1)));

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

  // Ticks in mm on the frame (origin: the pulley centre).
  for (double t : xt.values) {
    svg.line(X(t), f.bottom(), X(t), f.bottom() + 5, "class=\"tick x\" stroke=\"#333\"");
    svg.text(X(t), f.bottom() + 17, xt.label(t), "middle", "font-size=\"11\"");
  }
  for (double t : yt.values) {
    svg.line(f.left - 5, Y(t), f.left, Y(t), "class=\"tick y\" stroke=\"#333\"");
    svg.text(f.left - 7, Y(t) + 4, yt.label(t), "end", "font-size=\"11\"");
  }
  svg.text(f.right(), f.bottom() + 31, "x (mm) from the pulley centre", "end", "font-size=\"11\" fill=\"#555\"");
  svg.text(f.left - 46, f.top - 8, "y (mm)", "start", "font-size=\"11\" fill=\"#555\"");

  // Dimensions: a line with arrowheads between two points (px), its text beside its middle.
  auto dimension = [&](double ax, double ay, double bx, double by, const std::string& text, double tx, double ty,
                       std::string_view anchor, const std::string& title, double rotate = 0.0) {
    svg.raw(fmt::format("<g class=\"dimension\"><title>{}</title>", esc(title)));
    svg.line(ax, ay, bx, by, "stroke=\"#444\" stroke-width=\"1\"");
    const double len = std::hypot(bx - ax, by - ay);
    if (len > 1.0) {
      const double ux = (bx - ax) / len, uy = (by - ay) / len;
      for (int end = 0; end < 2; ++end) {
        const double px0 = end ? bx : ax, py0 = end ? by : ay, dir = end ? -1.0 : 1.0;
        svg.raw(fmt::format("<path d=\"M{} {}L{} {}L{} {}Z\" fill=\"#444\"/>", px(px0), px(py0),
                            px(px0 + dir * 8 * ux - 3 * uy), px(py0 + dir * 8 * uy + 3 * ux),
                            px(px0 + dir * 8 * ux + 3 * uy), px(py0 + dir * 8 * uy - 3 * ux)));
      }
    }
    svg.text(tx, ty, text, anchor,
             fmt::format("font-size=\"11\" fill=\"#222\" paint-order=\"stroke\" stroke=\"#fbfbfb\" stroke-width=\"3\"{}",
                         rotate != 0.0 ? fmt::format(" transform=\"rotate({} {} {})\"", px(rotate), px(tx), px(ty)) : ""));
    svg.raw("</g>\n");
  };
  {
    // Plate distance: pulley centre to the face's top edge, above both.
    const double yd = std::max(f.top + 12.0, std::min(Y(plate_top.y()), Y(rb + a.load.height * 1e3)) - 16.0);
    svg.line(X(0), Y(0), X(0), yd - 4, "stroke=\"#999\" stroke-dasharray=\"2 2\"");
    svg.line(X(plate_top.x()), Y(plate_top.y()), X(plate_top.x()), yd - 4, "stroke=\"#999\" stroke-dasharray=\"2 2\"");
    dimension(X(0), yd, X(plate_top.x()), yd, num(plate_top.x(), 0) + " mm", 0.5 * (X(0) + X(plate_top.x())), yd - 4,
              "middle", "plate distance: x of the face's top edge from the pulley centre");
    // Right of the plate: its height along the face, then its top edge's height above the pulley
    // centre; labels turned along the lines.
    const Pt off = 12.0 / s * Pt(std::cos(st.plate.angle), std::sin(st.plate.angle));
    const Pt q0 = plate_top + off, q1 = plate_bottom + off;
    dimension(X(q0.x()) + 3, Y(q0.y()), X(q1.x()) + 3, Y(q1.y()), num(st.plate.height * 1e3, 0) + " mm",
              0.5 * (X(q0.x()) + X(q1.x())) + 14, 0.5 * (Y(q0.y()) + Y(q1.y())), "middle",
              fmt::format("plate height along its face; {} deg from vertical", num(st.plate.angle * units::deg_per_rad, 1)),
              -90.0 + st.plate.angle * units::deg_per_rad);
    const double xd = std::min(f.right() - 14.0, std::max(X(plate_top.x()), X(plate_bottom.x())) + 40.0);
    svg.line(X(plate_top.x()) + 6, Y(plate_top.y()), xd + 4, Y(plate_top.y()), "stroke=\"#999\" stroke-dasharray=\"2 2\"");
    svg.line(X(0) + rb * s + 4, Y(0), xd + 4, Y(0), "stroke=\"#999\" stroke-dasharray=\"2 2\"");
    dimension(xd, Y(0), xd, Y(plate_top.y()), num(plate_top.y(), 0) + " mm", xd + 11, 0.5 * (Y(0) + Y(plate_top.y())), "middle",
              "plate top: y of the face's top edge above the pulley centre", -90.0);
    // Pulley diameter across the pulley, on the 45 degree line below-left.
    const Pt d0 = rp * Pt(-std::sqrt(0.5), -std::sqrt(0.5)), d1 = -d0;
    dimension(X(d0.x()), Y(d0.y()), X(d1.x()), Y(d1.y()), "Ø " + num(2 * rp, 0) + " mm", X(d0.x()) - 4, Y(d0.y()) + 12,
              "end", "head pulley diameter");
  }

  // Scale bar, bottom left: 1, 2 or 5 x 10^k mm, the largest such length under a fifth of the frame.
  {
    const double target = 0.2 * f.width / s;
    const double decade = std::pow(10.0, std::floor(std::log10(target)));
    double length = decade;
    for (double m : {2.0, 5.0})
      if (m * decade <= target) length = m * decade;
    const double bar = length * s;
    svg.raw("<g class=\"scale-bar\">");
    svg.rect(f.left + 12, f.bottom() - 16, bar, 5, "fill=\"#333\"");
    svg.rect(f.left + 12 + bar / 2, f.bottom() - 16, bar / 2, 5, "fill=\"#fff\" stroke=\"#333\"");
    svg.text(f.left + 12 + bar / 2, f.bottom() - 21, fixed(length, length < 1.0 ? 1 : 0) + " mm", "middle",
             "font-size=\"11\" fill=\"#333\"");
    svg.raw("</g>\n");
  }

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
  row(fmt::format("α{} = {}°", "<tspan baseline-shift=\"sub\" font-size=\"75%\">p</tspan>", num(kc.alpha * units::deg_per_rad, 1)), "alpha");
  row(k.stationary_flow ? "stationary flow: yes (Eq 3)" : "stationary flow: no (Eq 3)",
      k.stationary_flow ? "verdict stationary" : "verdict none");
  row(esc(fmt::format("  α_p+β = {}° {} atan μ_pw = {}°", num(incidence * units::deg_per_rad, 1), k.stationary_flow ? ">" : "≤",
                      num(std::atan(a.plate_interaction.friction) * units::deg_per_rad, 1))),
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
  // A troughed belt: its cross-section under the readout, since the side view shows the load's
  // height h_b but not its shape.
  if (st.belt.trough.troughed()) {
    const auto& tr = st.belt.trough;
    const double c = tr.centre_roll, wing = 0.5 * (st.belt.belt_width - c);
    const double lam = tr.idler_angle, hb = a.load.height, cw = a.load.contact_width;
    const double iw = W - tx - 12.0, ih = std::min(110.0, H - ty - 14.0), ix = tx, iy = ty + 6.0;
    const double k = std::min((iw - 16) / std::max(c + 2 * wing * std::cos(lam), 1e-6), (ih - 26) / std::max(hb, wing * std::sin(lam)));
    auto IX = [&](double u) { return ix + 0.5 * iw + u * k; };
    auto IY = [&](double v) { return iy + ih - 8 - v * k; };
    svg.raw("<g class=\"trough-section\"><title>cross-section of the troughed belt and its load (CEMA shape): "
            + esc(fmt::format("idler angle {} deg, centre roll {} mm, surcharge angle {} deg, h_b = {} mm, contact "
                              "width {} mm", num(lam * units::deg_per_rad, 0), num(c * 1e3, 0), num(tr.surcharge_angle * units::deg_per_rad, 0),
                              num(hb * 1e3, 1), num(cw * 1e3, 0)))
            + "</title>\n");
    svg.rect(ix, iy, iw, ih, "fill=\"#ffffff\" stroke=\"#bbb\"");
    // The load: on the rolls up to the contact width, topped by a circular arc of apex h_b.
    double ex = 0.5 * std::min(cw, c), ey = 0.0;
    if (cw > c) {
      const double up = 0.5 * (cw - c);
      ex = 0.5 * c + up * std::cos(lam);
      ey = up * std::sin(lam);
    }
    const double sag = std::max(hb - ey, 1e-9), radius = (ex * ex + sag * sag) / (2 * sag);
    std::string load = fmt::format("M{} {}", px(IX(-ex)), px(IY(ey)));
    if (cw > c) load += fmt::format("L{} {}L{} {}", px(IX(-0.5 * c)), px(IY(0)), px(IX(0.5 * c)), px(IY(0)));
    load += fmt::format("L{} {}A{} {} 0 0 0 {} {}Z", px(IX(ex)), px(IY(ey)), px(radius * k), px(radius * k),
                        px(IX(-ex)), px(IY(ey)));
    svg.raw(fmt::format("<path class=\"load-section\" d=\"{}\" fill=\"#e8d9b0\" stroke=\"#b59a55\"/>\n", load));
    const double tx = 0.5 * c + wing * std::cos(lam), ty = wing * std::sin(lam);
    svg.raw(fmt::format("<polyline class=\"belt-section\" points=\"{},{} {},{} {},{} {},{}\" fill=\"none\" stroke=\"#333\" "
                        "stroke-width=\"2.5\"/>\n",
                        px(IX(-tx)), px(IY(ty)), px(IX(-0.5 * c)), px(IY(0)), px(IX(0.5 * c)), px(IY(0)), px(IX(tx)), px(IY(ty))));
    svg.text(ix + 4, iy + 11, fmt::format("trough {}°, section", num(lam * units::deg_per_rad, 0)), "start", "font-size=\"10\" fill=\"#444\"");
    svg.raw("</g>\n");
  }

  return svg.finish();
}

}  // namespace chutelab::reports
