#include "reports/svg.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <fmt/format.h>

#include "core/markup.h"
#include "core/utf8.h"

namespace chutelab::reports {

std::string esc(std::string_view raw) {
  // The pages declare UTF-8: names from users' files are made valid UTF-8 before escaping.
  return markup_escape(to_utf8(raw), Markup::html);
}

std::string md_esc(std::string_view raw) {
  const std::string s = to_utf8(raw);
  std::string o;
  o.reserve(s.size());
  auto next_is = [&](std::size_t k, auto pred) {
    return k + 1 < s.size() && pred(static_cast<unsigned char>(s[k + 1]));
  };
  for (std::size_t k = 0; k < s.size(); ++k) {
    const char c = s[k];
    switch (c) {
      // Markdown renderers pass inline HTML and entities through. A backslash escapes the few
      // places where they could start (a tag, an entity, a quote at the start), so the file reads
      // as text, without entities: "|E/u| > 2" stays as it is.
      case '<':
        if (next_is(k, [](unsigned char n) { return std::isalpha(n) || n == '/' || n == '!' || n == '?'; })) o += '\\';
        o += c;
        break;
      case '&': {
        // An entity is & then # or a name, then ';': "V&V" and "R & D" stay as they are.
        std::size_t e = k + 1;
        while (e < s.size() && (std::isalnum(static_cast<unsigned char>(s[e])) || s[e] == '#')) ++e;
        if (e > k + 1 && e < s.size() && s[e] == ';') o += '\\';
        o += c;
        break;
      }
      case '>':
        if (k == 0) o += '\\';
        o += c;
        break;
      // Table cell separator and emphasis/link/code syntax.
      case '|': case '\\': case '*': case '_': case '`': case '[': case ']':
        o += '\\';
        o += c;
        break;
      case '\n': case '\r': o += ' '; break;
      default: o += c;
    }
  }
  return o;
}

std::string md_unesc(std::string_view s) {
  std::string o;
  o.reserve(s.size());
  for (std::size_t k = 0; k < s.size(); ++k) {
    if (s[k] == '\\' && k + 1 < s.size()) {
      o += s[++k];
      continue;
    }
    if (s[k] == '&') {
      bool done = false;
      for (auto [entity, c] : {std::pair{std::string_view("&amp;"), '&'}, {"&lt;", '<'}, {"&gt;", '>'}})
        if (s.substr(k, entity.size()) == entity) {
          o += c;
          k += entity.size() - 1;
          done = true;
          break;
        }
      if (done) continue;
    }
    o += s[k];
  }
  return o;
}

std::string symbol_html(std::string_view symbol) {
  const auto u = symbol.find('_');
  if (u == std::string_view::npos) return esc(symbol);
  return esc(symbol.substr(0, u)) + "<sub>" + esc(symbol.substr(u + 1)) + "</sub>";
}

std::string symbol_svg(std::string_view symbol) {
  const auto u = symbol.find('_');
  if (u == std::string_view::npos) return esc(symbol);
  return esc(symbol.substr(0, u)) + "<tspan baseline-shift=\"sub\" font-size=\"75%\">" +
         esc(symbol.substr(u + 1)) + "</tspan>";
}

std::string fixed(double v, int decimals) {
  if (!std::isfinite(v)) return v > 0 ? "inf" : (v < 0 ? "-inf" : "nan");
  std::string s = fmt::format("{:.{}f}", v, std::max(0, decimals));
  // A value that rounds to zero prints without a sign.
  if (s.front() == '-' && s.find_first_not_of("-0.") == std::string::npos) s.erase(0, 1);
  return s;
}

int decimals_for(double max_abs, int digits) {
  if (!(max_abs > 0.0) || !std::isfinite(max_abs)) return 2;
  const int mag = static_cast<int>(std::floor(std::log10(max_abs)));
  return std::clamp(digits - 1 - mag, 0, 4);
}

std::string px(double v) { return fixed(v, 1); }

namespace {

// Heckbert's nice numbers: the nearest (round) or next larger 1, 2, 5 x 10^k.
double nice_number(double x, bool round) {
  const double e = std::floor(std::log10(x));
  const double f = x / std::pow(10.0, e);
  double nf;
  if (round) nf = f < 1.5 ? 1 : f < 3 ? 2 : f < 7 ? 5 : 10;
  else nf = f <= 1 ? 1 : f <= 2 ? 2 : f <= 5 ? 5 : 10;
  return nf * std::pow(10.0, e);
}

void widen_degenerate(double& lo, double& hi) {
  if (!std::isfinite(lo) || !std::isfinite(hi)) { lo = 0.0; hi = 1.0; }
  if (hi < lo) std::swap(lo, hi);
  if (hi - lo < 1e-12 * std::max(1.0, std::abs(hi))) {
    const double pad = lo == 0.0 ? 1.0 : 0.1 * std::abs(lo);
    lo -= pad;
    hi += pad;
  }
}

int tick_decimals(double step) {
  return std::max(0, -static_cast<int>(std::floor(std::log10(step) + 1e-9)));
}

}  // namespace

std::string Ticks::label(double v) const {
  if (log) return fmt::format("{:g}", v);
  return fixed(v, decimals);
}

Ticks nice_ticks(double lo, double hi, int target) {
  widen_degenerate(lo, hi);
  Ticks t;
  t.step = nice_number((hi - lo) / std::max(1, target - 1), true);
  t.lo = std::floor(lo / t.step + 1e-9) * t.step;
  t.hi = std::ceil(hi / t.step - 1e-9) * t.step;
  // Index times step, not repeated addition: no creeping rounding error in the labels.
  const long n = std::lround((t.hi - t.lo) / t.step);
  for (long i = 0; i <= n; ++i) t.values.push_back(t.lo + static_cast<double>(i) * t.step);
  t.decimals = tick_decimals(t.step);
  return t;
}

Ticks inner_ticks(double lo, double hi, int target) {
  widen_degenerate(lo, hi);
  Ticks t;
  t.lo = lo;
  t.hi = hi;
  t.step = nice_number((hi - lo) / std::max(1, target - 1), true);
  const long first = static_cast<long>(std::ceil(lo / t.step - 1e-9));
  const long last = static_cast<long>(std::floor(hi / t.step + 1e-9));
  for (long i = first; i <= last; ++i) t.values.push_back(static_cast<double>(i) * t.step);
  t.decimals = tick_decimals(t.step);
  return t;
}

Ticks log_ticks(double lo, double hi) {
  lo = std::max(lo, 1e-12);
  hi = std::max(hi, lo * 10.0);
  Ticks t;
  const int e0 = static_cast<int>(std::floor(std::log10(lo) + 1e-9));
  const int e1 = static_cast<int>(std::ceil(std::log10(hi) - 1e-9));
  t.lo = std::pow(10.0, e0);
  t.hi = std::pow(10.0, e1);
  t.step = 10.0;
  for (int e = e0; e <= e1; ++e) {
    const double d = std::pow(10.0, e);
    t.values.push_back(d);
    // Few decades: intermediate 2 and 5 keep the axis readable.
    if (e1 - e0 <= 2 && e < e1) {
      t.values.push_back(2 * d);
      t.values.push_back(5 * d);
    }
  }
  std::sort(t.values.begin(), t.values.end());
  t.decimals = std::max(0, -e0);
  t.log = true;
  return t;
}

double Scale::operator()(double v) const {
  double t;
  if (log) t = (std::log10(std::max(v, 1e-300)) - std::log10(d0)) / (std::log10(d1) - std::log10(d0));
  else t = (v - d0) / (d1 - d0);
  return r0 + t * (r1 - r0);
}

Svg::Svg(double width, double height, std::string_view cls, std::string_view id,
         std::string_view label)
    : width_(width), height_(height), id_(id) {
  out_ = fmt::format(
      "<svg class=\"{}\" id=\"{}\" viewBox=\"0 0 {} {}\" width=\"{}\" height=\"{}\" role=\"img\" "
      "aria-label=\"{}\">\n",
      esc(cls), esc(id), px(width), px(height), px(width), px(height), esc(label));
}

void Svg::line(double x1, double y1, double x2, double y2, std::string_view attrs) {
  out_ += fmt::format("<line x1=\"{}\" y1=\"{}\" x2=\"{}\" y2=\"{}\" {}/>\n", px(x1), px(y1), px(x2),
                      px(y2), attrs);
}

void Svg::rect(double x, double y, double w, double h, std::string_view attrs, std::string_view title) {
  out_ += fmt::format("<rect x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" {}", px(x), px(y),
                      px(std::max(0.0, w)), px(std::max(0.0, h)), attrs);
  if (title.empty()) out_ += "/>\n";
  else out_ += fmt::format("><title>{}</title></rect>\n", esc(title));
}

void Svg::polyline(const std::vector<std::pair<double, double>>& pts, std::string_view attrs) {
  if (pts.size() < 2) return;
  std::string p;
  for (const auto& [x, y] : pts) {
    if (!p.empty()) p += ' ';
    p += px(x) + ',' + px(y);
  }
  out_ += fmt::format("<polyline fill=\"none\" points=\"{}\" {}/>\n", p, attrs);
}

void Svg::text(double x, double y, std::string_view s, std::string_view anchor, std::string_view attrs) {
  out_ += fmt::format("<text x=\"{}\" y=\"{}\" text-anchor=\"{}\" {}>{}</text>\n", px(x), px(y),
                      anchor, attrs, esc(s));
}

void Svg::markup(double x, double y, std::string_view m, std::string_view anchor, std::string_view attrs) {
  out_ += fmt::format("<text x=\"{}\" y=\"{}\" text-anchor=\"{}\" {}>{}</text>\n", px(x), px(y), anchor, attrs, m);
}

void Svg::marker(Shape shape, double x, double y, double size, std::string_view colour, bool filled,
                 std::string_view title) {
  const double h = size / 2.0;
  const std::string paint =
      fmt::format("fill=\"{}\" stroke=\"{}\" stroke-width=\"1.3\"", filled ? colour : "#fff", colour);
  std::string open;
  std::string tag;
  auto poly = [&](std::initializer_list<std::pair<double, double>> pts) {
    std::string p;
    for (const auto& [dx, dy] : pts) p += fmt::format("{}{},{}", p.empty() ? "" : " ", px(x + dx), px(y + dy));
    tag = "polygon";
    open = fmt::format("<polygon points=\"{}\" {}", p, paint);
  };
  switch (shape) {
    case Shape::circle:
      tag = "circle";
      open = fmt::format("<circle cx=\"{}\" cy=\"{}\" r=\"{}\" {}", px(x), px(y), px(h), paint);
      break;
    case Shape::square:
      tag = "rect";
      open = fmt::format("<rect x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" {}", px(x - h * 0.85),
                         px(y - h * 0.85), px(size * 0.85), px(size * 0.85), paint);
      break;
    case Shape::triangle_up: poly({{0, -h * 1.1}, {h, h * 0.8}, {-h, h * 0.8}}); break;
    case Shape::triangle_down: poly({{0, h * 1.1}, {h, -h * 0.8}, {-h, -h * 0.8}}); break;
    case Shape::diamond: poly({{0, -h * 1.2}, {h, 0}, {0, h * 1.2}, {-h, 0}}); break;
    case Shape::cross:
      tag = "path";
      open = fmt::format("<path d=\"M{} {}L{} {}M{} {}L{} {}\" stroke=\"{}\" stroke-width=\"2\" fill=\"none\"",
                         px(x - h), px(y - h), px(x + h), px(y + h), px(x - h), px(y + h), px(x + h),
                         px(y - h), colour);
      break;
  }
  if (title.empty()) out_ += open + "/>\n";
  else out_ += fmt::format("{}><title>{}</title></{}>\n", open, esc(title), tag);
}

void Svg::title(std::string_view s) {
  text(width_ / 2.0, 18.0, s, "middle", "class=\"plot-title\" font-size=\"14\" font-weight=\"600\"");
}

namespace {
double max_label_width(const Ticks& t, double font) {
  double w = 0.0;
  for (double v : t.values) w = std::max(w, text_width(t.label(v), font));
  return w;
}
}  // namespace

void Svg::y_axis(const Frame& f, const Scale& y, const Ticks& yt, std::string_view ylabel, bool grid) {
  for (double v : yt.values) {
    const double yy = y(v);
    if (yy < f.top - 0.5 || yy > f.bottom() + 0.5) continue;
    if (grid) line(f.left, yy, f.right(), yy, "stroke=\"#e2e2e2\" stroke-width=\"1\"");
    line(f.left - 4, yy, f.left, yy, "stroke=\"#444\"");
    text(f.left - 7, yy + 4, yt.label(v), "end", "font-size=\"11\" fill=\"#333\"");
  }
  line(f.left, f.top, f.left, f.bottom(), "stroke=\"#444\"");
  if (!ylabel.empty()) {
    const double x = f.left - 14 - max_label_width(yt, 11);
    out_ += fmt::format(
        "<text x=\"{}\" y=\"{}\" text-anchor=\"middle\" transform=\"rotate(-90 {} {})\" "
        "class=\"axis-label\" font-size=\"12\">{}</text>\n",
        px(x), px(f.top + f.height / 2), px(x), px(f.top + f.height / 2), esc(ylabel));
  }
}

void Svg::axes(const Frame& f, const Scale& x, const Ticks& xt, const Scale& y, const Ticks& yt,
               std::string_view xlabel, std::string_view ylabel, bool grid) {
  for (double v : xt.values) {
    const double xx = x(v);
    if (xx < f.left - 0.5 || xx > f.right() + 0.5) continue;
    if (grid) line(xx, f.top, xx, f.bottom(), "stroke=\"#e2e2e2\" stroke-width=\"1\"");
    line(xx, f.bottom(), xx, f.bottom() + 4, "stroke=\"#444\"");
    text(xx, f.bottom() + 16, xt.label(v), "middle", "font-size=\"11\" fill=\"#333\"");
  }
  y_axis(f, y, yt, ylabel, grid);
  rect(f.left, f.top, f.width, f.height, "fill=\"none\" stroke=\"#444\"");
  if (!xlabel.empty())
    text(f.left + f.width / 2, f.bottom() + 32, xlabel, "middle",
         "class=\"axis-label\" font-size=\"12\"");
}

std::string Svg::clip(const Frame& f) {
  const std::string cid = fmt::format("{}-clip{}", id_, clips_++);
  out_ += fmt::format(
      "<clipPath id=\"{}\"><rect x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\"/></clipPath>\n",
      esc(cid), px(f.left), px(f.top), px(f.width), px(f.height));
  return esc(cid);
}

double text_width(std::string_view s, double font_px) {
  std::size_t chars = 0;
  for (unsigned char c : s)
    if ((c & 0xC0) != 0x80) ++chars;  // count UTF-8 code points, not bytes
  return 0.6 * font_px * static_cast<double>(chars);
}

std::string shorten(std::string_view s, std::size_t n) {
  std::size_t chars = 0, cut = s.size();
  for (std::size_t i = 0; i < s.size(); ++i) {
    if ((static_cast<unsigned char>(s[i]) & 0xC0) == 0x80) continue;
    if (chars == n - 1) cut = i;
    ++chars;
  }
  if (chars <= n) return std::string(s);
  return std::string(s.substr(0, cut)) + "\u2026";
}

namespace {
constexpr double kSwatch = 24.0, kGap = 5.0, kSpacing = 18.0, kRow = 18.0, kFont = 12.0;
double entry_width(const LegendEntry& e) { return kSwatch + kGap + text_width(e.label, kFont) + kSpacing; }

constexpr std::string_view kXmlProlog = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
constexpr std::string_view kFigureStyle =
    "<style>text { font-family: system-ui, -apple-system, \"Segoe UI\", Roboto, \"Helvetica Neue\", Arial, "
    "sans-serif; fill: #1b1b1b; }</style>\n";

// The top-level <svg>...</svg> elements of a figure's HTML, in order (a chart is one; a grid of
// panels, as the trajectories', several).
std::vector<std::string_view> svg_elements(std::string_view html) {
  std::vector<std::string_view> out;
  for (auto at = html.find("<svg "); at != std::string_view::npos; at = html.find("<svg ", at)) {
    const auto end = html.find("</svg>", at);
    if (end == std::string_view::npos) break;
    out.push_back(html.substr(at, end + 6 - at));
    at = end;
  }
  return out;
}

// A number attribute of an element's opening tag (` width="980.0"`); 0 when absent.
double tag_number(std::string_view element, std::string_view name) {
  const std::string_view tag = element.substr(0, element.find('>'));
  const std::string key = " " + std::string(name) + "=\"";
  const auto at = tag.find(key);
  if (at == std::string_view::npos) return 0.0;
  const auto from = at + key.size();
  return std::strtod(std::string(tag.substr(from, tag.find('"', from) - from)).c_str(), nullptr);
}

}  // namespace

std::string svg_file(std::string_view html, std::string_view caption) {
  const auto parts = svg_elements(html);
  if (parts.empty()) return {};
  const std::string head = fmt::format("<title>{}</title>\n{}", esc(caption), kFigureStyle);
  if (parts.size() == 1) {
    std::string svg(parts.front());
    svg.insert(svg.find('>') + 1, "\n" + head + "<rect width=\"100%\" height=\"100%\" fill=\"#fff\"/>");
    svg.insert(5, "xmlns=\"http://www.w3.org/2000/svg\" ");
    return std::string(kXmlProlog) + svg + "\n";
  }
  double width = 0.0;
  for (const auto p : parts) width = std::max(width, tag_number(p, "width"));
  std::string body;
  double x = 0.0, y = 0.0, row = 0.0;
  for (const auto p : parts) {
    const double w = tag_number(p, "width"), h = tag_number(p, "height");
    if (x > 0.0 && x + w > width + 0.05) x = 0.0, y += row + 10.0, row = 0.0;
    body += fmt::format("<svg x=\"{}\" y=\"{}\" {}", px(x), px(y), p.substr(5));
    if (!body.ends_with('\n')) body += '\n';
    x += w + 14.0;
    row = std::max(row, h);
  }
  const double height = y + row;
  return std::string(kXmlProlog) + fmt::format(
      "<svg xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"0 0 {0} {1}\" width=\"{0}\" height=\"{1}\" role=\"img\" "
      "aria-label=\"{2}\">\n{3}<rect width=\"100%\" height=\"100%\" fill=\"#fff\"/>\n{4}</svg>\n",
      px(width), px(height), esc(caption), head, body);
}

double legend_height(double width, const std::vector<LegendEntry>& entries) {
  if (entries.empty()) return 0.0;
  double x = 0.0;
  int rows = 1;
  for (const auto& e : entries) {
    const double w = entry_width(e);
    if (x > 0.0 && x + w > width) { ++rows; x = 0.0; }
    x += w;
  }
  return rows * kRow;
}

double Svg::legend(double x0, double y0, double width, const std::vector<LegendEntry>& entries) {
  if (entries.empty()) return 0.0;
  out_ += "<g class=\"legend\">\n";
  double x = 0.0, y = 0.0;
  for (const auto& e : entries) {
    const double w = entry_width(e);
    if (x > 0.0 && x + w > width) { y += kRow; x = 0.0; }
    const double sx = x0 + x, sy = y0 + y + kRow / 2;
    const std::string opacity = e.opacity < 1.0 ? fmt::format(" opacity=\"{}\"", fixed(e.opacity, 2)) : "";
    switch (e.kind) {
      case LegendEntry::Kind::line:
        line(sx, sy, sx + kSwatch, sy,
             fmt::format("stroke=\"{}\" stroke-width=\"2\"{}{}", e.colour,
                         e.dash.empty() ? "" : fmt::format(" stroke-dasharray=\"{}\"", e.dash), opacity));
        break;
      case LegendEntry::Kind::box:
        rect(sx + 4, sy - 6, kSwatch - 8, 12,
             fmt::format("fill=\"{}\" stroke=\"{}\"{}", e.colour, e.colour, opacity));
        break;
      case LegendEntry::Kind::marker:
        if (!e.dash.empty() || e.opacity < 1.0)  // a marker drawn over a line style
          line(sx, sy, sx + kSwatch, sy, fmt::format("stroke=\"{}\" stroke-width=\"1.5\"{}", e.colour, opacity));
        marker(e.shape, sx + kSwatch / 2, sy, 9, e.colour, e.filled);
        break;
    }
    text(sx + kSwatch + kGap, sy + 4, e.label, "start", "font-size=\"12\"");
    x += w;
  }
  out_ += "</g>\n";
  return y + kRow;
}

std::string Svg::finish() { return out_ + "</svg>\n"; }

}  // namespace chutelab::reports
