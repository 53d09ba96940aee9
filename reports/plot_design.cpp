// One design as a designer sees it on a trajectory calculator: the head pulley with the belt and its
// load, the four streamlines from the belt over the pulley to the plate, the plate, the impact
// points, the analytical impact zone on the plate face, and the Korzen readout beside it. Equal
// aspect, so angles and distances look as they are. design_svg is the list of drawing steps; each
// step draws one part from the computed design (reports/design.h) and the view of it.
#include <algorithm>
#include <cmath>
#include <fmt/format.h>

#include "core/units.h"
#include "reports/design.h"
#include "reports/svg.h"

namespace chutelab::reports {
namespace {

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

// The path of a streamline in mm as drawn: along the belt at height e, then the exported path.
std::vector<Pt> drawn_path(const DesignDrawing& d, Streamline which, double approach /* mm */) {
  const double gamma = d.station.belt.incline;
  std::vector<Pt> p;
  for (const auto& q : d.line(which).path) p.push_back(q * 1e3);
  p.insert(p.begin(), p.front() - approach * Pt(std::cos(gamma), std::sin(gamma)));
  return p;
}

std::string num(double v, int decimals) { return fixed(v, decimals); }

std::string dash_attr(const LineStyle& sty) {
  return sty.dash.empty() ? "" : fmt::format(" stroke-dasharray=\"{}\"", sty.dash);
}

constexpr double kWidth = 980.0, kHeight = 540.0, kSide = 300.0;

// The picture's frame and scale: the design in mm, where it sits on the page, and the mm ticks.
struct View {
  explicit View(const DesignDrawing& drawing) : d(drawing), st(drawing.station) {}
  const DesignDrawing& d;
  const Station& st;
  double rb = 0.0, rp = 0.0;  // belt radius, pulley radius, mm
  double approach = 0.0;      // mm of belt drawn before the pulley
  Pt plate_top, plate_bottom;
  std::array<std::vector<Pt>, 4> paths;
  double x0 = 0.0, x1 = 0.0, y0 = 0.0, y1 = 0.0;  // extent, mm
  Frame f{0, 0, 0, 0};
  double s = 0.0, cx = 0.0, cy = 0.0;  // px per mm, page position of (x0, y1)
  Ticks xt, yt;
  double X(double x) const { return cx + (x - x0) * s; }
  double Y(double y) const { return cy + (y1 - y) * s; }
};

// Extent: the belt, the pulley, the plate and every streamline that reaches the plate; a stream
// that misses it is cut at the picture's edge rather than stretching the picture.
void fit_extent(View& v) {
  const auto& d = v.d;
  v.x0 = -v.rb - v.approach;
  v.x1 = std::max(v.plate_top.x(), v.plate_bottom.x());
  v.y0 = std::min({-v.rb, v.plate_bottom.y(), v.plate_top.y()});
  v.y1 = std::max(v.rb + d.load_height * 1e3, v.plate_top.y());
  for (std::size_t i = 0; i < v.paths.size(); ++i)
    if (d.lines[i].hit)
      for (const auto& q : v.paths[i]) {
        v.x0 = std::min(v.x0, q.x()); v.x1 = std::max(v.x1, q.x());
        v.y0 = std::min(v.y0, q.y()); v.y1 = std::max(v.y1, q.y());
      }
  const double pad = 0.06 * std::max(v.x1 - v.x0, v.y1 - v.y0);
  v.x0 -= pad; v.x1 += pad; v.y0 -= pad; v.y1 += pad;
  v.x1 += 0.1 * std::max(v.x1 - v.x0, v.y1 - v.y0);  // room right of the plate for its dimensions
}

View make_view(const DesignDrawing& d) {
  View v(d);
  const auto& st = d.station;
  v.rb = st.belt.belt_radius() * 1e3;
  v.rp = 0.5 * st.belt.pulley_diameter * 1e3;
  v.approach = std::max(1.5 * v.rb, 0.35 * st.plate_distance * 1e3);
  v.plate_top = Pt(st.plate_distance * 1e3, st.plate_top * 1e3);
  v.plate_bottom = v.plate_top + st.plate.height * 1e3 * Pt(std::sin(st.plate.angle), -std::cos(st.plate.angle));
  for (std::size_t i = 0; i < v.paths.size(); ++i) v.paths[i] = drawn_path(d, kAllStreamlines[i], v.approach);
  fit_extent(v);
  // Margins for the mm ticks: y on the left, x below.
  v.f = Frame{52.0, 34.0, kWidth - kSide - 66.0, kHeight - 72.0};
  const Frame& f = v.f;
  v.s = std::min(f.width / (v.x1 - v.x0), f.height / (v.y1 - v.y0));
  v.cx = f.left + 0.5 * (f.width - v.s * (v.x1 - v.x0));
  v.cy = f.top + 0.5 * (f.height - v.s * (v.y1 - v.y0));
  const double xv0 = v.x0 - (v.cx - f.left) / v.s, xv1 = xv0 + f.width / v.s;
  const double yv1 = v.y1 + (v.cy - f.top) / v.s, yv0 = yv1 - f.height / v.s;
  v.xt = inner_ticks(xv0, xv1, 9);
  v.yt = inner_ticks(yv0, yv1, 6);
  return v;
}

void draw_title(Svg& svg, const View& v) {
  const auto& st = v.st;
  // A design typed on the command line has no condition name of its own ("cli").
  svg.title(fmt::format("{}V_b = {} m/s, m_s = {} t/h, plate at x = {} mm",
                        st.condition == "cli" ? std::string() : st.condition + ": ", num(st.belt_speed, 2),
                        num(st.mass_flow * 3.6, 1), num(st.plate_distance * 1e3, 0)));
}

// Axes through the pulley centre and a light mm grid on the ticks: the designer reads coordinates
// off the frame's edges and distances off the scale bar and the dimensions.
void draw_grid(Svg& svg, const View& v) {
  const Frame& f = v.f;
  for (double t : v.xt.values) svg.line(v.X(t), f.top, v.X(t), f.bottom(), "stroke=\"#f0f0f0\"");
  for (double t : v.yt.values) svg.line(f.left, v.Y(t), f.right(), v.Y(t), "stroke=\"#f0f0f0\"");
  svg.line(f.left, v.Y(0), f.right(), v.Y(0), "stroke=\"#d8d8d8\"");
  svg.line(v.X(0), f.top, v.X(0), f.bottom(), "stroke=\"#d8d8d8\"");
}

// The top strand towards the pulley and the load on it; a troughed belt's wing edges dashed.
void draw_belt(Svg& svg, const View& v) {
  const auto& st = v.st;
  const double rb = v.rb;
  const double gamma = st.belt.incline;
  const Pt dir(std::cos(gamma), std::sin(gamma)), tan_b = rb * Pt(-std::sin(gamma), std::cos(gamma));
  const Pt belt_start = tan_b - v.approach * dir;
  const Pt load_top = (rb + v.d.load_height * 1e3) * Pt(-std::sin(gamma), std::cos(gamma));
  svg.raw(fmt::format("<polygon class=\"load\" points=\"{},{} {},{} {},{} {},{}\" fill=\"#e8d9b0\" stroke=\"none\"/>\n",
                      px(v.X(belt_start.x())), px(v.Y(belt_start.y())), px(v.X(tan_b.x())), px(v.Y(tan_b.y())),
                      px(v.X(load_top.x())), px(v.Y(load_top.y())), px(v.X((load_top - v.approach * dir).x())),
                      px(v.Y((load_top - v.approach * dir).y()))));
  svg.line(v.X(belt_start.x()), v.Y(belt_start.y()), v.X(tan_b.x()), v.Y(tan_b.y()),
           "class=\"belt\" stroke=\"#333\" stroke-width=\"3\"");
  svg.line(v.X(belt_start.x()), v.Y(-rb), v.X(0), v.Y(-rb), "stroke=\"#333\" stroke-width=\"3\"");
  if (st.belt.trough.troughed()) {
    // The trough's wing edges stand above the belt's centre line: seen from the side, the load lies
    // in the trough below this line (its section is drawn beside the readout).
    const double edge = 0.5 * (st.belt.belt_width - st.belt.trough.centre_roll) * std::sin(st.belt.trough.idler_angle) * 1e3;
    const Pt e0 = belt_start + edge * Pt(-std::sin(gamma), std::cos(gamma)), e1 = tan_b + edge * Pt(-std::sin(gamma), std::cos(gamma));
    svg.raw(fmt::format("<line class=\"trough-edge\" x1=\"{}\" y1=\"{}\" x2=\"{}\" y2=\"{}\" stroke=\"#333\" "
                        "stroke-dasharray=\"6 3\"><title>edge of the troughed belt ({} mm above its centre line)</title></line>\n",
                        px(v.X(e0.x())), px(v.Y(e0.y())), px(v.X(e1.x())), px(v.Y(e1.y())), num(edge, 0)));
  }
}

void draw_pulley(Svg& svg, const View& v) {
  svg.raw(fmt::format("<circle class=\"pulley\" cx=\"{}\" cy=\"{}\" r=\"{}\" fill=\"#bbb\" stroke=\"#333\" stroke-width=\"3\">"
                      "<title>head pulley, {} mm diameter, belt radius R_b = {} mm</title></circle>\n",
                      px(v.X(0)), px(v.Y(0)), px(v.rb * v.s), num(2 * v.rp, 0), num(v.rb, 1)));
  svg.raw(fmt::format("<circle cx=\"{}\" cy=\"{}\" r=\"{}\" fill=\"#999\"/>\n", px(v.X(0)), px(v.Y(0)), px(0.06 * v.rb * v.s)));
}

// The plate, its face towards the pulley.
void draw_plate(Svg& svg, const View& v) {
  const auto& st = v.st;
  svg.raw(fmt::format("<line class=\"plate\" x1=\"{}\" y1=\"{}\" x2=\"{}\" y2=\"{}\" stroke=\"#555\" stroke-width=\"6\" "
                      "stroke-linecap=\"butt\"><title>plate: face at x = {} mm, top y = {} mm, {} mm high, {} deg from vertical</title></line>\n",
                      px(v.X(v.plate_top.x()) + 3), px(v.Y(v.plate_top.y())), px(v.X(v.plate_bottom.x()) + 3),
                      px(v.Y(v.plate_bottom.y())), num(v.plate_top.x(), 0), num(v.plate_top.y(), 0),
                      num(st.plate.height * 1e3, 0), num(st.plate.angle * units::deg_per_rad, 1)));
}

// The analytical impact zone: the band of the face between the hits of Booth's outer streamlines,
// with Korzen's R_n spread over it; drawn on the face, in front of the plate, so a designer sees
// where the wear will be before any DEM map exists.
void draw_impact_zone(Svg& svg, const View& v) {
  const auto& st = v.st;
  const auto& zone = v.d.zone;
  const Pt down(std::sin(st.plate.angle), -std::cos(st.plate.angle));
  const Pt z0 = v.plate_top + zone.top_along * 1e3 * down, z1 = v.plate_top + zone.bottom_along * 1e3 * down;
  svg.raw(fmt::format("<line class=\"impact-zone\" x1=\"{}\" y1=\"{}\" x2=\"{}\" y2=\"{}\" stroke=\"#ff7f0e\" "
                      "stroke-opacity=\"0.55\" stroke-width=\"12\" stroke-linecap=\"butt\"><title>analytical impact zone: y = "
                      "{} to {} mm on the face, {} mm wide; mean pressure {} Pa, mean shear stress {} Pa (Korzen R_n, R_s "
                      "spread over it){}</title></line>\n",
                      px(v.X(z0.x()) - 3), px(v.Y(z0.y())), px(v.X(z1.x()) - 3), px(v.Y(z1.y())), num(zone.top_y * 1e3, 1),
                      num(zone.bottom_y * 1e3, 1), num(zone.width * 1e3, 0), num(zone.mean_pressure, 0),
                      num(zone.mean_shear_stress, 0),
                      zone.top_clipped || zone.bottom_clipped ? "; part of the stream misses the plate" : ""));
}

void draw_streamlines(Svg& svg, const View& v) {
  for (Streamline which : kAllStreamlines) {
    const auto i = static_cast<std::size_t>(which);
    const auto sty = style(which);
    std::vector<std::pair<double, double>> pts;
    for (const auto& q : v.paths[i]) pts.emplace_back(v.X(q.x()), v.Y(q.y()));
    svg.polyline(pts, fmt::format("class=\"streamline {}\" stroke=\"{}\" stroke-width=\"2\"{}", sty.cls, sty.colour,
                                  dash_attr(sty)));
    const auto& l = v.d.lines[i];
    svg.marker(Shape::circle, v.X(l.release.x() * 1e3), v.Y(l.release.y() * 1e3), 5, sty.colour, true,
               fmt::format("{} leaves the pulley at x = {} mm, y = {} mm", sty.label, num(l.release.x() * 1e3, 1),
                           num(l.release.y() * 1e3, 1)));
  }
}

// Where each centroid meets the plate; the Korzen one carries the readout.
void draw_impact_points(Svg& svg, const View& v) {
  for (Streamline which : {Streamline::cema_centroid, Streamline::korzen_centroid}) {
    const auto& l = v.d.line(which);
    if (!l.hit) continue;
    const Pt p = l.hit->point * 1e3;
    svg.raw(fmt::format("<g class=\"impact-point {}\">", style(which).cls));
    svg.marker(which == Streamline::korzen_centroid ? Shape::diamond : Shape::square, v.X(p.x()), v.Y(p.y()), 11,
               style(which).colour, which == Streamline::korzen_centroid,
               fmt::format("{} meets the plate at y = {} mm{}", style(which).label, num(p.y(), 1),
                           l.hit->on_plate ? "" : " (off the plate)"));
    svg.raw("</g>\n");
  }
}

// Ticks in mm on the frame (origin: the pulley centre).
void draw_ticks(Svg& svg, const View& v) {
  const Frame& f = v.f;
  for (double t : v.xt.values) {
    svg.line(v.X(t), f.bottom(), v.X(t), f.bottom() + 5, "class=\"tick x\" stroke=\"#333\"");
    svg.text(v.X(t), f.bottom() + 17, v.xt.label(t), "middle", "font-size=\"11\"");
  }
  for (double t : v.yt.values) {
    svg.line(f.left - 5, v.Y(t), f.left, v.Y(t), "class=\"tick y\" stroke=\"#333\"");
    svg.text(f.left - 7, v.Y(t) + 4, v.yt.label(t), "end", "font-size=\"11\"");
  }
  svg.text(f.right(), f.bottom() + 31, "x (mm) from the pulley centre", "end", "font-size=\"11\" fill=\"#555\"");
  svg.text(f.left - 46, f.top - 8, "y (mm)", "start", "font-size=\"11\" fill=\"#555\"");
}

// A dimension: a line with arrowheads between two points (px), its text beside its middle.
void dimension(Svg& svg, double ax, double ay, double bx, double by, const std::string& text, double tx, double ty,
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
}

// Plate distance: pulley centre to the face's top edge, above both.
void dimension_plate_distance(Svg& svg, const View& v) {
  const Pt& top = v.plate_top;
  const double yd = std::max(v.f.top + 12.0, std::min(v.Y(top.y()), v.Y(v.rb + v.d.load_height * 1e3)) - 16.0);
  svg.line(v.X(0), v.Y(0), v.X(0), yd - 4, "stroke=\"#999\" stroke-dasharray=\"2 2\"");
  svg.line(v.X(top.x()), v.Y(top.y()), v.X(top.x()), yd - 4, "stroke=\"#999\" stroke-dasharray=\"2 2\"");
  dimension(svg, v.X(0), yd, v.X(top.x()), yd, num(top.x(), 0) + " mm", 0.5 * (v.X(0) + v.X(top.x())), yd - 4,
            "middle", "plate distance: x of the face's top edge from the pulley centre");
}

// Right of the plate: its height along the face, then its top edge's height above the pulley
// centre; labels turned along the lines.
void dimension_plate(Svg& svg, const View& v) {
  const auto& st = v.st;
  const Pt& top = v.plate_top;
  const Pt& bottom = v.plate_bottom;
  const Pt off = 12.0 / v.s * Pt(std::cos(st.plate.angle), std::sin(st.plate.angle));
  const Pt q0 = top + off, q1 = bottom + off;
  dimension(svg, v.X(q0.x()) + 3, v.Y(q0.y()), v.X(q1.x()) + 3, v.Y(q1.y()), num(st.plate.height * 1e3, 0) + " mm",
            0.5 * (v.X(q0.x()) + v.X(q1.x())) + 14, 0.5 * (v.Y(q0.y()) + v.Y(q1.y())), "middle",
            fmt::format("plate height along its face; {} deg from vertical", num(st.plate.angle * units::deg_per_rad, 1)),
            -90.0 + st.plate.angle * units::deg_per_rad);
  const double xd = std::min(v.f.right() - 14.0, std::max(v.X(top.x()), v.X(bottom.x())) + 40.0);
  svg.line(v.X(top.x()) + 6, v.Y(top.y()), xd + 4, v.Y(top.y()), "stroke=\"#999\" stroke-dasharray=\"2 2\"");
  svg.line(v.X(0) + v.rb * v.s + 4, v.Y(0), xd + 4, v.Y(0), "stroke=\"#999\" stroke-dasharray=\"2 2\"");
  dimension(svg, xd, v.Y(0), xd, v.Y(top.y()), num(top.y(), 0) + " mm", xd + 11, 0.5 * (v.Y(0) + v.Y(top.y())),
            "middle", "plate top: y of the face's top edge above the pulley centre", -90.0);
}

// Pulley diameter across the pulley, on the 45 degree line below-left.
void dimension_pulley(Svg& svg, const View& v) {
  const Pt d0 = v.rp * Pt(-std::sqrt(0.5), -std::sqrt(0.5)), d1 = -d0;
  dimension(svg, v.X(d0.x()), v.Y(d0.y()), v.X(d1.x()), v.Y(d1.y()), "Ø " + num(2 * v.rp, 0) + " mm",
            v.X(d0.x()) - 4, v.Y(d0.y()) + 12, "end", "head pulley diameter");
}

// Scale bar, bottom left: 1, 2 or 5 x 10^k mm, the largest such length under a fifth of the frame.
void draw_scale_bar(Svg& svg, const View& v) {
  const Frame& f = v.f;
  const double target = 0.2 * f.width / v.s;
  const double decade = std::pow(10.0, std::floor(std::log10(target)));
  double length = decade;
  for (double m : {2.0, 5.0})
    if (m * decade <= target) length = m * decade;
  const double bar = length * v.s;
  svg.raw("<g class=\"scale-bar\">");
  svg.rect(f.left + 12, f.bottom() - 16, bar, 5, "fill=\"#333\"");
  svg.rect(f.left + 12 + bar / 2, f.bottom() - 16, bar / 2, 5, "fill=\"#fff\" stroke=\"#333\"");
  svg.text(f.left + 12 + bar / 2, f.bottom() - 21, fixed(length, length < 1.0 ? 1 : 0) + " mm", "middle",
           "font-size=\"11\" fill=\"#333\"");
  svg.raw("</g>\n");
}

// Right of the drawing: the legend, then the readout rows, then a troughed belt's section; `y` is
// where the next one starts.
struct SidePanel {
  double x = 0.0, y = 0.0;
};

void draw_legend(Svg& svg, SidePanel& p) {
  for (Streamline which : {Streamline::upper, Streamline::cema_centroid, Streamline::korzen_centroid, Streamline::lower}) {
    const auto sty = style(which);
    svg.line(p.x, p.y + 5, p.x + 26, p.y + 5, fmt::format("stroke=\"{}\" stroke-width=\"2\"{}", sty.colour, dash_attr(sty)));
    svg.text(p.x + 32, p.y + 9, sty.label, "start", "font-size=\"12\"");
    p.y += 18;
  }
  svg.line(p.x, p.y + 5, p.x + 26, p.y + 5, "stroke=\"#ff7f0e\" stroke-opacity=\"0.55\" stroke-width=\"10\"");
  svg.text(p.x + 32, p.y + 9, "impact zone (Booth limits)", "start", "font-size=\"12\"");
  p.y += 18;
  p.y += 10;
}

void readout_row(Svg& svg, SidePanel& p, std::string_view markup, const std::string& cls) {
  svg.raw(fmt::format("<text class=\"readout {}\" x=\"{}\" y=\"{}\" font-size=\"13\">{}</text>\n", cls, px(p.x),
                      px(p.y + 12), markup));
  p.y += 20;
}

// The Korzen readout: the stream on the belt and its discharge, the impact, Korzen's verdict and
// forces (as the Korzen model reports them), the impact zone.
void draw_readout(Svg& svg, SidePanel& p, const DesignDrawing& d, const QuantityValues& korzen) {
  const auto& kc = *d.line(Streamline::korzen_centroid).hit;
  const double incidence = kc.alpha + d.station.plate.angle;
  auto row = [&](std::string_view markup, const std::string& cls) { readout_row(svg, p, markup, cls); };
  auto val = [&](Quantity q, int dec) {
    return korzen[q] ? num(*korzen[q] * info(q).to_boundary, dec) + " " + std::string(info(q).unit) : std::string("-");
  };
  const auto& rel = d.line(Streamline::cema_centroid);
  row(fmt::format("h{} = {} mm ({})", "<tspan baseline-shift=\"sub\" font-size=\"75%\">b</tspan>",
                  num(d.load_height * 1e3, 1), d.thickness_from_continuity ? "continuity" : "given"), "hb");
  row(esc(fmt::format("discharge: {}, K = {}", rel.high_speed ? "high-speed" : "low-speed", num(rel.release_ratio, 2))),
      "discharge");
  row(symbol_svg("V_p") + " = " + esc(val(Quantity::impact_velocity, 2)), "vp");
  row(fmt::format("α{} = {}°", "<tspan baseline-shift=\"sub\" font-size=\"75%\">p</tspan>", num(kc.alpha * units::deg_per_rad, 1)), "alpha");
  row(d.stationary_flow ? "stationary flow: yes (Eq 3)" : "stationary flow: no (Eq 3)",
      d.stationary_flow ? "verdict stationary" : "verdict none");
  row(esc(fmt::format("  α_p+β = {}° {} atan μ_pw = {}°", num(incidence * units::deg_per_rad, 1), d.stationary_flow ? ">" : "≤",
                      num(std::atan(d.plate_friction) * units::deg_per_rad, 1))),
      "criterion");
  row(symbol_svg("V_a") + " = " + esc(korzen[Quantity::exit_velocity] ? val(Quantity::exit_velocity, 2) : "none (Eq 4)"), "va");
  row(symbol_svg("R_n") + " = " + esc(val(Quantity::normal_force, 2)), "rn");
  row(symbol_svg("R_s") + " = " + esc(val(Quantity::shear_force, 2) + " (" + d.shear_equation + ")"), "rs");
  row("R = " + esc(val(Quantity::resultant_force, 2)), "r");
  row(esc("impact y = " + val(Quantity::impact_point_y, 1) + (kc.on_plate ? "" : " (off the plate)")), "impact");
  const auto& zone = d.zone;
  row(esc(fmt::format("zone y = {} to {} mm", num(zone.bottom_y * 1e3, 1), num(zone.top_y * 1e3, 1)) +
          (zone.top_clipped || zone.bottom_clipped ? " (clipped)" : "")),
      "zone");
  row(esc(fmt::format("mean pressure = {} Pa", num(zone.mean_pressure, 0))), "zone-pressure");
}

// A troughed belt: its cross-section under the readout, since the side view shows the load's
// height h_b but not its shape.
void draw_trough_section(Svg& svg, const SidePanel& p, const DesignDrawing& d) {
  const auto& st = d.station;
  const auto& tr = st.belt.trough;
  const double c = tr.centre_roll, wing = 0.5 * (st.belt.belt_width - c);
  const double lam = tr.idler_angle, hb = d.load_height, cw = d.load_contact_width;
  const double iw = kWidth - p.x - 12.0, ih = std::min(110.0, kHeight - p.y - 14.0), ix = p.x, iy = p.y + 6.0;
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

}  // namespace

std::string design_svg(const DesignDrawing& d, const QuantityValues& korzen, std::string_view id) {
  const View v = make_view(d);
  Svg svg(kWidth, kHeight, "design-picture", id, "transfer station: streamlines, plate and impact point");
  draw_title(svg, v);
  const std::string clip = svg.clip(v.f);
  svg.rect(v.f.left, v.f.top, v.f.width, v.f.height, "fill=\"#fbfbfb\" stroke=\"#ccc\"");
  svg.raw(fmt::format("<g clip-path=\"url(#{})\">\n", clip));
  draw_grid(svg, v);
  draw_belt(svg, v);
  draw_pulley(svg, v);
  draw_plate(svg, v);
  draw_impact_zone(svg, v);
  draw_streamlines(svg, v);
  draw_impact_points(svg, v);
  svg.raw("</g>\n");
  draw_ticks(svg, v);
  dimension_plate_distance(svg, v);
  dimension_plate(svg, v);
  dimension_pulley(svg, v);
  draw_scale_bar(svg, v);
  SidePanel side{v.f.right() + 16, v.f.top + 6};
  draw_legend(svg, side);
  draw_readout(svg, side, d, korzen);
  if (d.station.belt.trough.troughed()) draw_trough_section(svg, side, d);
  return svg.finish();
}

}  // namespace chutelab::reports
