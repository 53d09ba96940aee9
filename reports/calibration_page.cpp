#include "reports/calibration_page.h"

#include <cmath>

#include <fmt/format.h>

#include "reports/studies.h"
#include "reports/svg.h"

namespace chutelab::reports {
namespace {

using dem::rigs::CalibrationRow;
using dem::rigs::CalibrationStudy;
using dem::rigs::GrainKind;
using studies::CalibrationContext;
using studies::CalibrationPoint;
using studies::grain_label;

std::string num(double v, int decimals) { return std::isfinite(v) ? fixed(v, decimals) : "–"; }

std::string rig_text(const CalibrationStudy& s) {
  const auto& st = s.plan.settings;
  return fmt::format(
      "Swing-arm slump tester (reference study Fig. 5): {:.0f} mm I.D. split tube on a bed of glued grains of the same "
      "material filling a {:.0f} mm pipe; sample poured to about {:.0f} mm, settled (no grain faster than {:g} m/s), "
      "tube halves moved apart at {:g} m/s; Young's modulus x {:g} (a shorter run; the reference study found mean flow "
      "results insensitive to G x10 and /10). Bulk density: mass per volume of the settled column's core; angle of "
      "repose: line fit of the pile's surface profile over its flank (20-80 % of the peak); pile height: that line at "
      "the axis (the fitted cone's apex; a single pour scatters by ~0.6 % in bulk density and ~3 % in this height, "
      "5 seeds).",
      st.tube_diameter * 1e3, st.pipe_diameter * 1e3, st.fill_height * 1e3, st.settle_speed, st.open_speed,
      st.modulus_scale);
}

}  // namespace

std::string table3_md(const CalibrationStudy& s) {
  // Column pairs per shape, in the order asked for; a combination that did not run is a dash.
  std::string md = "| rolling friction mu_r | solid density (kg/m^3) |";
  std::string rule = "|---:|---:|";
  for (GrainKind k : s.plan.shapes) {
    md += fmt::format(" {0}: bulk density (kg/m^3) | {0}: pile height (mm) |", grain_label(s, k));
    rule += "---:|---:|";
  }
  md += "\n" + rule + "\n";
  for (double mu : s.plan.rolling)
    for (double rho : s.plan.density) {
      md += fmt::format("| {:g} | {:g} |", mu, rho);
      for (GrainKind k : s.plan.shapes) {
        const CalibrationRow* row = nullptr;
        int index = -1;
        for (std::size_t i = 0; i < s.rows.size(); ++i)
          if (s.rows[i].shape == k && s.rows[i].rolling_friction == mu && s.rows[i].solid_density == rho) {
            row = &s.rows[i];
            index = static_cast<int>(i);
          }
        if (!row) {
          md += " – | – |";
          continue;
        }
        const bool best = index == s.closest;
        const std::string b = best ? "**" : "";
        md += fmt::format(" {b}{:.0f}{b}{} | {b}{:.1f}{b} |", row->slump.bulk_density, best ? " ◀ closest" : "",
                          row->slump.pile_height * 1e3, fmt::arg("b", b));
      }
      md += "\n";
    }
  if (s.plan.targets.any()) {
    md += "| experiment (target) | |";
    for (std::size_t k = 0; k < s.plan.shapes.size(); ++k)
      md += fmt::format(" {} | {} |",
                        s.plan.targets.bulk_density ? fmt::format("{:.0f}", *s.plan.targets.bulk_density) : "–",
                        s.plan.targets.pile_height ? fmt::format("{:.1f}", *s.plan.targets.pile_height * 1e3) : "–");
    md += "\n";
  }
  return md;
}

namespace {

constexpr std::string_view kChartTitle = "Pile height and bulk density against rolling friction";

// The chart is the report's (reports/plot_calibration.cpp), drawn from the rows as calibration.csv has them.
std::string sweep_chart(const CalibrationStudy& s) {
  std::vector<CalibrationPoint> points;
  for (std::size_t k = 0; k < s.rows.size(); ++k) {
    const auto& r = s.rows[k];
    CalibrationPoint p;
    p.shape = std::string(name(r.shape));
    p.grain = grain_label(s, r.shape);
    p.rolling_friction = r.rolling_friction;
    p.solid_density = r.solid_density;
    p.bulk_density = r.slump.bulk_density;
    p.pile_height = r.slump.pile_height;
    p.closest = static_cast<int>(k) == s.closest;
    points.push_back(p);
  }
  return calibration_chart(points, {s.plan.targets.bulk_density, s.plan.targets.pile_height}, "calibration-sweep");
}

}  // namespace

std::string calibration_svg(const CalibrationStudy& s) { return svg_file(sweep_chart(s), kChartTitle); }

std::string calibration_md(const CalibrationContext& c, const CalibrationStudy& s) {
  std::string md = "# Slump-test calibration (reference study Table 3)\n\n";
  md += fmt::format("![{}](calibration.svg)\n\n", kChartTitle);
  md += fmt::format("Dataset `{}` (`{}`), quality `{}`; {} slump tests (run times: calibration-timing.csv).\n\n",
                    reports::md_esc(c.setup.name), reports::md_esc(c.dataset), c.quality, s.rows.size());
  md += rig_text(s) + "\n\n";
  md += fmt::format("Held constant from the dataset: mu_s = {:g} (particle-particle), e = {:g}, E = {:g} MPa, nu = {:g}.\n\n",
                    c.setup.material.friction_particle, c.setup.material.restitution_particle,
                    c.setup.material.youngs_modulus / 1e6, c.setup.material.poisson_ratio);
  md += fmt::format("Target (measured): {}.\n\n", studies::targets_text(s));
  md += "## Table 3 (the reference study's layout)\n\n";
  md += table3_md(s);
  md += "\n## Every slump test\n\n";
  md += "| particle | rolling friction mu_r | solid density (kg/m^3) | bulk density (kg/m^3) | pile height (mm) | "
        "angle of repose (deg) | grains | steps | distance to target |\n";
  md += "|---|---:|---:|---:|---:|---:|---:|---:|---:|\n";
  for (std::size_t k = 0; k < s.rows.size(); ++k) {
    const auto& r = s.rows[k];
    const bool best = static_cast<int>(k) == s.closest;
    const std::string b = best ? "**" : "";
    md += fmt::format("| {b}{}{b}{} | {b}{:g}{b} | {b}{:g}{b} | {b}{:.0f}{b} | {b}{:.1f}{b} | {} | {} | {} | {} |\n",
                      grain_label(s, r.shape), best ? " ◀ closest" : "", r.rolling_friction, r.solid_density,
                      r.slump.bulk_density, r.slump.pile_height * 1e3, num(r.slump.repose_angle_deg, 1),
                      r.slump.particles, r.slump.steps,
                      std::isfinite(r.distance) ? fmt::format("{:.1f} %", 100.0 * r.distance) : "–",
                      fmt::arg("b", b));
  }
  if (s.plan.targets.any())
    md += fmt::format("| experiment (target) | | | {} | {} | | | | |\n",
                      s.plan.targets.bulk_density ? fmt::format("{:.0f}", *s.plan.targets.bulk_density) : "–",
                      s.plan.targets.pile_height ? fmt::format("{:.1f}", *s.plan.targets.pile_height * 1e3) : "–");
  bool unsettled = false;
  for (const auto& r : s.rows) unsettled = unsettled || !r.slump.settled;
  if (unsettled) md += "\nSome runs reached their time limit before every grain came to rest (settled = 0 in the CSV).\n";
  md += "\n## What the sweep shows\n\n";
  for (const auto& f : studies::calibration_findings(s)) md += "- " + f + "\n";
  if (!s.incline.empty()) {
    md += "\n## Inclined-plane rig (particle-wall rolling friction)\n\n";
    md += "A sphere of the scaled size on the plate material, tilted in steps (bisection to 0.05 deg); onset = the "
          "first angle at which it accelerates down the slope. The reference study's Eq 10 (constant rolling torque mu_r F_n R) with "
          "Coulomb friction predicts tan(theta) = min(mu_r, mu_s): rolling when mu_r < mu_s, sliding otherwise.\n\n";
    md += "| mu_r (wall) | mu_s (wall) | onset, DEM (deg) | Eq 10 (deg) | motion | predicted |\n|---:|---:|---:|---:|---|---|\n";
    for (const auto& r : s.incline)
      md += fmt::format("| {:g} | {:g} | {} | {:.2f} | {} | {} |\n", r.rolling_friction, r.wall_friction,
                        num(r.result.onset_deg, 2), r.result.predicted.onset_deg, dem::rigs::name(r.result.motion),
                        dem::rigs::name(r.result.predicted.motion));
  }
  md += "\n## Chosen material\n\n";
  const auto& ch = studies::chosen(s);
  md += fmt::format("{} `material.toml`: {}, mu_r = {:g}, rho_s = {:g} kg/m^3.\n\n",
                    s.closest >= 0 ? "Closest to the target, written to" : "No target given; the first row is written to",
                    grain_label(s, ch.shape), ch.rolling_friction, ch.solid_density);
  md += "```toml\n" + studies::material_toml(c, s) + "```\n";
  md += "\nThe reference study's own Table 3 values are not legible in the available text, so no comparison with its numbers is "
        "made; its findings are checked in the list above.\n";
  return md;
}

std::string calibration_html(const CalibrationContext& c, const CalibrationStudy& s) {
  const std::string chart = sweep_chart(s);

  // The Markdown tables, rendered simply: the page has no script and no external asset.
  const std::string md = calibration_md(c, s);
  std::string body;
  bool in_table = false, in_code = false;
  std::size_t pos = 0;
  while (pos < md.size()) {
    const auto end = md.find('\n', pos);
    std::string line = md.substr(pos, end == std::string::npos ? std::string::npos : end - pos);
    pos = end == std::string::npos ? md.size() : end + 1;
    if (line.rfind("```", 0) == 0) {
      body += in_code ? "</pre>\n" : "<pre>";
      in_code = !in_code;
      continue;
    }
    if (in_code) {
      body += esc(line) + "\n";
      continue;
    }
    if (!line.empty() && line[0] == '|') {
      if (line.find("---") != std::string::npos) continue;
      std::string row = "<tr>";
      std::size_t a = 1;
      while (a < line.size()) {
        const auto b = line.find('|', a);
        if (b == std::string::npos) break;
        std::string cell = reports::md_unesc(line.substr(a, b - a));
        const bool bold = cell.find("**") != std::string::npos;
        std::string plain;
        for (std::size_t i = 0; i < cell.size(); ++i)
          if (!(cell[i] == '*' && i + 1 < cell.size() && cell[i + 1] == '*')) plain += cell[i]; else ++i;
        row += fmt::format("<{0}>{1}</{0}>", in_table ? "td" : "th", bold ? "<b>" + esc(plain) + "</b>" : esc(plain));
        a = b + 1;
      }
      body += (in_table ? "" : "<table>") + row + "</tr>\n";
      in_table = true;
      continue;
    }
    if (in_table) {
      body += "</table>\n";
      in_table = false;
    }
    if (line.rfind("![", 0) == 0) continue;  // the chart's file: the page draws it inline
    line = md_unesc(line);
    if (line.rfind("# ", 0) == 0) body += "<h1>" + esc(line.substr(2)) + "</h1>\n" + chart + "\n";
    else if (line.rfind("## ", 0) == 0) body += "<h2>" + esc(line.substr(3)) + "</h2>\n";
    else if (line.rfind("- ", 0) == 0) body += "<p class=\"item\">• " + esc(line.substr(2)) + "</p>\n";
    else if (!line.empty()) body += "<p>" + esc(line) + "</p>\n";
  }
  if (in_table) body += "</table>\n";
  return "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>chutelab calibration</title>"
         "<style>body{font-family:sans-serif;max-width:1000px;margin:2em auto;color:#222}"
         "table{border-collapse:collapse;margin:1em 0}td,th{border:1px solid #ccc;padding:3px 8px;text-align:right}"
         "th{background:#f3f3f3}pre{background:#f6f6f6;padding:8px}p.item{margin:0.3em 0 0.3em 1em}svg{max-width:100%;height:auto}</style></head><body>\n" +
         body + "</body></html>\n";
}

}  // namespace chutelab::reports
