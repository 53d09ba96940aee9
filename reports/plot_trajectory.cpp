// The stream picture of every condition (the reference study's Fig. 7), as small multiples: the head pulley,
// the plate, each model's streamlines, the measured stream points and the measured impact point.
// Equal aspect in every panel so that angles and distances look as they are on the rig.
#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <map>

#include "reports/common.h"

namespace chutelab::reports {
namespace {

// Dash patterns given to curve names in order of first appearance: the picture distinguishes a
// model by colour and a streamline by dash, whatever the models call their curves.
constexpr std::array<std::string_view, 6> kDashes = {"", "8 4", "2 3", "10 3 2 3", "5 2", "1 4"};

// At most this many measured points of one boundary are drawn in a panel (see trajectory_grid).
constexpr std::size_t kDrawnPerBoundary = 60;

Shape boundary_shape(Boundary b) {
  switch (b) {
    case Boundary::upper: return Shape::triangle_up;
    case Boundary::lower: return Shape::triangle_down;
    case Boundary::centre: return Shape::circle;
  }
  return Shape::circle;
}

// Point clouds (a DEM's particles) are coloured by their value in bins of kRamp (dark = slow), one
// shared scale over all panels so that the colours compare.

struct ValueScale {
  double lo = 0.0, hi = 0.0;
  std::string label;
  bool valid() const { return hi > lo; }
  std::size_t bin(double v) const {
    const double t = valid() ? (v - lo) / (hi - lo) : 0.5;
    return static_cast<std::size_t>(std::clamp(t * kRamp.size(), 0.0, kRamp.size() - 1.0));
  }
};

// The cloud as one path per colour bin of zero-length round-capped segments: a dot per particle at
// a fraction of the bytes of one element each.
void draw_cloud(Svg& svg, const validation::Curve& cv, const Scale& X, const Scale& Y, const ValueScale& vs,
                std::string_view fallback, const std::string& tip) {
  std::array<std::string, kRamp.size()> paths;
  const bool coloured = vs.valid() && cv.value.size() == cv.points.size();
  for (std::size_t i = 0; i < cv.points.size(); ++i) {
    const auto& q = cv.points[i];
    paths[coloured ? vs.bin(cv.value[i]) : 0] += fmt::format("M{} {}h0", px(X(q.x() * 1e3)), px(Y(q.y() * 1e3)));
  }
  svg.raw(fmt::format("<g class=\"cloud\" opacity=\"0.75\"><title>{}</title>\n", esc(tip)));
  for (std::size_t b = 0; b < paths.size(); ++b)
    if (!paths[b].empty())
      svg.raw(fmt::format("<path d=\"{}\" stroke=\"{}\" stroke-width=\"2.2\" stroke-linecap=\"round\" fill=\"none\"/>\n",
                          paths[b], coloured ? kRamp[b] : fallback));
  svg.raw("</g>\n");
}

// A horizontal colour bar for the legend figure.
void draw_colour_bar(Svg& svg, double x, double y, const ValueScale& vs, std::string_view what) {
  const double w = 24.0, h = 10.0;
  svg.text(x, y + 9, std::string(what), "start", "font-size=\"12\"");
  x += text_width(what, 12) + 8;
  svg.text(x, y + 9, fmt::format("{:.2f}", vs.lo), "start", "font-size=\"11\"");
  x += text_width(fmt::format("{:.2f}", vs.lo), 11) + 4;
  for (std::size_t b = 0; b < kRamp.size(); ++b)
    svg.raw(fmt::format("<rect x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" fill=\"{}\"/>\n", px(x + b * w), px(y),
                        px(w), px(h), kRamp[b]));
  svg.text(x + kRamp.size() * w + 4, y + 9, fmt::format("{:.2f} {}", vs.hi, vs.label), "start", "font-size=\"11\"");
}

struct Geometry {
  double x0, x1, y0, y1;  // mm
};

// The plate face runs from its top edge (Z, top) along (sin beta, -cos beta).
double face_x(const Station& s, double y) {
  const double c = std::cos(s.plate.angle);
  const double along = c > 1e-9 ? (s.plate_top - y) / c : 0.0;
  return s.plate_distance + along * std::sin(s.plate.angle);
}


struct PlateHit {
  std::string model, curve;
  double y;  // mm
};

// The plate face as a vertical axis of its own (mm), zoomed onto where the stream meets it:
// measured impact point with its error bar, each model's impact point, and where each streamline
// arrives.
template <class Dash>
void draw_plate_strip(Svg& svg, const Frame& sf, const Context& c, const validation::Measurement* meas_y,
                      const std::vector<std::pair<std::string, double>>& model_impacts,
                      const std::vector<PlateHit>& hits, Dash dash) {
  double lo = 1e300, hi = -1e300;
  auto note = [&](double y) { lo = std::min(lo, y); hi = std::max(hi, y); };
  if (meas_y) {
    note(meas_y->value * 1e3 - meas_y->uncertainty.value_or(0.0) * 1e3);
    note(meas_y->value * 1e3 + meas_y->uncertainty.value_or(0.0) * 1e3);
  }
  for (const auto& [m, y] : model_impacts) note(y);
  for (const auto& h : hits) note(h.y);
  const double pad = std::max(2.0, 0.12 * (hi - lo));
  lo -= pad;
  hi += pad;
  const Ticks t = inner_ticks(lo, hi, 5);
  const Scale Y{lo, hi, sf.bottom(), sf.top};
  svg.text(sf.left + sf.width / 2, sf.top - 6, "at the plate", "middle", "font-size=\"10\" fill=\"#333\"");
  svg.rect(sf.left, sf.top, sf.width, sf.height, "fill=\"#fafafa\" stroke=\"#444\"");
  double label_w = 0.0;
  for (double v : t.values) {
    svg.line(sf.left, Y(v), sf.right(), Y(v), "stroke=\"#e2e2e2\"");
    svg.line(sf.right(), Y(v), sf.right() + 4, Y(v), "stroke=\"#444\"");
    svg.text(sf.right() + 7, Y(v) + 4, t.label(v), "start", "font-size=\"11\" fill=\"#333\"");
    label_w = std::max(label_w, text_width(t.label(v), 11));
  }
  const double lx = sf.right() + 14 + label_w;
  svg.raw(fmt::format("<text x=\"{}\" y=\"{}\" text-anchor=\"middle\" transform=\"rotate(90 {} {})\" "
                      "class=\"axis-label\" font-size=\"11\">y on the plate (mm)</text>\n",
                      px(lx), px(sf.top + sf.height / 2), px(lx), px(sf.top + sf.height / 2)));
  svg.rect(sf.left, sf.top, 4, sf.height, "fill=\"#555\"");  // the plate face
  for (const auto& h : hits) {
    const std::string d = dash(h.curve);
    svg.raw(fmt::format("<line x1=\"{}\" y1=\"{}\" x2=\"{}\" y2=\"{}\" stroke=\"{}\" stroke-width=\"2\"{}>"
                        "<title>{}: {} meets the plate at y = {:.1f} mm</title></line>\n",
                        px(sf.left + 4), px(Y(h.y)), px(sf.left + 26), px(Y(h.y)), c.colour(h.model),
                        d.empty() ? "" : fmt::format(" stroke-dasharray=\"{}\"", d), esc(h.model), esc(h.curve), h.y));
  }
  const double n = static_cast<double>(model_impacts.size());
  for (std::size_t i = 0; i < model_impacts.size(); ++i) {
    const auto& [m, y] = model_impacts[i];
    const double x = sf.left + 36 + (static_cast<double>(i) - (n - 1) / 2) * 11;
    std::string tip = fmt::format("{}: impact point y_R = {:.1f} mm", m, y);
    if (meas_y) tip += fmt::format(" (error {:+.1f} mm)", y - meas_y->value * 1e3);
    svg.marker(Shape::diamond, x, Y(y), 10, c.colour(m), false, tip);
  }
  if (meas_y) {
    const double y = meas_y->value * 1e3, x = sf.left + 36;
    std::string tip = fmt::format("measured impact point y_R = {:.1f}", y);
    if (meas_y->uncertainty) {
      const double u = *meas_y->uncertainty * 1e3;
      tip += fmt::format(" ± {:.1f}", u);
      svg.line(x, Y(y + u), x, Y(y - u), "stroke=\"#111\" stroke-width=\"1.2\"");
      svg.line(x - 3, Y(y + u), x + 3, Y(y + u), "stroke=\"#111\"");
      svg.line(x - 3, Y(y - u), x + 3, Y(y - u), "stroke=\"#111\"");
    }
    svg.marker(Shape::diamond, x, Y(y), 7, kMeasuredColour, true, tip + " mm");
  }
}

// What every panel shares: a dash per curve name, a colour per model (Context), who predicts an
// impact point, which boundaries are measured, and one colour scale for every point cloud.
struct GridStyle {
  std::vector<std::string> curve_names;
  std::vector<std::pair<std::string, std::string>> model_curves;  // (model, curve) as they occur
  std::vector<std::string> impact_models;
  std::vector<Boundary> boundaries;
  bool any_impact_measured = false;
  ValueScale vs;
  std::string cloud_name;
  std::string dash(const std::string& curve) const {
    const auto i = static_cast<std::size_t>(std::find(curve_names.begin(), curve_names.end(), curve) -
                                            curve_names.begin());
    return std::string(kDashes[i % kDashes.size()]);
  }
};

void collect_curves(GridStyle& g, const validation::ValidationResult& r) {
  for (const auto& m : r.models)
    for (const auto& p : r.predictions)
      if (p.model == m)
        for (const auto& cv : p.prediction.curves) {
          if (std::find(g.curve_names.begin(), g.curve_names.end(), cv.name) == g.curve_names.end())
            g.curve_names.push_back(cv.name);
          if (std::find(g.model_curves.begin(), g.model_curves.end(), std::pair{m, cv.name}) == g.model_curves.end())
            g.model_curves.emplace_back(m, cv.name);
        }
}

void collect_impacts(GridStyle& g, const Context& c, const validation::ValidationResult& r) {
  for (const auto& m : r.models)
    for (const auto& p : r.predictions)
      if (p.model == m && p.prediction.values[Quantity::impact_point_y]) {
        g.impact_models.push_back(m);
        break;
      }
  for (Boundary b : kAllBoundaries)
    for (const auto& pt : c.in.dataset->trajectory)
      if (pt.boundary == b) {
        g.boundaries.push_back(b);
        break;
      }
  for (const auto& row : c.conditions)
    g.any_impact_measured = g.any_impact_measured || find_measurement(*c.in.dataset, row.name, Quantity::impact_point_y);
}

// One colour scale for every point cloud of every panel.
void cloud_scale(GridStyle& g, const validation::ValidationResult& r) {
  bool first_value = true;
  for (const auto& p : r.predictions)
    for (const auto& cv : p.prediction.curves)
      if (cv.kind == validation::Curve::Kind::points && cv.value.size() == cv.points.size() && !cv.value.empty()) {
        const auto [lo, hi] = std::minmax_element(cv.value.begin(), cv.value.end());
        g.vs.lo = first_value ? *lo : std::min(g.vs.lo, *lo);
        g.vs.hi = first_value ? *hi : std::max(g.vs.hi, *hi);
        g.vs.label = cv.value_label;
        g.cloud_name = fmt::format("{}: {}", p.model, cv.name);
        first_value = false;
      }
}

GridStyle grid_style(const Context& c, const validation::ValidationResult& r) {
  GridStyle g;
  collect_curves(g, r);
  collect_impacts(g, c, r);
  cloud_scale(g, r);
  return g;
}

bool is_cloud(const validation::ValidationResult& r, const std::string& model, const std::string& curve) {
  for (const auto& p : r.predictions)
    if (p.model == model)
      for (const auto& cv : p.prediction.curves)
        if (cv.name == curve) return cv.kind == validation::Curve::Kind::points;
  return false;
}

std::vector<LegendEntry> grid_legend(const Context& c, const validation::ValidationResult& r, const GridStyle& g) {
  std::vector<LegendEntry> legend;
  for (const auto& [m, cv] : g.model_curves) {
    if (is_cloud(r, m, cv))
      legend.push_back({LegendEntry::Kind::marker, fmt::format("{}: {} (coloured by {})", m, cv,
                                                               g.vs.valid() ? g.vs.label : "model"),
                        g.vs.valid() ? std::string(kRamp[kRamp.size() / 2]) : c.colour(m), "", Shape::circle, true});
    else
      legend.push_back({LegendEntry::Kind::line, fmt::format("{}: {}", m, cv), c.colour(m), g.dash(cv)});
  }
  for (Boundary b : g.boundaries)
    legend.push_back({LegendEntry::Kind::marker, fmt::format("measured {} boundary", name(b)),
                      std::string(kMeasuredColour), "", boundary_shape(b), true});
  if (g.any_impact_measured)
    legend.push_back({LegendEntry::Kind::marker, "measured impact point", std::string(kMeasuredColour), "",
                      Shape::diamond, true});
  for (const auto& m : g.impact_models)
    legend.push_back({LegendEntry::Kind::marker, fmt::format("{}: impact point", m), c.colour(m), "",
                      Shape::diamond, false});
  legend.push_back({LegendEntry::Kind::line, "impact plate", "#555", ""});
  legend.push_back({LegendEntry::Kind::box, "head pulley", "#d9d9d9"});
  return legend;
}

std::string legend_svg(const GridStyle& g, const std::vector<LegendEntry>& legend, std::string_view id,
                       double legend_width) {
  const double W = legend_width;
  const double lh = legend_height(W - 20, legend);
  const double bar = g.vs.valid() ? 22.0 : 0.0;
  Svg leg(W, lh + 30.0 + bar, "plot traj-legend", fmt::format("{}-legend", id), "Legend of the stream pictures");
  leg.title("Stream trajectories per condition: x, y from the head-pulley centre (mm)");
  leg.legend(10.0, 26.0, W - 20, legend);
  if (g.vs.valid()) draw_colour_bar(leg, 10.0, 26.0 + lh + 4.0, g.vs, g.cloud_name);
  return leg.finish();
}

// What one panel shows besides the models' curves: the measured stream points (a boundary
// measured at thousands of x values thinned), the measured and predicted impact points, and where
// each streamline meets the plate.
struct PanelData {
  std::vector<const validation::TrajectoryPoint*> points;
  std::size_t measured_here = 0;  // measured points of the condition, before thinning
  bool thinned = false;
  const validation::Measurement* meas_y = nullptr;
  std::vector<std::pair<std::string, double>> model_impacts;  // mm
  std::vector<PlateHit> hits;
};

// A boundary measured at thousands of x values is drawn thinned, evenly along x (kDrawnPerBoundary
// markers, first and last included): a marker per point would make a report of hundreds of MB.
void thin_points(std::vector<const validation::TrajectoryPoint*>& points) {
  std::map<Boundary, std::size_t> per_boundary;
  for (const auto* pt : points) ++per_boundary[pt->boundary];
  if (std::none_of(per_boundary.begin(), per_boundary.end(),
                   [](const auto& b) { return b.second > kDrawnPerBoundary; }))
    return;
  std::stable_sort(points.begin(), points.end(), [](const auto* a, const auto* b) {
    return a->boundary != b->boundary ? a->boundary < b->boundary : a->x < b->x;
  });
  std::vector<const validation::TrajectoryPoint*> thinned;
  for (std::size_t i = 0; i < points.size();) {
    const std::size_t n = per_boundary[points[i]->boundary];
    const std::size_t keep = std::min(n, kDrawnPerBoundary);
    for (std::size_t k = 0; k < keep; ++k) thinned.push_back(points[i + (keep > 1 ? k * (n - 1) / (keep - 1) : 0)]);
    i += n;
  }
  points = std::move(thinned);
}

PanelData panel_data(const Context& c, const validation::ValidationResult& r, const GridStyle& g,
                     const ConditionRow& row) {
  PanelData d;
  for (const auto& pt : c.in.dataset->trajectory)
    if (pt.condition == row.name) d.points.push_back(&pt);
  d.measured_here = d.points.size();
  thin_points(d.points);
  d.thinned = d.points.size() < d.measured_here;
  d.meas_y = find_measurement(*c.in.dataset, row.name, Quantity::impact_point_y);
  for (const auto& m : g.impact_models)
    if (const auto* p = r.prediction(row.name, m); p && p->prediction.values[Quantity::impact_point_y])
      d.model_impacts.emplace_back(m, *p->prediction.values[Quantity::impact_point_y] * 1e3);
  if (!row.station) return d;
  for (const auto& m : r.models)
    if (const auto* p = r.prediction(row.name, m))
      for (const auto& cv : p->prediction.curves) {
        if (cv.points.empty() || cv.kind == validation::Curve::Kind::points) continue;
        const auto& e = cv.points.back();
        if (std::abs(e.x() * 1e3 - face_x(*row.station, e.y()) * 1e3) < 5.0) d.hits.push_back({m, cv.name, e.y() * 1e3});
      }
  return d;
}

// One panel's frame: the rig in mm at equal aspect (one mm the same pixels along x and y), and the
// plate strip beside it.
struct PanelView {
  double Rb = 0.0, Z = 0.0, T = 0.0, Hp = 0.0, plate_bottom = 0.0;  // mm
  double x0 = 0.0, x1 = 0.0, y0 = 0.0, y1 = 0.0, k = 0.0;            // extent (mm), px per mm
  Frame f, sf;
  bool strip = false;
  double W = 0.0, H = 0.0;
  Scale X, Y;
};

// Vertically from above the plate's top edge to a bit below the lowest impact point (the plate
// goes on much further down; that is not the interesting part), and where a streamline meets the
// plate (the lower one hits below the impact point).
std::pair<double, double> vertical_extent(const validation::ValidationResult& r, const ConditionRow& row,
                                          const PanelData& d, const PanelView& v) {
  double top = std::max(v.T, v.Rb), low = 1e300;
  auto note_low = [&](double y) {
    if (std::isfinite(y) && y >= v.plate_bottom - 1e-9) low = std::min(low, y);
  };
  if (d.meas_y) note_low(d.meas_y->value * 1e3 - d.meas_y->uncertainty.value_or(0.0) * 1e3);
  for (const auto& [m, y] : d.model_impacts) note_low(y);
  for (const auto* pt : d.points) {
    note_low(pt->y * 1e3 - pt->uncertainty.value_or(0.0) * 1e3);
    top = std::max(top, pt->y * 1e3 + pt->uncertainty.value_or(0.0) * 1e3);
  }
  for (const auto& h : d.hits) note_low(h.y);
  for (const auto& m : r.models)
    if (const auto* p = r.prediction(row.name, m))
      for (const auto& cv : p->prediction.curves)
        if (!cv.points.empty() && cv.kind != validation::Curve::Kind::points)
          for (const auto& q : cv.points) top = std::max(top, q.y() * 1e3);
  if (low > 1e299) low = std::max(v.plate_bottom, -v.Rb);  // nothing to show below: the pulley
  return {low, top};
}

PanelView panel_view(const validation::ValidationResult& r, const ConditionRow& row, const PanelData& d) {
  const Station& s = *row.station;
  PanelView v;
  v.Rb = s.belt.belt_radius() * 1e3;
  v.Z = s.plate_distance * 1e3, v.T = s.plate_top * 1e3, v.Hp = s.plate.height * 1e3;
  v.plate_bottom = v.T - v.Hp * std::cos(s.plate.angle);
  const auto [low, top] = vertical_extent(r, row, d, v);
  const double span_y0 = top - low;
  const double pad_y = std::max(10.0, 0.08 * span_y0);
  v.y0 = low - pad_y, v.y1 = top + pad_y;
  // Rightmost: the plate face over the shown height (a tilted plate reaches further down there).
  double right = std::max(v.Z, face_x(s, std::max(v.y0, v.plate_bottom) / 1e3) * 1e3);
  for (const auto* pt : d.points) right = std::max(right, pt->x * 1e3);
  const double span_x0 = right + v.Rb;
  const double pad_x = std::max(10.0, 0.05 * span_x0);
  v.x0 = -v.Rb - pad_x, v.x1 = right + pad_x;
  const double max_w = 300.0, max_h = 460.0, min_h = 170.0;
  v.k = std::min(max_w / (v.x1 - v.x0), max_h / (v.y1 - v.y0));
  if ((v.y1 - v.y0) * v.k < min_h) {  // a flat picture: show more below rather than squash it
    v.y0 = v.y1 - min_h / v.k;
  }
  const double pw = (v.x1 - v.x0) * v.k, ph = (v.y1 - v.y0) * v.k;
  v.f = Frame{60.0, 30.0, pw, ph};
  // Beside the picture, the plate face magnified: at the rig's scale the impact points of the
  // models and the measurement sit within a few pixels of each other.
  v.strip = d.meas_y || !d.model_impacts.empty() || !d.hits.empty();
  v.sf = Frame{v.f.right() + 26.0, v.f.top, 56.0, v.f.height};
  v.W = (v.strip ? v.sf.right() + 74.0 : v.f.right() + 14.0), v.H = v.f.bottom() + 44.0;
  v.X = Scale{v.x0, v.x1, v.f.left, v.f.right()};
  v.Y = Scale{v.y0, v.y1, v.f.bottom(), v.f.top};
  return v;
}

// Same tick step on both axes (equal aspect, equal grid squares).
void draw_axes(Svg& svg, const PanelView& v) {
  Ticks xt = inner_ticks(v.x0, v.x1, 6);
  Ticks yt = xt;
  yt.values.clear();
  for (long i = static_cast<long>(std::ceil(v.y0 / xt.step)); i * xt.step <= v.y1 + 1e-9; ++i)
    yt.values.push_back(static_cast<double>(i) * xt.step);
  if (yt.values.size() < 3) {  // a short y range: finer ticks there
    yt = inner_ticks(v.y0, v.y1, 4);
  }
  svg.axes(v.f, v.X, xt, v.Y, yt, "x (mm)", "y (mm)");
}

// Head pulley and the belt running onto it (tangent at the top, along the belt's incline), and the
// plate's face from the top edge down its height.
void draw_rig(Svg& svg, const PanelView& v, const Station& s) {
  const auto& X = v.X;
  const auto& Y = v.Y;
  const double Rb = v.Rb;
  const double inc = s.belt.incline;
  svg.raw(fmt::format("<circle cx=\"{}\" cy=\"{}\" r=\"{}\" fill=\"#d9d9d9\" stroke=\"#888\"><title>head "
                      "pulley, belt radius {:.1f} mm</title></circle>\n",
                      px(X(0)), px(Y(0)), px(Rb * v.k), Rb));
  svg.line(X(-Rb * std::sin(inc) - 2000 * std::cos(inc)), Y(Rb * std::cos(inc) - 2000 * std::sin(inc)),
           X(-Rb * std::sin(inc)), Y(Rb * std::cos(inc)), "stroke=\"#888\" stroke-width=\"2\"");
  svg.raw(fmt::format("<line x1=\"{}\" y1=\"{}\" x2=\"{}\" y2=\"{}\" stroke=\"#555\" stroke-width=\"4\" "
                      "stroke-linecap=\"butt\"><title>impact plate: Z = {:.1f} mm, top {:.1f} mm, height "
                      "{:.1f} mm, angle {:.1f} deg</title></line>\n",
                      px(X(v.Z)), px(Y(v.T)), px(X(v.Z + v.Hp * std::sin(s.plate.angle))), px(Y(v.plate_bottom)), v.Z,
                      v.T, v.Hp, s.plate.angle * 180.0 / M_PI));
}

// Each model's point clouds, under its lines.
void draw_model_curves(Svg& svg, const PanelView& v, const Context& c, const validation::ValidationResult& r,
                       const GridStyle& g, const ConditionRow& row) {
  for (const auto& m : r.models)  // clouds under the lines
    if (const auto* p = r.prediction(row.name, m))
      for (const auto& cv : p->prediction.curves)
        if (cv.kind == validation::Curve::Kind::points)
          draw_cloud(svg, cv, v.X, v.Y, g.vs, c.colour(m),
                     fmt::format("{}: {} ({} shown{})", m, cv.name, cv.points.size(),
                                 g.vs.valid() ? fmt::format(", colour: {}", g.vs.label) : ""));
  for (const auto& m : r.models)
    if (const auto* p = r.prediction(row.name, m))
      for (const auto& cv : p->prediction.curves) {
        if (cv.kind == validation::Curve::Kind::points) continue;
        std::vector<std::pair<double, double>> pts;
        for (const auto& q : cv.points) pts.emplace_back(v.X(q.x() * 1e3), v.Y(q.y() * 1e3));
        const std::string d = g.dash(cv.name);
        svg.raw(fmt::format("<g class=\"curve\"><title>{}: {}</title>\n", esc(m), esc(cv.name)));
        svg.polyline(pts, fmt::format("stroke=\"{}\" stroke-width=\"1.8\"{}", c.colour(m),
                                      d.empty() ? "" : fmt::format(" stroke-dasharray=\"{}\"", d)));
        svg.raw("</g>\n");
      }
}

void draw_measured_points(Svg& svg, const PanelView& v, const PanelData& d) {
  const auto& X = v.X;
  const auto& Y = v.Y;
  for (const auto* pt : d.points) {
    const double px_ = X(pt->x * 1e3), py = Y(pt->y * 1e3);
    std::string tip = fmt::format("measured {} boundary at x = {:.1f} mm: y = {:.1f}", name(pt->boundary),
                                  pt->x * 1e3, pt->y * 1e3);

    if (pt->uncertainty) {
      const double u = *pt->uncertainty * 1e3;
      tip += fmt::format(" ± {:.1f}", u);
      if (u * v.k > 2.0) {
        svg.line(px_, Y(pt->y * 1e3 + u), px_, Y(pt->y * 1e3 - u), "stroke=\"#111\" stroke-width=\"1\"");
        svg.line(px_ - 3, Y(pt->y * 1e3 + u), px_ + 3, Y(pt->y * 1e3 + u), "stroke=\"#111\"");
        svg.line(px_ - 3, Y(pt->y * 1e3 - u), px_ + 3, Y(pt->y * 1e3 - u), "stroke=\"#111\"");
      }
    }
    if (d.thinned)
      tip += fmt::format(" mm ({} of the condition's {} measured points drawn; all in trajectory.csv)", d.points.size(),
                         d.measured_here);
    else
      tip += " mm";
    svg.marker(boundary_shape(pt->boundary), px_, py, 7, kMeasuredColour, true, tip);
  }
}

// Impact points on the plate face: models hollow and larger, measured filled on top.
void draw_impact_points(Svg& svg, const PanelView& v, const Context& c, const PanelData& d, const Station& s) {
  const auto& X = v.X;
  const auto& Y = v.Y;
  for (const auto& [m, y] : d.model_impacts) {
    std::string tip = fmt::format("{}: impact point y_R = {:.1f} mm", m, y);
    if (d.meas_y) tip += fmt::format(" (error {:+.1f} mm)", y - d.meas_y->value * 1e3);
    svg.marker(Shape::diamond, X(face_x(s, y / 1e3) * 1e3), Y(y), 13, c.colour(m), false, tip);
  }
  if (const auto* meas_y = d.meas_y) {
    const double y = meas_y->value * 1e3, xx = X(face_x(s, meas_y->value) * 1e3);
    std::string tip = fmt::format("measured impact point y_R = {:.1f}", y);
    if (meas_y->uncertainty) {
      const double u = *meas_y->uncertainty * 1e3;
      tip += fmt::format(" ± {:.1f}", u);
      if (u * v.k > 2.0) svg.line(xx, Y(y + u), xx, Y(y - u), "stroke=\"#111\" stroke-width=\"1.2\"");
    }
    svg.marker(Shape::diamond, xx, Y(y), 8, kMeasuredColour, true, tip + " mm");
  }
}

std::string missing_geometry_panel(const ConditionRow& row, const std::string& pid) {
  Svg svg(300, 80, "plot trajectory-panel", pid, fmt::format("Stream picture of {}", row.name));
  svg.title(shorten(row.name, 40));
  svg.text(150, 50, "no geometry for this condition in the dataset", "middle", "font-size=\"12\"");
  return svg.finish();
}

// One condition's picture: the rig, the models' clouds and curves, the measured points and the
// impact points, clipped to the frame; the plate strip beside it.
std::string panel_svg(const Context& c, const validation::ValidationResult& r, const GridStyle& g,
                      const ConditionRow& row, const std::string& pid) {
  const PanelData d = panel_data(c, r, g, row);
  if (!row.station) return missing_geometry_panel(row, pid);
  const Station& s = *row.station;
  const PanelView v = panel_view(r, row, d);
  Svg svg(v.W, v.H, "plot trajectory-panel", pid, fmt::format("Stream picture of {}", row.name));
  svg.title(shorten(fmt::format("{} — {}, {}", row.name, row.speed_label(), row.flow_label()),
                    static_cast<std::size_t>(std::max(20.0, (v.W - 20.0) / 8.5))));
  draw_axes(svg, v);
  const std::string clip = svg.clip(v.f);
  svg.raw(fmt::format("<g clip-path=\"url(#{})\">\n", clip));
  draw_rig(svg, v, s);
  draw_model_curves(svg, v, c, r, g, row);
  draw_measured_points(svg, v, d);
  draw_impact_points(svg, v, c, d, s);
  svg.raw("</g>\n");
  if (v.strip) draw_plate_strip(svg, v.sf, c, d.meas_y, d.model_impacts, d.hits, [&](const std::string& n) { return g.dash(n); });
  return svg.finish();
}

}  // namespace

std::string trajectory_grid(const Context& c, const validation::ValidationResult& r, std::string_view id,
                            double legend_width) {
  const GridStyle g = grid_style(c, r);
  std::string o = fmt::format("<figure class=\"traj-figure\" id=\"{}\">\n", esc(id));
  o += legend_svg(g, grid_legend(c, r, g), id, legend_width);
  o += "<div class=\"traj-grid\">\n";
  std::size_t panel = 0;
  for (const auto& row : c.conditions) o += panel_svg(c, r, g, row, fmt::format("{}-{}", id, panel++));
  o += "</div>\n</figure>\n";
  return o;
}

}  // namespace chutelab::reports
