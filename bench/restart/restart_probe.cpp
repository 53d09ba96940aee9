// Restart probes against runs from an empty station (bench/RESTART.md): one condition's steady
// baseline is saved; each effect then runs twice, from empty and continued from that state, and the
// baseline itself is continued with no change (the paired run of common random numbers). Prints the
// plate load's steady means, their standard errors, the simulated and wall time of every run, and,
// per effect, the restart's difference from the continued baseline block by block (paired) against
// the unpaired difference of two independent runs.
//
//   restart_probe DATASET CONDITION QUALITY THREADS EFFECT=VALUE...
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include <unistd.h>

#include <fmt/format.h>

#include "core/input_error.h"
#include "dem/station/run.h"
#include "effects/registry.h"
#include "validation/dataset.h"
#include "validation/models/dem_model.h"

namespace st = chutelab::dem::station;
namespace v = chutelab::validation;

namespace {

// Means of `v` over consecutive blocks of `block` s within (a, b].
std::vector<double> blocks(const st::StationResult& r, double a, double b, double block, bool shear) {
  const int n = static_cast<int>(std::floor((b - a) / block + 1e-9));
  std::vector<double> sum(n, 0.0), cnt(n, 0.0);
  for (const auto& f : r.forces) {
    if (f.t <= a + 1e-12 || f.t > a + n * block + 1e-12) continue;
    const int i = std::min(n - 1, static_cast<int>(std::floor((f.t - a - 1e-12) / block)));
    sum[i] += shear ? f.shear : f.normal;
    cnt[i] += 1.0;
  }
  for (int i = 0; i < n; ++i) sum[i] /= cnt[i];
  return sum;
}

double mean(const std::vector<double>& x) {
  double s = 0;
  for (double v : x) s += v;
  return s / x.size();
}
double se(const std::vector<double>& x) {
  const double m = mean(x);
  double s = 0;
  for (double v : x) s += (v - m) * (v - m);
  return std::sqrt(s / (x.size() - 1) / x.size());
}

void line(const char* what, const st::StationResult& r) {
  fmt::print("{:<34} R_n {:8.3f} ± {:5.3f} N  R_s {:7.3f} ± {:5.3f} N  y_R {:6.2f} ± {:4.2f} mm  window {:.3f}-{:.3f} s  "
             "simulated {:.3f} s  wall {:5.1f} s\n",
             what, r.normal_force.value, r.normal_force.se, r.shear_force.value, r.shear_force.se,
             r.impact_point_y.value * 1e3, r.impact_point_y.se * 1e3, r.window.start, r.window.end,
             r.simulated_time - std::max(0.0, r.restart_time), r.wall_seconds);
}

int probe(int argc, char** argv) {
  if (argc < 6) {
    std::fprintf(stderr, "usage: restart_probe DATASET CONDITION QUALITY THREADS EFFECT=VALUE...\n");
    return 2;
  }
  const std::filesystem::path dir = argv[1];
  const auto setup = v::read_setup(dir / "setup.toml");
  const auto stations = v::read_conditions(dir / "conditions.csv", setup);
  const chutelab::Station station = v::condition_row(stations, argv[2], dir / "conditions.csv", "condition");
  const st::DemTable table = st::read_dem_table((dir / "setup.toml").string());
  st::SettingsOverrides ov;
  if (const auto q = st::parse_quality(argv[3])) ov.set_quality(*q);
  ov.threads = std::stoi(argv[4]);
  const st::RunSettings settings = st::resolve(table, ov);
  // One state file per process: two probes side by side must not read each other's state.
  const std::string state =
      (std::filesystem::temp_directory_path() / fmt::format("restart_probe.{}.state", static_cast<long>(getpid()))).string();

  auto run = [&](const v::DemEffectInputs& fx, std::optional<st::Restart> rs, bool save) {
    st::RunOptions o;
    o.settings = settings;
    o.geometry = table;
    o.external = fx.external;
    o.restart = rs;
    if (save) o.save_state = state;
    return st::run_station(fx.station, o);
  };
  const v::DemEffectInputs base = v::dem_effect_inputs(station, {});
  const st::StationResult b = run(base, std::nullopt, true);
  line("baseline from empty", b);
  const st::StationResult bc = run(base, st::Restart{state, st::ChangeAt::plate}, false);
  line("baseline continued", bc);
  for (int k = 5; k < argc; ++k) {
    const auto fx = v::dem_effect_inputs(station, chutelab::effects::instantiate({chutelab::effects::parse_setting(argv[k], false)}));
    const auto at = v::restart_change(base, fx);
    if (!at) {
      std::fprintf(stderr, "restart_probe: %s does not act on a running station (another rig): no restart\n", argv[k]);
      return 2;
    }
    const st::StationResult e = run(fx, std::nullopt, false);
    const st::StationResult c = run(fx, st::Restart{state, *at}, false);
    line(fmt::format("{} from empty", argv[k]).c_str(), e);
    line(fmt::format("{} restarted", argv[k]).c_str(), c);
    const double dn = c.normal_force.value - e.normal_force.value;
    fmt::print("  restarted - from empty: R_n {:+.3f} N = {:+.2f} combined se; R_s {:+.3f} N = {:+.2f} se\n", dn,
               dn / std::hypot(c.normal_force.se, e.normal_force.se), c.shear_force.value - e.shear_force.value,
               (c.shear_force.value - e.shear_force.value) / std::hypot(c.shear_force.se, e.shear_force.se));
    // Paired: the restart and the continued baseline over the same 0.1 s blocks after the transit.
    const double a = c.transient_end, end = std::min(c.simulated_time, bc.simulated_time);
    for (bool shear : {false, true}) {
      const auto x = blocks(c, a, end, settings.mean_block, shear), y = blocks(bc, a, end, settings.mean_block, shear);
      if (x.size() < 3) continue;
      std::vector<double> d(x.size());
      for (std::size_t i = 0; i < x.size(); ++i) d[i] = x[i] - y[i];
      fmt::print("  paired {} over {} blocks: difference {:+.3f} ± {:.3f} N; unpaired ± {:.3f} N (ratio {:.2f})\n",
                 shear ? "R_s" : "R_n", d.size(), mean(d), se(d), std::hypot(se(x), se(y)),
                 se(d) / std::hypot(se(x), se(y)));
    }
  }
  std::filesystem::remove(state);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return probe(argc, argv);
  } catch (const chutelab::InputError& e) {
    std::fprintf(stderr, "restart_probe: %s\n", e.what());
    return 2;
  }
}
