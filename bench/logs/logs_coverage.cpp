// The log import against the virtual rig (bench/LOGS.md): for each scenario (clean, zero drift,
// creep, all at once) and 100 seeds, sampled at 10, 25, 50 and 100 Hz in turn, how often ±2 u holds
// the true mean, and how often the log is flagged.
//   logs_coverage [seeds] [scratch folder]
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "logs/virtual_rig_check.h"

using namespace chutelab;
using namespace chutelab::logs;

int main(int argc, char** argv) {
  const int seeds = argc > 1 ? std::atoi(argv[1]) : 100;
  const std::filesystem::path scratch =
      argc > 2 ? std::filesystem::path(argv[2]) : std::filesystem::temp_directory_path() / "chutelab-logs-bench";
  TrueCondition truth;
  truth.condition = "V4-28";  // the reference study's 4 m/s, 28 t/h: R_n ~ 30 N, R_s ~ 2 N, y_R ~ -86 mm
  truth.normal = 30.0;
  truth.shear = 2.5;
  truth.impact_y = -0.086;
  truth.belt_speed = 4.0;
  truth.mass_flow = 28.0 / 3.6;
  struct Scenario {
    const char* name;
    double drift_N, creep_per_s;
    bool dirty;
  };
  const Scenario scenarios[] = {
      {"clean", 0.0, 0.0, false},
      {"zero drift 0.5 N", 0.5, 0.0, true},
      {"creep 0.1 %/s", 0.0, 0.001, true},
      {"creep 0.2 %/s", 0.0, 0.002, true},
      {"creep 0.3 %/s", 0.0, 0.003, true},
      {"creep 0.4 %/s", 0.0, 0.004, true},
      {"creep 0.5 %/s", 0.0, 0.005, true},
      {"drift and creep", 0.5, 0.005, true},
  };
  const std::vector<double> rates = {10.0, 25.0, 50.0, 100.0};
  std::printf("| scenario | logs | flagged | drift flagged | creep flagged | too short | R_n covered | R_s covered | R covered | y_R covered | RMS z R_n | RMS z R_s | RMS z y_R | u/R_n |\n");
  std::printf("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
  for (const auto& sc : scenarios) {
    SensorModel m;
    m.drift_N = sc.drift_N;
    m.creep_per_s = sc.creep_per_s;
    const TrialCounts c = run_trials(truth, m, 1000, seeds, rates, scratch);
    auto cov = [&](Quantity q) { return c.read.count(q) ? 100.0 * c.covered.at(q) / c.read.at(q) : 0.0; };
    auto rms = [&](Quantity q) { return c.read.count(q) ? std::sqrt(c.sum_z2.at(q) / c.read.at(q)) : 0.0; };
    std::printf("| %s | %d | %d %% | %d %% | %d %% | %d %% | %.0f %% | %.0f %% | %.0f %% | %.0f %% | %.2f | %.2f | %.2f | %.2f %% |\n",
                sc.name, c.logs, 100 * c.flagged / c.logs, 100 * c.drift_flagged / c.logs,
                100 * c.creep_flagged / c.logs, 100 * c.warned_short / c.logs, cov(Quantity::normal_force),
                cov(Quantity::shear_force), cov(Quantity::resultant_force), cov(Quantity::impact_point_y),
                rms(Quantity::normal_force), rms(Quantity::shear_force), rms(Quantity::impact_point_y),
                100.0 * c.sum_rel_u.at(Quantity::normal_force) / c.read.at(Quantity::normal_force));
    std::fflush(stdout);
  }
  std::filesystem::remove_all(scratch);
  return 0;
}
