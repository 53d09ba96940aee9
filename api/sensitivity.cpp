#include "api/sensitivity.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>

#include <fmt/format.h>

#include "api/dem_options.h"
#include "core/campaign.h"
#include "core/input_error.h"
#include "core/option_check.h"
#include "dem/station/cache.h"
#include "dem/station/progress.h"
#include "dem/station/run.h"
#include "reports/sensitivity_page.h"
#include "validation/dataset.h"
#include "validation/dataset_output.h"

namespace chutelab::api {
namespace {

namespace st = dem::station;
using studies::SensitivityRow;
using studies::SensitivityStudy;
using studies::SensitivityVariant;
using studies::Stat;
using studies::VariantOutcome;

// Each size is one more station DEM run (a 5.6 mm one is 6.6 min of CPU at quick quality,
// bench/SENSITIVITY.md).
constexpr options::NumberRule kSize{"sizes", 0.0, 100.0, true, false, false, "mm"};
constexpr options::NumberRule kLimit{"limit", 0.0, 100.0, false, false, false, "%"};
constexpr std::size_t kMaxSizes = 6;

// Standard deviation of the load-cell samples inside the steady window: the force fluctuation.
void fluctuations(const st::StationResult& r, VariantOutcome& o) {
  double sn = 0, sn2 = 0, ss = 0, ss2 = 0, sr = 0, sr2 = 0;
  int n = 0;
  for (const auto& f : r.forces) {
    if (f.t <= r.window.start || f.t > r.window.end + 1e-12) continue;
    const double R = std::hypot(f.normal, f.shear);
    sn += f.normal, sn2 += f.normal * f.normal;
    ss += f.shear, ss2 += f.shear * f.shear;
    sr += R, sr2 += R * R;
    ++n;
  }
  if (n < 2) return;
  auto sd = [n](double s, double s2) { return std::sqrt(std::max(0.0, (s2 - s * s / n) / (n - 1))); };
  o.fluct_normal = sd(sn, sn2);
  o.fluct_shear = sd(ss, ss2);
  o.fluct_resultant = sd(sr, sr2);
}

Stat stat(const st::Estimate& e) { return {e.ok() ? e.value : std::nan(""), std::isfinite(e.se) ? e.se : 0.0}; }

VariantOutcome outcome(const st::StationResult& r) {
  VariantOutcome out;
  out.normal = stat(r.normal_force);
  out.shear = stat(r.shear_force);
  out.resultant = stat(r.resultant_force);
  fluctuations(r, out);
  out.diameter = r.diameter;
  out.dt = r.dt;
  out.collision_time = r.collision_time;
  out.simulated = r.simulated_time;
  out.wall_seconds = r.wall_seconds;
  out.steps = r.steps;
  out.particles = r.peak_particles;
  out.steady = r.window.found;
  out.notes = r.notes;
  return out;
}

// The variants to run: all, or the base and those of `only` (the others said as left out).
std::vector<SensitivityVariant> chosen_variants(std::vector<SensitivityVariant> variants,
                                                const std::vector<std::string>& only, SensitivityStudy& study) {
  if (only.empty()) return variants;
  std::vector<SensitivityVariant> keep{variants[0]};
  for (const auto& key : only) {
    bool found = false;
    for (std::size_t k = 1; k < variants.size(); ++k)
      if (variants[k].key == key) {
        keep.push_back(variants[k]);
        found = true;
      }
    if (!found) {
      std::vector<std::string> names;
      for (const auto& v : variants) names.push_back(v.key);
      throw InputError("", 0, "only", fmt::format("unknown variant '{}' (known: {})", key, fmt::join(names, ", ")));
    }
  }
  for (std::size_t k = 1; k < variants.size(); ++k)
    if (std::find(only.begin(), only.end(), variants[k].key) == only.end())
      study.variants_left_out.push_back(variants[k].key);
  return keep;
}

// One campaign job per variant (core/campaign.h): in order in one process, side by side with jobs,
// or spread over the ranks of mpirun; each result comes back as the run's full text.
std::vector<campaign::Job> variant_jobs(const std::vector<SensitivityVariant>& variants, const st::RunSettings& base,
                                        const studies::Table6Base& b, double base_d, const st::DemTable& table,
                                        const Station* station, bool progress) {
  std::vector<campaign::Job> jobs;
  for (std::size_t k = 0; k < variants.size(); ++k) {
    const SensitivityVariant& v = variants[k];
    st::RunSettings s = base;
    const auto law = st::parse_contact(v.contact);
    if (!law)
      throw InputError("", 0, st::field_name(&st::RunSettings::contact), fmt::format("unknown contact law '{}' (known: {})", v.contact, dem::NormalLaw::keys()));
    s.contact = *law;
    s.particle_diameter = v.diameter;
    s.particle_shape = v.shape == "clump" ? st::ParticleShape::clump : st::ParticleShape::sphere;
    s.dt_fraction = v.dt_fraction;
    s.rayleigh_fraction = v.rayleigh_fraction;
    s.shear_modulus_scale = b.modulus_scale * v.modulus_scale;
    campaign::Job j;
    j.key = v.key;
    // Relative cost, to hand out the dear runs first: particles ~ d^-3 and steps ~ 1/dt ~ 1/d; a
    // step of Hertz contacts ~ E^(2/5); a two-sphere clump ~ 2.7 spheres (bench/SENSITIVITY.md).
    j.cost = std::pow(base_d / v.diameter, 4.0) * (b.dt_fraction / v.dt_fraction) * std::pow(v.modulus_scale, 0.4) *
             (v.shape == "clump" ? 2.7 : 1.0);
    const std::string label = fmt::format("[{}/{}] {}", k + 1, variants.size(), v.key);
    j.run = [s, &table, station, label, progress](const campaign::JobContext& ctx) {
      st::RunOptions ro;
      ro.settings = s;
      ro.geometry = table;
      if (progress && ctx.progress) ro.progress = st::ProgressPrinter(label);
      return st::to_text(st::run_station(*station, ro));
    };
    jobs.push_back(std::move(j));
  }
  return jobs;
}

}  // namespace

void check(const SensitivityOptions& o) {
  for (double d : o.sizes_mm) kSize.check(d);
  options::at_most("sizes", o.sizes_mm.size(), kMaxSizes, "station DEM runs");
  for (const auto& key : o.only) options::non_empty("only", key);
  kLimit.check(o.limit);
  if (o.threads) options::rules::threads.check(static_cast<double>(*o.threads));
  options::NumberRule{"jobs", 0.0, 256.0, false, false, true, ""}.check(static_cast<double>(o.jobs));
  st::SettingsOverrides ov;
  ov.set(st::dem_field(&st::RunSettings::quality).option, o.quality).check();
}

std::vector<OutputFile> SensitivityResult::files() const {
  return {{"sensitivity.csv", studies::sensitivity_csv(study)},
          {"sensitivity.md", reports::sensitivity_md(study)},
          {"sensitivity.html", reports::sensitivity_html(study)},
          {"sensitivity.svg", reports::sensitivity_svg(study)},
          {"sensitivity-timing.csv", studies::sensitivity_timing_csv(study)}};
}

SensitivityResult sensitivity(const SensitivityOptions& o) {
  namespace fs = std::filesystem;
  const auto t0 = std::chrono::steady_clock::now();
  check(o);
  const fs::path dir = o.dataset.empty() ? o.default_dataset : o.dataset;
  const validation::DatasetFile setup_file = validation::read_setup_file(dir / "setup.toml");
  const Setup setup = validation::read_setup(setup_file);
  const auto stations = validation::read_conditions(dir / "conditions.csv", setup);
  if (o.prepare_output) {  // before minutes of DEM runs
    OutputPlan plan;
    plan.inputs = validation::dataset_files(dir);
    plan.files = {"sensitivity.csv", "sensitivity.md", "sensitivity.html", "sensitivity.svg", "sensitivity-timing.csv"};
    o.prepare_output(plan);
  }
  const Station* station = &validation::condition_row(stations, o.condition, dir / "conditions.csv", "condition");
  st::SettingsOverrides ov;
  ov.set(st::dem_field(&st::RunSettings::quality).option, o.quality).check();
  ov.threads = o.threads.value_or(1);
  if (o.seed) ov.set_whole(st::dem_field(&st::RunSettings::seed).option, *o.seed);
  const st::DemTable table = st::read_dem_table(setup_file.shown, &setup_file.text);
  const st::RunSettings base = st::resolve(table, ov);
  const double base_d = base.particle_diameter > 0.0 ? base.particle_diameter : station->material.particle_diameter;

  SensitivityResult res;
  SensitivityStudy& study = res.study;
  studies::Table6Base& b = study.base;
  b.diameter = base_d;
  b.modulus_scale = base.shear_modulus_scale;  // of the dataset's: the preset's and the [dem] table's
  b.dt_fraction = base.dt_fraction;
  b.rayleigh_fraction = base.rayleigh_fraction;
  if (!o.sizes_mm.empty()) {
    b.sizes.clear();
    for (double d : o.sizes_mm) b.sizes.push_back(d * 1e-3);
  } else if (base.quality == st::Quality::quick) {
    // Measured (bench/SENSITIVITY.md): one 5.6 mm run at quick settings costs 6.6 min of CPU, more
    // than the whole rest of the study, which must stay within ~10 min; left out by default.
    b.sizes = {9.0e-3, 13.6e-3};
  }
  // Every size of the reference study's Table 6 that will not run is said (verdict "not fully
  // tested"), whatever left it out.
  for (double d : studies::Table6Base::reference_sizes()) {
    bool runs = std::abs(d - base_d) < 0.05e-3;
    for (double x : b.sizes) runs = runs || std::abs(d - x) < 0.05e-3;
    if (!runs) study.sizes_left_out.push_back(d);
  }
  const std::vector<SensitivityVariant> variants = chosen_variants(studies::table6_variants(b), o.only, study);

  study.dataset = dir.string();
  study.dataset_name = setup.name;
  study.condition = station->condition;
  study.quality = o.quality;
  study.belt_speed = station->belt_speed;
  study.mass_flow = station->mass_flow;
  study.limit_percent = o.limit;
  if (o.planned) o.planned(study, variants);
  const std::vector<campaign::Job> jobs = variant_jobs(variants, base, b, base_d, table, station, o.progress);
  campaign::Options co;
  co.label = "sensitivity";
  co.threads = resolve_jobs(o.jobs);
  co.progress = o.progress;
  const std::vector<std::string> texts = campaign::run_campaign(jobs, co);
  for (std::size_t k = 0; k < variants.size(); ++k) {
    const std::optional<st::StationResult> parsed = st::from_text(texts[k]);
    if (!parsed) throw std::logic_error("a DEM result text does not read back");
    SensitivityRow row;
    row.variant = variants[k];
    row.outcome = outcome(*parsed);
    study.rows.push_back(row);
  }
  studies::evaluate(study);
  study.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return res;
}

}  // namespace chutelab::api
