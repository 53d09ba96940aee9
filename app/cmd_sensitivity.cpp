// `chutelab sensitivity`: the reference study's Table 6 (§6.1) as one command at one condition. The transfer-
// station DEM (dem/station) runs once per variant — LSD vs Hertz-Mindlin, sphere vs two-sphere clump,
// dt = t_c/10 vs t_c/20, G x10 and /10, the reference study's particle sizes — and the table of R_n, R_s, R with
// standard errors, their fluctuation, the change against the base and the run time is printed and
// written (sensitivity.csv/.md/.html), with the verdict on the reference study's conclusion.
#include <filesystem>
#include <iostream>

#include <fmt/format.h>

#include "api/sensitivity.h"
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

struct SensitivityCli {
  std::string dataset, condition = "V3-41", quality = "quick", out, only, sizes;
  std::optional<int> threads;
  std::optional<std::uint64_t> seed;
  double limit = 10.0;
  int jobs = 0;  // 0: one per idle core (resolve_jobs)
};

int run_sensitivity(const SensitivityCli& o) {
  namespace fs = std::filesystem;
  // The lists as typed, read before anything else (core/option_check.h); the library checks the rest.
  constexpr options::NumberRule kSize{"sizes", 0.0, 100.0, true, false, false, "mm"};
  api::SensitivityOptions opt;
  if (!o.sizes.empty()) opt.sizes_mm = options::number_list(kSize, o.sizes);
  options::at_most("sizes", opt.sizes_mm.size(), 6, "station DEM runs");
  if (!o.only.empty()) opt.only = options::list("only", o.only);
  opt.dataset = o.dataset;
  opt.default_dataset = default_dataset();
  opt.condition = o.condition;
  opt.quality = o.quality;
  opt.threads = o.threads;
  opt.seed = o.seed;
  opt.limit = o.limit;
  opt.jobs = o.jobs;
  opt.progress = true;
  std::optional<OutputFolder> out;
  opt.prepare_output = place_output(out, o.out, "sensitivity");  // --out checked before minutes of DEM runs
  opt.planned = [&](const api::SensitivityStudy& study, const std::vector<api::SensitivityVariant>& variants) {
    std::cout << fmt::format("sensitivity: {} DEM runs of {} / {} ({} quality), base {}\n", variants.size(),
                             one_line(study.dataset_name, 80), one_line(study.condition, 80), study.quality,
                             variants[0].label);
    for (const auto& n : api::run_notes(study)) std::cout << "note: " << n << "\n";
    std::cout << std::flush;
  };
  const api::SensitivityResult res = api::sensitivity(opt);
  const api::SensitivityStudy& study = res.study;
  for (std::size_t k = 0; k < study.rows.size(); ++k) {
    const auto& v = study.rows[k].variant;
    const auto& r = study.rows[k].outcome;
    std::cout << fmt::format("[{}/{}] {:<9} R_n {:7.1f} ± {:4.1f} N, R_s {:6.1f} ± {:4.1f} N, R {:7.1f} ± {:4.1f} N, "
                             "sd(R) {:5.1f} N, dt {:.2f} us, {:.0f} s\n",
                             k + 1, study.rows.size(), v.key, r.normal.value, r.normal.se, r.shear.value, r.shear.se,
                             r.resultant.value, r.resultant.se, r.fluct_resultant, r.dt * 1e6, r.wall_seconds)
              << std::flush;
  }
  for (const auto& [name, content] : res.files()) out->write(name, content);
  out->commit();
  std::cout << study.verdict.text << "\n";
  std::cout << fmt::format("{:.0f} s; written: {}\n", study.wall_seconds, (fs::path(o.out) / "sensitivity.html").string());
  return kExitOk;
}

}  // namespace

void add_sensitivity(CLI::App& app, Action& action) {
  auto o = std::make_shared<SensitivityCli>();
  auto* cmd = app.add_subcommand(
      "sensitivity",
      "The reference study's Table 6 at one condition: the station DEM with LSD vs Hertz-Mindlin, sphere vs clump, dt/20, "
      "G x10 and /10, particle sizes 5.6/9/13.6 mm; writes sensitivity.csv/.md/.html/.svg to --out and says whether the reference study's "
      "conclusion is reproduced.");
  cmd->add_option("--dataset", o->dataset, "dataset (default: bundled grima2010)");
  cmd->add_option("--condition", o->condition, "condition of the dataset (reference study Table 6: V_b = 3 m/s, 41 t/h)")
      ->capture_default_str();
  cmd->add_option("--quality", o->quality, "quick, standard or paper (the base run's preset)")->capture_default_str();
  cmd->add_option("--only", o->only, "run only these variants besides the base (comma list of keys)");
  cmd->add_option("--sizes", o->sizes,
                  "sphere diameters of the size variants, mm (comma list; the one equal to the base diameter is the "
                  "base). Default: the reference study's 5.6,9,13.6; at quick quality 9,13.6 (5.6 mm alone would break the ~10 "
                  "min budget; the verdict then says so)");
  with_rule(cmd->add_option("--limit", o->limit, "'changes little' means |change of mean R| <= this, %")
                ->capture_default_str(),
            options::NumberRule{"--limit", 0.0, 100.0, false, false, false, "%"});
  with_rule(cmd->add_option("--threads", o->threads, "OpenMP threads per run (default 1; results do not depend on it)"),
            options::rules::threads);
  with_rule(cmd->add_option("--seed", o->seed, "feed random seed"), options::rules::seed);
  add_jobs_option(*cmd, o->jobs);
  add_quiet_option(*cmd);
  cmd->add_option("--out", o->out, "output folder")->required();
  cmd->callback([o, &action] { action = [o] { return run_sensitivity(*o); }; });
}

}  // namespace chutelab::app
