// `chutelab calibrate`: the reference study's slump-test calibration (§5, Table 3) as one command: sweeps the
// particle-particle rolling friction, the solid density and the particle shape over the swing-arm
// slump tester, prints and writes Table 3, marks the combination closest to the measured bulk density
// (and pile height), and writes it as a [material] block.
#include <cmath>
#include <cstdio>
#include <iostream>
#include <optional>
#include <unistd.h>

#include <fmt/format.h>

#include "app/commands.h"
#include "core/rig_needs.h"
#include "app/dem_options.h"
#include "app/option_checks.h"
#include "core/campaign.h"
#include "core/progress.h"
#include "core/input_error.h"
#include "core/message.h"
#include "core/option_check.h"
#include "core/number.h"
#include "dem/rigs/calibration.h"
#include "core/output_folder.h"
#include "reports/calibration_page.h"
#include "studies/calibration.h"
#include "validation/dataset.h"
#include "validation/output_files.h"

namespace chutelab::app {
namespace {

struct CalibrateCli {
  std::string dataset, out, quality = "quick", rolling = "0.05,0.1,0.2", density = "925,1000", shape = "sphere,clump";
  double sphere_diameter_mm = 5.6, clump_diameter_mm = 4.4;
  std::optional<double> target_bulk, target_pile_mm;
  bool no_target = false, no_incline = false;
  // One thread per run: a slump test has only a few hundred grains, and OpenMP threads on a shared
  // 2-core machine spend more time waiting at barriers than computing (measured: 4 s vs 15-100 s).
  int threads = 1;
  std::uint64_t seed = 1;
  int jobs = 0;  // 0: one per idle core (resolve_jobs)
};

// What each list and number may be (core/option_check.h): physical ranges, wide enough for any
// bulk solid (the densest solid, osmium, is 22 600 kg/m^3).
constexpr options::NumberRule kRolling{"--rolling", 0.0, 1.0, false, false, false, ""};
constexpr options::NumberRule kDensity{"--density", 0.0, 25000.0, true, false, false, "kg/m^3"};
constexpr options::NumberRule kDiameter{"", 0.0, 100.0, true, false, false, "mm"};
constexpr options::NumberRule kTargetBulk{"", 0.0, 25000.0, true, false, false, "kg/m^3"};
constexpr options::NumberRule kTargetPile{"", 0.0, 10000.0, true, false, false, "mm"};
constexpr options::NumberRule kRigThreads{"", 1.0, 256.0, false, false, true, ""};
// A quick slump test takes ~20 s of one core, a standard one minutes (bench/CALIBRATION.md): beyond
// this many a command would run for hours; it is refused before the first one starts.
constexpr std::size_t kMaxSlumpTests = 100;

int run_calibrate(const CalibrateCli& o) {
  namespace fs = std::filesystem;
  using namespace dem::rigs;
  using reports::calibration_html;
  using reports::calibration_md;
  using reports::table3_md;
  using studies::CalibrationContext;
  using studies::calibration_timing_csv;
  using studies::incline_csv;
  // Every list checked before anything is read or run.
  CalibrationPlan plan;
  plan.rolling = options::number_list(kRolling, o.rolling);
  plan.density = options::number_list(kDensity, o.density);
  for (const auto& s : options::list("--shape", o.shape)) {
    if (s == "sphere") plan.shapes.push_back(GrainKind::sphere);
    else if (s == "clump") plan.shapes.push_back(GrainKind::clump);
    else throw InputError("", 0, "--shape", fmt::format("unknown shape {} (sphere, clump)", shown(s)));
  }
  const auto count_tests = plan.shapes.size() * plan.rolling.size() * plan.density.size();
  if (count_tests > kMaxSlumpTests)
    throw InputError("", 0, "--rolling",
                     fmt::format("{} shapes x {} rolling frictions x {} densities = {} slump tests; at most {} run in one "
                                 "command (each takes ~20 s to minutes): shorten the lists or split them over runs",
                                 plan.shapes.size(), plan.rolling.size(), plan.density.size(), count_tests,
                                 kMaxSlumpTests));
  const fs::path dir = o.dataset.empty() ? default_dataset() : fs::path(o.dataset);
  CalibrationContext ctx;
  ctx.dataset = dir.string();
  ctx.quality = o.quality;
  ctx.setup = validation::read_setup(dir / "setup.toml");
  {
    Station probe;  // the slump tests and the incline are the DEM's: every contact value is needed
    probe.material = ctx.setup.material;
    probe.belt = ctx.setup.belt;
    probe.plate = ctx.setup.plate;
    require_dem_keys(probe, (dir / "setup.toml").string(), "calibrate's DEM");
  }
  OutputFolder out(o.out, dataset_inputs(dir), "calibrate");  // checked before minutes of slump tests
  check_entries(out, {"calibration.csv", "incline.csv", "calibration.md", "calibration.html", "calibration.svg",
                      "material.toml", "calibration-timing.csv"});

  plan.sphere = Grain::sphere(o.sphere_diameter_mm * 1e-3);
  plan.clump = Grain::reference_clump(o.clump_diameter_mm * 1e-3);
  plan.settings = slump_preset(o.quality == "standard" ? RigQuality::standard : RigQuality::quick);
  plan.settings.threads = o.threads;
  plan.settings.seed = o.seed;
  if (!o.no_target) {
    // Default target: the dataset's measured loose-poured bulk density.
    plan.targets.bulk_density = o.target_bulk ? *o.target_bulk : ctx.setup.material.bulk_density;
    if (o.target_pile_mm) plan.targets.pile_height = *o.target_pile_mm * 1e-3;
  }
  plan.incline = !o.no_incline;
  campaign::set_threads(resolve_jobs(o.jobs));

  const int count = static_cast<int>(plan.shapes.size() * plan.rolling.size() * plan.density.size());
  std::cout << fmt::format("calibrate: {} slump tests ({} quality) on {} ({})\n", count, o.quality,
                           one_line(ctx.setup.name, 80),
                           ctx.dataset)
            << std::flush;
  auto progress = [&](const CalibrationProgress& p) {
    if (p.done) {
      const auto& r = *p.done;
      progress::status("");
      std::cout << fmt::format("[{:>2}/{}] {:<16} mu_r {:<5g} rho_s {:<5g}: bulk {:4.0f} kg/m^3, pile {:5.1f} mm, "
                               "repose {:4.1f} deg, {} grains ({:.1f} s)\n",
                               p.index, p.count, r.shape == GrainKind::sphere ? plan.sphere.label() : plan.clump.label(),
                               r.rolling_friction, r.solid_density, r.slump.bulk_density, r.slump.pile_height * 1e3,
                               r.slump.repose_angle_deg, r.slump.particles, r.slump.wall_seconds)
                << std::flush;
    } else {
      progress::status(fmt::format("[{:>2}/{}] {} {:.2f}/{:.2f} s", p.index, p.count, p.slump.phase, p.slump.time,
                                   p.slump.max_time));
    }
  };
  const CalibrationStudy study = run_calibration(ctx.setup.material, plan, progress);
  if (!study.incline.empty()) {
    std::cout << "inclined-plane rig (particle-wall, sphere on the plate material):\n";
    for (const auto& r : study.incline)
      std::cout << fmt::format("  mu_r {:<5g} mu_s {:<5g}: onset {:.2f} deg ({}); Eq 10 {:.2f} deg ({})\n", r.rolling_friction,
                               r.wall_friction, r.result.onset_deg, name(r.result.motion), r.result.predicted.onset_deg,
                               name(r.result.predicted.motion));
  }
  std::cout << "Table 3 (the reference study's layout):\n" << table3_md(study);
  out.write("calibration.csv", calibration_csv(ctx, study));
  out.write("incline.csv", incline_csv(study));
  out.write("calibration.md", calibration_md(ctx, study));
  out.write("calibration.html", calibration_html(ctx, study));
  out.write("calibration.svg", reports::calibration_svg(study));
  out.write("material.toml", material_toml(ctx, study));
  out.write("calibration-timing.csv", calibration_timing_csv(study));
  out.commit();
  if (study.closest >= 0) {
    const auto& b = study.rows[static_cast<std::size_t>(study.closest)];
    std::cout << fmt::format("closest to the target: {} mu_r = {:g}, rho_s = {:g} kg/m^3 (bulk {:.0f} kg/m^3, pile {:.1f} mm; "
                             "{:.1f} % from the target)\n",
                             b.shape == GrainKind::sphere ? plan.sphere.label() : plan.clump.label(), b.rolling_friction,
                             b.solid_density, b.slump.bulk_density, b.slump.pile_height * 1e3, 100.0 * b.distance);
  }
  std::cout << fmt::format("{:.0f} s; written: {}\n", study.wall_seconds,
                           (fs::path(o.out) / "calibration.md").string());
  return kExitOk;
}

}  // namespace

void add_calibrate(CLI::App& app, Action& action) {
  auto o = std::make_shared<CalibrateCli>();
  auto* cmd = app.add_subcommand(
      "calibrate",
      "Slump-test calibration (reference study §5, Table 3): rolling friction x solid density x shape over the swing-arm "
      "slump tester; writes calibration.csv/.md/.html/.svg, incline.csv and material.toml to --out.");
  cmd->add_option("--dataset", o->dataset, "dataset whose [material] to calibrate (default: bundled grima2010)");
  cmd->add_option("--quality", o->quality, "quick (~500 spheres, soft) or standard")
      ->check(CLI::IsMember({"quick", "standard"}))
      ->capture_default_str();
  cmd->add_option("--rolling", o->rolling, "particle-particle rolling friction coefficients")->capture_default_str();
  cmd->add_option("--density", o->density, "solid densities, kg/m^3")->capture_default_str();
  cmd->add_option("--shape", o->shape, "particle shapes: sphere (reference study Fig. 4b), clump (2 overlapping spheres, Fig. 4c)")
      ->capture_default_str();
  with_rule(cmd->add_option("--sphere-diameter", o->sphere_diameter_mm, "sphere diameter, mm")->capture_default_str(),
            kDiameter);
  with_rule(
      cmd->add_option("--clump-diameter", o->clump_diameter_mm, "diameter of the clump's spheres, mm")->capture_default_str(),
      kDiameter);
  with_rule(cmd->add_option("--target-bulk-density", o->target_bulk,
                            "measured loose-poured bulk density, kg/m^3 (default: the dataset's bulk_density_kgm3)"),
            kTargetBulk);
  with_rule(cmd->add_option("--target-pile-height", o->target_pile_mm, "measured pile height, mm"), kTargetPile);
  cmd->add_flag("--no-target", o->no_target, "mark no combination (and write the first one)");
  cmd->add_flag("--no-incline", o->no_incline, "skip the inclined-plane rig");
  with_rule(cmd->add_option("--threads", o->threads, "OpenMP threads per run")->capture_default_str(), kRigThreads);
  with_rule(cmd->add_option("--seed", o->seed, "random seed of the pour")->capture_default_str(), options::rules::seed);
  add_jobs_option(*cmd, o->jobs);
  add_quiet_option(*cmd);
  cmd->add_option("--out", o->out, "output folder")->required();
  cmd->callback([o, &action] { action = [o] { return run_calibrate(*o); }; });
}

}  // namespace chutelab::app
