#include "reports/sensitivity_page.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "reports/svg.h"

namespace chutelab::reports {

using studies::mm_text;
using studies::run_notes;
using studies::SensitivityStudy;
using studies::VariantGroup;

std::string dataset_text(const SensitivityStudy& s, bool markdown) {
  auto code = [&](const std::string& x) { return markdown ? "`" + md_esc(x) + "`" : x; };
  if (s.dataset_name.empty()) return code(s.dataset) + " (dataset name not recorded)";
  return code(s.dataset_name) + (s.dataset.empty() ? std::string() : " (" + code(s.dataset) + ")");
}

namespace {
constexpr std::string_view kChartTitle = "Mean resultant plate force and its fluctuation per variant";
}  // namespace

std::string sensitivity_md(const SensitivityStudy& s) {
  std::string md = "# Sensitivity of the plate force (the reference study's Table 6)\n\n";
  md += fmt::format("![{}](sensitivity.svg)\n\n", kChartTitle);
  md += fmt::format("Dataset {}, condition `{}` (V_b = {:g} m/s, {:.1f} t/h), quality `{}`; {} DEM runs.\n\n",
                    dataset_text(s, true), md_esc(s.condition), s.belt_speed, s.mass_flow * 3.6,
                    s.quality, s.rows.size());
  md += s.verdict.text + "\n\n";
  md += "| variant | what changes | d (mm) | dt (µs) | dt / t_c | R_n (N) | R_s (N) | R (N) | sd R_n (N) | sd R_s (N) | sd R (N) | "
        "change of R vs base (%) | work (10⁶ particle-steps) |\n";
  md += "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
  for (const auto& r : s.rows) {
    const auto& o = r.outcome;
    md += fmt::format("| {} | {} | {} | {:.2f} | {} | {:.1f} ± {:.1f} | {:.1f} ± {:.1f} | {:.1f} ± {:.1f} | {:.1f} | {:.1f} | {:.1f} | {} | {:.0f} |\n",
                      r.variant.key, md_esc(r.variant.label), mm_text(o.diameter), o.dt * 1e6,
                      o.collision_time > 0.0 ? fmt::format("{:.3f}", o.dt / o.collision_time) : std::string("–"),
                      o.normal.value,
                      o.normal.se, o.shear.value, o.shear.se, o.resultant.value, o.resultant.se, o.fluct_normal,
                      o.fluct_shear, o.fluct_resultant,
                      &r == &s.rows[0] ? std::string("—") : fmt::format("{:+.1f} ± {:.1f}", r.change.value, r.change.se),
                      static_cast<double>(o.steps) * static_cast<double>(o.particles) * 1e-6);
  }
  md += "\nMeans are over the steady window of the plate load cell with block standard errors (±); sd is the "
        "standard deviation of the load-cell samples in that window (the fluctuation); change = R / R_base - 1; work = "
        "steps x peak particles, a measure of cost that does not depend on the machine (wall-clock times are in "
        "sensitivity-timing.csv, which differs from run to run).\n";
  std::vector<std::string> notes = run_notes(s);
  for (const auto& r : s.rows) {
    if (!r.outcome.steady) notes.push_back(fmt::format("{}: no steady window within the time limit (means uncertain)", r.variant.key));
    for (const auto& n : r.outcome.notes) notes.push_back(fmt::format("{}: {}", r.variant.key, n));
  }
  if (!notes.empty()) {
    md += "\n## Notes\n\n";
    for (const auto& n : notes) md += "- " + md_esc(n) + "\n";
  }
  return md;
}

std::string sensitivity_chart(const SensitivityStudy& s, std::string_view id) {
  const std::size_t n = s.rows.size();
  double rmax = 0.0, fmax = 0.0;
  for (const auto& r : s.rows) {
    rmax = std::max(rmax, r.outcome.resultant.value + r.outcome.resultant.se);
    fmax = std::max(fmax, r.outcome.fluct_resultant);
  }
  auto colour = [](VariantGroup g) {
    switch (g) {
      case VariantGroup::base: return "#555555";
      case VariantGroup::contact: return "#1f77b4";
      case VariantGroup::shape: return "#2ca02c";
      case VariantGroup::time_step: return "#9467bd";
      case VariantGroup::modulus: return "#ff7f0e";
      case VariantGroup::size: return "#d62728";
    }
    return "#000000";
  };
  std::vector<LegendEntry> legend;
  for (VariantGroup g : {VariantGroup::base, VariantGroup::contact, VariantGroup::shape, VariantGroup::time_step,
                         VariantGroup::modulus, VariantGroup::size})
    legend.push_back({LegendEntry::Kind::box, std::string(name(g)), colour(g)});
  const double W = 960, lh = legend_height(W - 40, legend);
  Svg svg(W, 70 + lh + 330, "plot sensitivity", id, "Mean resultant plate force and its fluctuation per variant");
  svg.title("Plate force per variant: mean R (± 1 standard error) and its fluctuation (sd of R)");
  svg.legend(20, 28, W - 40, legend);
  auto panel = [&](double left, double top_value, const std::string& ylabel, bool mean) {
    Frame f{left, 40 + lh + 10, 370, 250};
    const Ticks yt = nice_ticks(0.0, top_value > 0.0 ? top_value * 1.08 : 1.0, 6);
    const Scale y{0.0, yt.hi, f.bottom(), f.top};
    svg.y_axis(f, y, yt, ylabel);
    svg.line(f.left, f.bottom(), f.right(), f.bottom(), "stroke=\"#444\"");
    const double gw = f.width / static_cast<double>(std::max<std::size_t>(n, 1));
    if (mean && n > 0) {
      const double yb = y(s.rows[0].outcome.resultant.value);
      svg.line(f.left, yb, f.right(), yb, "stroke=\"#555\" stroke-dasharray=\"4,3\"");
    }
    for (std::size_t k = 0; k < n; ++k) {
      const auto& r = s.rows[k];
      const double v = mean ? r.outcome.resultant.value : r.outcome.fluct_resultant;
      const double cx = f.left + gw * (static_cast<double>(k) + 0.5), bw = std::min(30.0, 0.6 * gw);
      const double yv = y(std::max(0.0, v));
      svg.rect(cx - bw / 2, yv, bw, f.bottom() - yv, fmt::format("fill=\"{}\" class=\"bar\"", colour(r.variant.group)),
               mean ? fmt::format("{}: R = {:.1f} ± {:.1f} N ({})", r.variant.key, v, r.outcome.resultant.se,
                                  k == 0 ? std::string("base") : fmt::format("{:+.1f} %", r.change.value))
                    : fmt::format("{}: sd of R = {:.1f} N", r.variant.key, v));
      if (mean && r.outcome.resultant.se > 0.0) {
        const double y1 = y(v + r.outcome.resultant.se), y2 = y(std::max(0.0, v - r.outcome.resultant.se));
        const std::string st = "stroke=\"#000\" stroke-width=\"1.2\"";
        svg.line(cx, y1, cx, y2, st);
        svg.line(cx - 4, y1, cx + 4, y1, st);
        svg.line(cx - 4, y2, cx + 4, y2, st);
      }
      svg.text(cx, f.bottom() + 14, r.variant.key, "end",
               fmt::format("font-size=\"11\" transform=\"rotate(-35 {} {})\"", px(cx), px(f.bottom() + 14)));
    }
  };
  panel(70, rmax, "mean resultant R (N)", true);
  panel(560, fmax, "fluctuation: sd of R (N)", false);
  return svg.finish();
}

std::string sensitivity_svg(const SensitivityStudy& s) {
  return svg_file(sensitivity_chart(s, "sensitivity-chart"), kChartTitle);
}

std::string sensitivity_html(const SensitivityStudy& s) {
  const std::size_t n = s.rows.size();

  // Page: verdict, chart, table (the Markdown's table rendered), notes.
  const std::string md = sensitivity_md(s);
  std::string body = "<h1>Sensitivity of the plate force (the reference study's Table 6)</h1>\n";
  body += fmt::format("<p>Dataset {}, condition <code>{}</code> (V<sub>b</sub> = {:g} m/s, {:.1f} t/h), "
                      "quality <code>{}</code>; {} DEM runs.</p>\n",
                      esc(dataset_text(s, false)), esc(s.condition), s.belt_speed, s.mass_flow * 3.6, esc(s.quality), n);
  body += fmt::format("<p class=\"verdict {}\">{}</p>\n", s.verdict.reproduced() ? "ok" : "not", esc(s.verdict.text));
  body += sensitivity_chart(s, "sensitivity-chart") + "\n<table>\n";
  std::size_t pos = 0;
  bool header = true;
  std::string tail;
  while (pos < md.size()) {
    const auto end = md.find('\n', pos);
    const std::string line = md.substr(pos, end == std::string::npos ? std::string::npos : end - pos);
    pos = end == std::string::npos ? md.size() : end + 1;
    if (line.empty() || line[0] != '|') {
      if (!header && line.rfind("- ", 0) == 0) tail += "<p class=\"item\">• " + esc(md_unesc(line.substr(2))) + "</p>\n";
      else if (!header && line.rfind("Means are", 0) == 0) tail += "<p>" + esc(line) + "</p>\n";
      else if (line.rfind("## ", 0) == 0) tail += "<h2>" + esc(line.substr(3)) + "</h2>\n";
      continue;
    }
    if (line.find("|---") == 0) continue;
    std::string row = "<tr>";
    std::size_t a = 1;
    while (a < line.size()) {
      const auto b = line.find('|', a);
      if (b == std::string::npos) break;
      row += fmt::format("<{0}>{1}</{0}>", header ? "th" : "td", esc(md_unesc(line.substr(a, b - a))));
      a = b + 1;
    }
    body += row + "</tr>\n";
    header = false;
  }
  body += "</table>\n" + tail;
  return "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>chutelab sensitivity</title>"
         "<style>body{font-family:sans-serif;max-width:1000px;margin:2em auto;color:#222}"
         "table{border-collapse:collapse;margin:1em 0;font-size:13px}td,th{border:1px solid #ccc;padding:3px 6px;"
         "text-align:right}th{background:#f3f3f3}td:nth-child(2){text-align:left}p.verdict{padding:8px;border-left:4px solid}"
         "p.ok{border-color:#2e7d32;background:#eef7ee}p.not{border-color:#c62828;background:#fbeeee}"
         "p.item{margin:0.3em 0 0.3em 1em}svg{max-width:100%;height:auto}</style></head><body>\n" +
         body + "</body></html>\n";
}

}  // namespace chutelab::reports
