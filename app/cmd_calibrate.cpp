// `chutelab calibrate`: the reference study's slump-test calibration (§5, Table 3) as one command: sweeps the
// particle-particle rolling friction, the solid density and the particle shape over the swing-arm
// slump tester, prints and writes Table 3, marks the combination closest to the measured bulk density
// (and pile height), and writes it as a [material] block.
#include <filesystem>
#include <iostream>
#include <optional>

#include <fmt/format.h>

#include "api/calibrate.h"
#include "app/commands.h"
#include "app/output_hook.h"
#include "app/dem_options.h"
#include "app/option_checks.h"
#include "core/input_error.h"
#include "core/message.h"
#include "core/option_check.h"
#include "core/output_folder.h"

namespace chutelab::app {
namespace {

struct CalibrateCli {
  std::string dataset, out, quality = "quick", rolling = "0.05,0.1,0.2", density = "925,1000", shape = "sphere,clump";
  double sphere_diameter_mm = 5.6, clump_diameter_mm = 4.4;
  std::optional<double> target_bulk, target_pile_mm;
  bool no_target = false, no_incline = false;
  int threads = 1;  // api::CalibrateOptions::threads says why
  std::uint64_t seed = 1;
  int jobs = 0;  // 0: one per idle core (resolve_jobs)
};

// The flags' rules (core/option_check.h); the library checks its options again by the same ranges.
constexpr options::NumberRule kRolling{"rolling", 0.0, 1.0, false, false, false, ""};
constexpr options::NumberRule kDensity{"density", 0.0, 25000.0, true, false, false, "kg/m^3"};
constexpr options::NumberRule kDiameter{"", 0.0, 100.0, true, false, false, "mm"};
constexpr options::NumberRule kTargetBulk{"", 0.0, 25000.0, true, false, false, "kg/m^3"};
constexpr options::NumberRule kTargetPile{"", 0.0, 10000.0, true, false, false, "mm"};
constexpr options::NumberRule kRigThreads{"", 1.0, 256.0, false, false, true, ""};

int run_calibrate(const CalibrateCli& o) {
  namespace fs = std::filesystem;
  // The lists as typed, read before anything is read or run.
  api::CalibrateOptions opt;
  opt.rolling = options::number_list(kRolling, o.rolling);
  opt.density = options::number_list(kDensity, o.density);
  opt.shapes = options::list("shape", o.shape);
  opt.dataset = o.dataset;
  opt.default_dataset = default_dataset();
  opt.quality = o.quality;
  opt.sphere_diameter_mm = o.sphere_diameter_mm;
  opt.clump_diameter_mm = o.clump_diameter_mm;
  opt.target = !o.no_target;
  opt.target_bulk_density = o.target_bulk;
  opt.target_pile_height_mm = o.target_pile_mm;
  opt.incline = !o.no_incline;
  opt.threads = o.threads;
  opt.seed = o.seed;
  opt.jobs = o.jobs;
  opt.progress = true;
  std::optional<OutputFolder> out;
  opt.prepare_output = place_output(out, o.out, "calibrate");  // --out checked before minutes of slump tests
  opt.planned = [&](const api::CalibrationContext& ctx, int count) {
    std::cout << fmt::format("calibrate: {} slump tests ({} quality) on {} ({})\n", count, ctx.quality,
                             one_line(ctx.setup.name, 80), ctx.dataset)
              << std::flush;
  };
  const api::CalibrateResult res = api::calibrate(opt);
  const auto& study = res.study;
  const int count = static_cast<int>(study.rows.size());
  for (int k = 0; k < count; ++k) {
    const auto& r = study.rows[static_cast<std::size_t>(k)];
    std::cout << fmt::format("[{:>2}/{}] {:<16} mu_r {:<5g} rho_s {:<5g}: bulk {:4.0f} kg/m^3, pile {:5.1f} mm, "
                             "repose {:4.1f} deg, {} grains ({:.1f} s)\n",
                             k + 1, count, api::grain_label(study, r.shape), r.rolling_friction, r.solid_density,
                             r.slump.bulk_density, r.slump.pile_height * 1e3, r.slump.repose_angle_deg,
                             r.slump.particles, r.slump.wall_seconds)
              << std::flush;
  }
  if (!study.incline.empty()) {
    std::cout << "inclined-plane rig (particle-wall, sphere on the plate material):\n";
    for (const auto& r : study.incline)
      std::cout << fmt::format("  mu_r {:<5g} mu_s {:<5g}: onset {:.2f} deg ({}); Eq 10 {:.2f} deg ({})\n", r.rolling_friction,
                               r.wall_friction, r.result.onset_deg, name(r.result.motion), r.result.predicted.onset_deg,
                               name(r.result.predicted.motion));
  }
  std::cout << "Table 3 (the reference study's layout):\n" << res.table3();
  for (const auto& [name, content] : res.files()) out->write(name, content);
  out->commit();
  if (study.closest >= 0) {
    const auto& b = study.rows[static_cast<std::size_t>(study.closest)];
    std::cout << fmt::format("closest to the target: {} mu_r = {:g}, rho_s = {:g} kg/m^3 (bulk {:.0f} kg/m^3, pile {:.1f} mm; "
                             "{:.1f} % from the target)\n",
                             api::grain_label(study, b.shape), b.rolling_friction, b.solid_density,
                             b.slump.bulk_density, b.slump.pile_height * 1e3, 100.0 * b.distance);
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
