#include "studies/calibration.h"
#include "studies/csv_checks.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "core/csv_field.h"
#include "core/input_error.h"
#include "core/message.h"
#include "validation/csv_table.h"
#include "validation/output_files.h"

namespace chutelab::studies {

using dem::rigs::CalibrationRow;
using dem::rigs::CalibrationStudy;
using dem::rigs::GrainKind;
using validation::csv_number;

std::string grain_label(const CalibrationStudy& s, GrainKind k) {
  return k == GrainKind::sphere ? s.plan.sphere.label() : s.plan.clump.label();
}

const CalibrationRow& chosen(const CalibrationStudy& s) {
  return s.rows.at(s.closest >= 0 ? static_cast<std::size_t>(s.closest) : 0);
}

std::vector<std::string> calibration_findings(const CalibrationStudy& s) {
  std::vector<std::string> out;
  for (GrainKind k : s.plan.shapes)
    for (double rho : s.plan.density) {
      const CalibrationRow *lo = nullptr, *hi = nullptr;
      for (const auto& r : s.rows)
        if (r.shape == k && r.solid_density == rho) {
          if (!lo || r.rolling_friction < lo->rolling_friction) lo = &r;
          if (!hi || r.rolling_friction > hi->rolling_friction) hi = &r;
        }
      if (!lo || lo == hi) continue;
      out.push_back(fmt::format(
          "{}, rho_s = {:g} kg/m^3: raising mu_r from {:g} to {:g} changes the pile height from {:.1f} to {:.1f} mm "
          "({:+.0f} %) and the bulk density from {:.0f} to {:.0f} kg/m^3 ({:+.1f} %).",
          grain_label(s, k), rho, lo->rolling_friction, hi->rolling_friction, lo->slump.pile_height * 1e3,
          hi->slump.pile_height * 1e3, 100.0 * (hi->slump.pile_height / lo->slump.pile_height - 1.0),
          lo->slump.bulk_density, hi->slump.bulk_density, 100.0 * (hi->slump.bulk_density / lo->slump.bulk_density - 1.0)));
    }
  // Shape at equal rolling friction and density: packing (solid fraction).
  if (s.plan.shapes.size() == 2) {
    double sum_s = 0, sum_c = 0;
    int n = 0;
    for (const auto& a : s.rows)
      for (const auto& b : s.rows)
        if (a.shape == GrainKind::sphere && b.shape == GrainKind::clump && a.rolling_friction == b.rolling_friction &&
            a.solid_density == b.solid_density) {
          sum_s += a.slump.bulk_density / a.solid_density;
          sum_c += b.slump.bulk_density / b.solid_density;
          ++n;
        }
    if (n > 0)
      out.push_back(fmt::format("Mean solid fraction (bulk / solid density): spheres {:.3f}, clumps {:.3f} — the "
                                "shaped particles pack {} (reference study §5: \"the smaller shaped particles pack more "
                                "efficiently ... and achieve a higher loose-poured bulk density\").",
                                sum_s / n, sum_c / n, sum_c > sum_s ? "more densely, as in the reference study" : "less densely, unlike the reference study"));
  }
  // Density at equal shape and rolling friction: pile height sensitivity.
  if (s.plan.density.size() >= 2) {
    double worst = 0.0;
    for (const auto& a : s.rows)
      for (const auto& b : s.rows)
        if (a.shape == b.shape && a.rolling_friction == b.rolling_friction && a.solid_density < b.solid_density)
          worst = std::max(worst, std::abs(b.slump.pile_height / a.slump.pile_height - 1.0));
    out.push_back(fmt::format("Solid density changes the pile height by at most {:.0f} % at equal shape and mu_r "
                              "(reference study: \"the sensitivity of the solid density on the height of pile "
                              "formed is minor\").",
                              100.0 * worst));
  }
  return out;
}

std::string targets_text(const CalibrationStudy& s) {
  std::vector<std::string> t;
  if (s.plan.targets.bulk_density) t.push_back(fmt::format("bulk density {:.0f} kg/m^3", *s.plan.targets.bulk_density));
  if (s.plan.targets.pile_height) t.push_back(fmt::format("pile height {:.1f} mm", *s.plan.targets.pile_height * 1e3));
  if (t.empty()) return "none (no combination is marked)";
  return fmt::format("{}", fmt::join(t, ", "));
}

std::string calibration_csv(const CalibrationContext& c, const CalibrationStudy& s) {
  std::string out =
      "shape,grain,rolling_friction,solid_density_kgm3,bulk_density_kgm3,pile_height_mm,repose_angle_deg,"
      "peak_height_mm,fill_height_mm,particles,settled,steps,target_distance,closest,dataset,quality\n";
  for (std::size_t k = 0; k < s.rows.size(); ++k) {
    const auto& r = s.rows[k];
    out += fmt::format("{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{}\n", name(r.shape), grain_label(s, r.shape),
                       csv_number(r.rolling_friction), csv_number(r.solid_density), csv_number(r.slump.bulk_density),
                       csv_number(r.slump.pile_height * 1e3), csv_number(r.slump.repose_angle_deg),
                       csv_number(r.slump.peak_height * 1e3), csv_number(r.slump.fill_height * 1e3), r.slump.particles, r.slump.settled ? 1 : 0,
                       r.slump.steps,
                       std::isfinite(r.distance) ? csv_number(r.distance) : std::string(),
                       static_cast<int>(k) == s.closest ? 1 : 0, csv_field(c.setup.name), c.quality);
  }
  return out;
}

std::string calibration_timing_csv(const CalibrationStudy& s) {
  std::string out = "shape,rolling_friction,solid_density_kgm3,run_seconds\n";
  for (const auto& r : s.rows)
    out += fmt::format("{},{},{},{}\n", name(r.shape), csv_number(r.rolling_friction), csv_number(r.solid_density),
                       csv_number(r.slump.wall_seconds));
  return out;
}

std::string incline_csv(const CalibrationStudy& s) {
  std::string out = "rolling_friction_wall,friction_wall,onset_deg,predicted_deg,motion,predicted_motion\n";
  for (const auto& r : s.incline)
    out += fmt::format("{},{},{},{},{},{}\n", csv_number(r.rolling_friction), csv_number(r.wall_friction),
                       csv_number(r.result.onset_deg), csv_number(r.result.predicted.onset_deg),
                       dem::rigs::name(r.result.motion), dem::rigs::name(r.result.predicted.motion));
  return out;
}

std::string material_toml(const CalibrationContext& c, const CalibrationStudy& s) {
  const auto& ch = chosen(s);
  Setup setup = c.setup;
  setup.material.solid_density = ch.solid_density;
  setup.material.rolling_friction_particle = ch.rolling_friction;
  std::string out = fmt::format(
      "# chutelab calibrate: slump tests ({} quality) on {}; {} {}.\n"
      "# Calibrated for DEM {}: solid_density_kgm3 and rolling_friction_particle are the DEM values for that\n"
      "# particle; every other value is the dataset's.\n[material]\n",
      c.quality, one_line(c.dataset), s.closest >= 0 ? "closest to the target" : "no target given, first combination",
      targets_text(s), grain_label(s, ch.shape));
  for (const auto& f : rig_fields()) {
    if (f.section != "material") continue;
    const double v = f.ref(setup) / f.to_si;
    out += fmt::format("{} = {}\n", f.key, csv_number(v));
  }
  return out;
}

std::vector<CalibrationPoint> read_calibration_csv(const std::filesystem::path& file) {
  using validation::CsvTable;
  const CsvTable t = CsvTable::read(file, {"shape", "grain", "rolling_friction", "solid_density_kgm3",
                                           "bulk_density_kgm3", "pile_height_mm", "repose_angle_deg", "particles",
                                           "settled", "target_distance", "closest"});
  if (t.rows().empty()) throw InputError(file.string(), 0, "shape", "no slump tests in the file (a header only)");
  auto col = [&](std::string_view c) { return t.require(c); };
  std::vector<CalibrationPoint> out;
  std::vector<double> timing;
  if (const auto tf = file.parent_path() / "calibration-timing.csv"; std::filesystem::exists(tf)) {
    const CsvTable tt = CsvTable::read(tf, {"run_seconds"});
    for (const auto& r : tt.rows()) timing.push_back(tt.number(r, tt.require("run_seconds")));
  }
  for (const auto& r : t.rows()) {
    CalibrationPoint p;
    p.shape = t.text(r, col("shape"));
    if (p.shape != "sphere" && p.shape != "clump")
      throw InputError(file.string(), r.line, "shape", fmt::format("must be sphere or clump, got '{}'", p.shape));
    p.grain = t.text(r, col("grain"));
    p.rolling_friction = csv_in_range(t, r, col("rolling_friction"), 0.0, 10.0);
    p.solid_density = csv_in_range(t, r, col("solid_density_kgm3"), 1e-3, 1e5);
    p.bulk_density = csv_in_range(t, r, col("bulk_density_kgm3"), 0.0, 1e5);
    p.pile_height = csv_in_range(t, r, col("pile_height_mm"), 0.0, 1e5) * 1e-3;
    p.repose_angle_deg = csv_in_range(t, r, col("repose_angle_deg"), 0.0, 90.0, true);
    p.particles = static_cast<long>(csv_count(t, r, col("particles")));
    p.settled = csv_flag(t, r, col("settled"));
    // Older files carry the time; newer ones keep it in calibration-timing.csv beside them.
    p.run_seconds = t.column("run_seconds") ? t.number(r, col("run_seconds")) : std::nan("");
    p.distance = t.optional_number(r, col("target_distance"));
    p.closest = csv_flag(t, r, col("closest"));
    // Provenance columns came later: optional, so a study written before them still reads.
    if (const auto c = t.column("dataset")) p.dataset = t.text(r, *c);
    if (const auto c = t.column("quality")) p.quality = t.text(r, *c);
    if (!(p.solid_density > 0.0)) throw InputError(file.string(), r.line, "solid_density_kgm3", "must be > 0");
    if (timing.size() == t.rows().size()) p.run_seconds = timing[out.size()];
    out.push_back(p);
  }
  return out;
}

}  // namespace chutelab::studies
