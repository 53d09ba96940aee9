#pragma once
// Small helpers to write inline SVG by hand: escaping, number formatting, "nice" axis ticks,
// linear/log scales, axes, markers and legends. The report has no script and no external asset,
// so every picture is plain SVG text built here; everything is deterministic (fixed decimals, no
// locale) so that the same inputs give a byte-identical report.
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace chutelab::reports {

// Text for HTML and SVG (element content and attribute values alike).
std::string esc(std::string_view s);
// Text for Markdown: HTML-significant and Markdown-significant characters neutralised, so a
// condition called "a|b<c>" neither breaks a table nor injects markup.
std::string md_esc(std::string_view s);
// The text md_esc was given back (for pages rendered from their own Markdown, which escape again).
std::string md_unesc(std::string_view s);
// "R_n" -> "R<sub>n</sub>" (escaped) for headings and legends in HTML.
std::string symbol_html(std::string_view symbol);

// "R_n" -> "R<tspan ...>n</tspan>" (escaped) for SVG text drawn with Svg::markup.
std::string symbol_svg(std::string_view symbol);

// Fixed decimals, never "-0.00".
std::string fixed(double v, int decimals);
// Decimals that show about `digits` significant digits of the largest magnitude in a column.
int decimals_for(double max_abs, int digits = 4);
// SVG coordinate (one decimal is sub-pixel enough and keeps the file small).
std::string px(double v);

// Axis ticks on "nice" numbers (1, 2, 5 x 10^k) covering [lo, hi].
struct Ticks {
  double lo = 0.0, hi = 1.0, step = 1.0;  // extended range (multiples of step)
  std::vector<double> values;
  int decimals = 0;                       // enough to tell neighbouring ticks apart
  bool log = false;                       // decade labels: shortest form (0.1, 1, 10)
  std::string label(double v) const;
};
Ticks nice_ticks(double lo, double hi, int target = 6);
// Ticks strictly inside [lo, hi] (no range extension), for axes whose range is fixed by geometry.
Ticks inner_ticks(double lo, double hi, int target = 6);
// Decade ticks for a log axis covering [lo, hi] (lo > 0); range extended to whole decades.
Ticks log_ticks(double lo, double hi);

// Maps a data interval onto a pixel interval; log when asked (data must then be > 0).
struct Scale {
  double d0 = 0.0, d1 = 1.0, r0 = 0.0, r1 = 1.0;
  bool log = false;
  double operator()(double v) const;
};

// Marker shapes, in the order models get them.
enum class Shape { circle, square, triangle_up, diamond, triangle_down, cross };

struct LegendEntry {
  enum class Kind { line, box, marker } kind = Kind::line;
  std::string label{};   // plain text
  std::string colour{};
  std::string dash{};    // stroke-dasharray, "" = solid
  Shape shape = Shape::circle;
  bool filled = true;
  double opacity = 1.0;
};

// A plot area in pixels inside an SVG.
struct Frame {
  double left = 0.0, top = 0.0, width = 0.0, height = 0.0;
  double right() const { return left + width; }
  double bottom() const { return top + height; }
};

class Svg {
 public:
  // `cls` is the element's class (the browser test finds plots by it), `id` must be unique in the
  // page (clip paths derive theirs from it: inline SVGs share the document's id space), `label`
  // is the accessible name.
  Svg(double width, double height, std::string_view cls, std::string_view id,
      std::string_view label);
  double width() const { return width_; }
  double height() const { return height_; }

  void raw(std::string_view s) { out_ += s; }
  void line(double x1, double y1, double x2, double y2, std::string_view attrs);
  void rect(double x, double y, double w, double h, std::string_view attrs,
            std::string_view title = {});
  void polyline(const std::vector<std::pair<double, double>>& pts, std::string_view attrs);
  // Text is escaped here; `attrs` are extra attributes (already safe).
  void text(double x, double y, std::string_view s, std::string_view anchor = "start",
            std::string_view attrs = {});
  // Like text(), but `markup` is already-escaped SVG text content (e.g. from symbol_svg).
  void markup(double x, double y, std::string_view markup, std::string_view anchor = "start",
              std::string_view attrs = {});
  void marker(Shape shape, double x, double y, double size, std::string_view colour, bool filled,
              std::string_view title = {});
  // A title centred over the whole picture.
  void title(std::string_view s);
  // Frame, grid, ticks and tick labels; axis titles when non-empty. The y title is rotated.
  void axes(const Frame& f, const Scale& x, const Ticks& xt, const Scale& y, const Ticks& yt,
            std::string_view xlabel, std::string_view ylabel, bool grid = true);
  // Only the y axis (categorical charts label their x positions themselves).
  void y_axis(const Frame& f, const Scale& y, const Ticks& yt, std::string_view ylabel,
              bool grid = true);
  // Horizontal legend that wraps within `width`; returns the height it took.
  double legend(double x, double y, double width, const std::vector<LegendEntry>& entries);
  std::string finish();

  // The clip path id for a frame (clipped drawing stays inside the axes).
  std::string clip(const Frame& f);

 private:
  double width_, height_;
  std::string out_;
  int clips_ = 0;
  std::string id_;
};

// One SVG file a viewer or an editor opens on its own, from a figure's inline SVG (one chart, or the
// panels of a grid, laid out in rows as a page lays them: wrapping at the widest, 14 px apart across
// and 10 px down): the SVG namespace, `title`, the page's text style and a white ground.
std::string svg_file(std::string_view figure_html, std::string_view title);

double legend_height(double width, const std::vector<LegendEntry>& entries);
// Rough text width for layout (no font metrics in a report generator; 0.6 em per character
// over-estimates slightly for the sans-serif fonts a browser picks, which is the safe side).
double text_width(std::string_view s, double font_px);
// Shortens to at most n characters (UTF-8 aware), with an ellipsis.
std::string shorten(std::string_view s, std::size_t n);

}  // namespace chutelab::reports
