#include "app/dem_options.h"

#include <filesystem>

#include "app/flag_names.h"
#include "app/option_checks.h"
#include "core/progress.h"

namespace chutelab::app {
namespace {
constexpr options::NumberRule kSimulatedTime{"", 0.0, 100.0, true, false, false, "s"};

// The words a [dem] setting accepts, as its field in the [dem] table declares them.
CLI::Validator accepts(api::DemSetting s) {
  const std::vector<std::string> w = api::words(s);
  std::string set;
  for (const auto& x : w) set += (set.empty() ? "{" : ",") + x;
  return CLI::Validator([s](std::string& v) { return api::problem(s, v).value_or(std::string()); }, set + "}",
                        "dem-setting");
}
// The flag of a [dem] setting validate and diagnose take.
std::string flag(api::DemSetting s) { return flag_for(api::key(s)); }
}  // namespace

void add_dem_options(CLI::App& cmd, DemCli& o) {
  cmd.add_option(flag(api::DemSetting::quality), o.quality,
                 "DEM quality: quick (default; seconds to minutes per condition), standard (the dataset's "
                 "particles), paper");
  with_rule(cmd.add_option("--dem-threads", o.threads, "OpenMP threads of the DEM (default: one per idle core)"),
            options::rules::dem_threads);
  cmd.add_option("--dem-cache", o.cache, "DEM result cache folder (default $XDG_CACHE_HOME/chutelab/dem)");
  cmd.add_flag("--no-dem-cache", o.no_cache, "run the DEM again even when a cached result exists");
  cmd.add_option("--dem-ladder", o.ladder,
                 "on (default): u_num's discretisation part from more runs: one at twice the time step, at three "
                 "conditions that span the belt speeds, carried to the others relative to each one's standard error "
                 "or value (at every condition when there are fewer than four), and two at 1.25 and 1.56 times "
                 "the particle size per condition when it is coarser than the dataset's (GCI); all: the time-step "
                 "run at every condition; off: statistical part only")
      ->check(CLI::IsMember({"on", "all", "off"}));
  cmd.add_option("--dem-restart", o.restart,
                 "on: a run with effects that act on a running station (the flow fed, the plate friction, forces in "
                 "flight, the belt's adhesion) continues the steady state of the same run without them instead of "
                 "filling the station again; off (default): every run starts from an empty station")
      ->check(CLI::IsMember({"on", "off"}));
  cmd.add_option(flag(api::DemSetting::steady_on), o.steady_on,
                 "the plate loads each DEM run's steady window is judged on: normal (R_n, as the LIGGGHTS rig did; "
                 "the default unless the dataset's [dem] steady_on says otherwise) or all (R_n, R_s and the moment: "
                 "the build-up on the plate settles later, and runs take longer; bench/WINDOW.md)")
      ->check(accepts(api::DemSetting::steady_on));
  cmd.add_option("--signature-quality", o.signature_quality,
                 "quality of the DEM's own effect-signature runs in diagnose (default: the --dem-quality)")
      ->check(accepts(api::DemSetting::quality));
  cmd.add_flag("--dem-cache-only", o.cache_only,
               "never run the DEM: every run must be in the cache (recorded acceptance cases; exit 2 otherwise)");
  with_rule(cmd.add_option(flag(api::DemSetting::plate_cells), o.plate_cells,
                           "rows of cells down the generated plate for the DEM's pressure and wear maps (0: two "
                           "triangles)"),
            api::rule(api::DemSetting::plate_cells));
  with_rule(cmd.add_option("--liggghts-ranks", o.liggghts_ranks,
                           "MPI ranks of each LIGGGHTS run (mpirun -n K liggghts; default 1)"),
            options::NumberRule{"", 1.0, 1e6, false, false, true, ""});
  cmd.add_option("--liggghts-command", o.liggghts_command,
                 "launcher and program that run a LIGGGHTS deck, e.g. \"srun liggghts\" (replaces mpirun -n K liggghts)");
  with_rule(cmd.add_option("--liggghts-time", o.liggghts_time,
                           "seconds simulated per LIGGGHTS run (default: the quality's maximum, 1.3 s at standard)"),
            kSimulatedTime);
}

void add_jobs_option(CLI::App& cmd, int& jobs) {
  with_rule(cmd.add_option("--jobs", jobs,
                           "independent DEM runs at a time in this process, each on one thread (under mpirun the "
                           "ranks share the runs instead); default: one per core other processes leave free; "
                           "results do not depend on it"),
            options::rules::jobs);
}

void add_quiet_option(CLI::App& cmd) {
  cmd.add_flag_callback("--quiet", [] { progress::set_quiet(true); },
                        "no progress on stderr (results, warnings and errors still print)");
}

api::DemOptions dem_options(const DemCli& o) {
  api::DemOptions d;
  d.quality = o.quality;
  d.threads = o.threads;
  d.cache = o.cache;
  d.no_cache = o.no_cache;
  d.cache_only = o.cache_only;
  d.ladder = o.ladder != "off";
  d.ladder_all = o.ladder == "all";
  d.restart = o.restart != "off";
  d.signature_quality = o.signature_quality;
  d.steady_on = o.steady_on;
  d.plate_cells = o.plate_cells;
  d.liggghts_ranks = o.liggghts_ranks;
  d.liggghts_command = o.liggghts_command;
  d.liggghts_time = o.liggghts_time;
  return d;
}

}  // namespace chutelab::app
