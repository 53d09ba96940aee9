#include "reports/studies.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "core/input_error.h"
#include "reports/sensitivity_page.h"
#include "studies/sensitivity.h"

namespace chutelab::reports {
namespace {

namespace fs = std::filesystem;
using studies::CalibrationPoint;
using studies::SensitivityStudy;
using studies::Stat;

std::string num(double v, int decimals) { return std::isfinite(v) ? fixed(v, decimals) : std::string(kDash); }

Cell text_cell(std::string s, bool strong = false) { return {std::move(s), "", false, "", true, strong}; }
Cell num_cell(std::string s, bool strong = false) { return {std::move(s), "", false, "", false, strong}; }

}  // namespace

std::vector<std::string> provenance_paragraphs(std::string_view kind, std::string_view dataset, std::string_view quality,
                                               std::string_view validated) {
  std::vector<std::string> out;
  const std::string q = quality.empty() ? std::string("an unrecorded") : std::string(quality);
  if (dataset.empty()) {
    out.push_back(fmt::format("The {} study's file does not record its dataset ({} quality){}.", kind, q,
                              validated.empty() ? std::string()
                                                : fmt::format(": whether it was run on {} cannot be checked", validated)));
    return out;
  }
  out.push_back(fmt::format("The {} study ran on dataset {} at {} quality.", kind, dataset, q));
  if (!validated.empty() && dataset != validated)
    out.push_back(fmt::format("Warning: this report validates {}, but the {} study ran on {}: its numbers describe {}'s "
                              "rig and material, not {}'s.",
                              validated, kind, dataset, dataset, validated));
  return out;
}

StudySection calibration_section(const fs::path& csv_file, std::string_view suffix, std::string_view validated) {
  const std::vector<CalibrationPoint> pts = studies::read_calibration_csv(csv_file);
  StudySection s;
  s.id = fmt::format("calibration{}", suffix);
  s.title = "Calibration (the reference study's Table 3)";
  double seconds = 0.0;
  const CalibrationPoint* best = nullptr;
  for (const auto& p : pts) {
    seconds += p.run_seconds;
    if (p.closest) best = &p;
  }
  s.paragraphs.push_back(fmt::format(
      "Swing-arm slump tests (the reference study's Fig. 5) over particle-particle rolling friction, solid density and particle "
      "shape, from {} ({} tests{}). Loose-poured bulk density and pile height as the reference study's Table 3.",
      csv_file.string(), pts.size(), std::isfinite(seconds) ? fmt::format(", {:.0f} s of DEM", seconds) : std::string()));
  for (auto& p : provenance_paragraphs("calibration", pts.front().dataset, pts.front().quality, validated))
    s.paragraphs.push_back(std::move(p));
  if (best)
    s.verdict = fmt::format("Closest to the measured target: {}, mu_r = {:g}, rho_s = {:g} kg/m^3 (bulk density {:.0f} "
                            "kg/m^3, pile height {:.1f} mm; {:.1f} % from the target).",
                            best->grain, best->rolling_friction, best->solid_density, best->bulk_density,
                            best->pile_height * 1e3, best->distance ? 100.0 * *best->distance : std::nan(""));
  else
    s.paragraphs.push_back("No target was given to the calibration, so no combination is marked.");
  Table& t = s.table;
  t.id = s.id + "-table";
  t.caption = "Slump-test calibration: rolling friction × solid density × shape";
  t.columns = {{"", "particle", "", true},
               {"", "rolling friction μ_r", "", false},
               {"", "solid density (kg/m³)", "", false},
               {"", "bulk density (kg/m³)", "", false},
               {"", "pile height (mm)", "", false},
               {"", "angle of repose (°)", "", false},
               {"", "grains", "", false},
               {"", "distance to target (%)", "", false}};
  bool unsettled = false;
  for (const auto& p : pts) {
    unsettled = unsettled || !p.settled;
    t.rows.push_back({text_cell(p.grain + (p.closest ? " ◀ closest" : ""), p.closest),
                      num_cell(fmt::format("{:g}", p.rolling_friction), p.closest),
                      num_cell(fmt::format("{:g}", p.solid_density), p.closest),
                      num_cell(num(p.bulk_density, 0), p.closest), num_cell(num(p.pile_height * 1e3, 1), p.closest),
                      num_cell(num(p.repose_angle_deg, 1)), num_cell(fmt::format("{}", p.particles)),
                      num_cell(p.distance ? num(100.0 * *p.distance, 1) : std::string(kDash))});
  }
  if (unsettled) t.notes.push_back("Some slump tests reached their time limit before every grain came to rest.");
  t.notes.push_back("Pile height: apex of the cone fitted to the pile's flank; bulk density: the settled column's core.");
  s.chart_svg = calibration_chart(pts, {}, s.id + "-chart");
  s.caption = "Pile height and loose-poured bulk density against rolling friction, per particle and solid density.";
  return s;
}

StudySection sensitivity_section(const fs::path& csv_file, std::string_view suffix, std::string_view validated) {
  const SensitivityStudy st = studies::read_sensitivity_csv(csv_file);
  StudySection s;
  s.id = fmt::format("sensitivity{}", suffix);
  s.title = "Sensitivity (the reference study's Table 6)";
  s.verdict = st.verdict.text;
  s.paragraphs.push_back(fmt::format(
      "The transfer-station DEM at condition {} (V_b = {:g} m/s, {:.1f} t/h, {} quality) with one modelling shortcut "
      "changed at a time, from {} ({} runs{}). Means over the steady window with block standard "
      "errors; fluctuation = standard deviation of the load-cell samples in that window; change = R / R_base − 1.",
      st.condition, st.belt_speed, st.mass_flow * 3.6, st.quality, csv_file.string(), st.rows.size(),
      std::isfinite(st.wall_seconds) ? fmt::format(", {:.0f} s of DEM", st.wall_seconds) : std::string()));
  for (auto& p : provenance_paragraphs("sensitivity", st.dataset_name, st.quality, validated))
    s.paragraphs.push_back(std::move(p));
  Table& t = s.table;
  t.id = s.id + "-table";
  t.caption = "Plate force per variant";
  t.columns = {{"", "variant", "", true},           {"", "what changes", "", true},
               {"", "d (mm)", "", false},           {"", "dt (µs)", "", false},
               {"", "dt / t_c", "", false},
               {"mean (N)", "R_n", "", false},      {"mean (N)", "R_s", "", false},
               {"mean (N)", "R", "", false},        {"fluctuation, sd (N)", "R_n", "", false},
               {"fluctuation, sd (N)", "R_s", "", false}, {"fluctuation, sd (N)", "R", "", false},
               {"", "change of R vs base (%)", "", false}, {"", "run (s)", "", false}};
  auto pm = [](const Stat& x) { return std::isfinite(x.value) ? fmt::format("{:.1f} ± {:.1f}", x.value, x.se) : std::string(kDash); };
  for (std::size_t k = 0; k < st.rows.size(); ++k) {
    const auto& r = st.rows[k];
    const auto& o = r.outcome;
    t.rows.push_back({text_cell(r.variant.key, k == 0), text_cell(r.variant.label),
                      num_cell(studies::mm_text(o.diameter)), num_cell(num(o.dt * 1e6, 2)),
                      num_cell(o.collision_time > 0.0 ? num(o.dt / o.collision_time, 3) : std::string(kDash)),
                      num_cell(pm(o.normal)), num_cell(pm(o.shear)), num_cell(pm(o.resultant)),
                      num_cell(num(o.fluct_normal, 1)), num_cell(num(o.fluct_shear, 1)), num_cell(num(o.fluct_resultant, 1)),
                      num_cell(k == 0 ? std::string(kDash)
                                      : std::isfinite(r.change.value) ? fmt::format("{:+.1f} ± {:.1f}", r.change.value, r.change.se)
                                                                       : std::string(kDash)),
                      num_cell(std::isfinite(o.wall_seconds) ? num(o.wall_seconds, 0) : std::string(kDash))});
  }
  for (const auto& r : st.rows)
    if (!r.outcome.steady) t.notes.push_back(r.variant.key + ": no steady window within the time limit (means uncertain).");
  for (const auto& n : studies::run_notes(st)) t.notes.push_back(n + ".");
  s.chart_svg = sensitivity_chart(st, s.id + "-chart");
  s.caption = "Mean resultant plate force (± 1 standard error; dashed: the base) and its fluctuation per variant.";
  return s;
}

std::vector<StudySection> read_studies(const std::vector<fs::path>& paths, std::string_view validated) {
  std::vector<StudySection> out;
  int calibrations = 0, sensitivities = 0;
  // The second study of a kind gets "-2" on its anchors: ids are unique in the page.
  auto add_cal = [&](const fs::path& f) {
    ++calibrations;
    out.push_back(calibration_section(f, calibrations > 1 ? fmt::format("-{}", calibrations) : std::string(), validated));
  };
  auto add_sens = [&](const fs::path& f) {
    ++sensitivities;
    out.push_back(sensitivity_section(f, sensitivities > 1 ? fmt::format("-{}", sensitivities) : std::string(), validated));
  };
  for (const auto& path : paths) {
    if (fs::is_regular_file(path)) {
      const std::string f = path.filename().string();
      if (f == "calibration.csv") add_cal(path);
      else if (f == "sensitivity.csv") add_sens(path);
      else
        throw InputError(path.string(), 0, "studies",
                         "not a study file (give the folder of a calibrate or sensitivity run, or its calibration.csv "
                         "/ sensitivity.csv)");
      continue;
    }
    if (!fs::is_directory(path))
      throw InputError(path.string(), 0, "studies", "no such folder (the output folder of a calibrate or sensitivity study)");
    const bool cal = fs::exists(path / "calibration.csv"), sens = fs::exists(path / "sensitivity.csv");
    if (!cal && !sens) throw InputError(path.string(), 0, "studies", "holds neither calibration.csv nor sensitivity.csv");
    if (cal) add_cal(path / "calibration.csv");
    if (sens) add_sens(path / "sensitivity.csv");
  }
  return out;
}

}  // namespace chutelab::reports
