// `chutelab simulate`: one DEM run of one condition of a dataset, with a progress bar, the steady
// means and their uncertainties on stdout, and CSV time series, a side view and VTK in --out.
#include <filesystem>
#include <fmt/format.h>
#include <iostream>
#include <map>

#include "api/simulate.h"
#include "app/commands.h"
#include "app/output_hook.h"
#include "app/dem_options.h"
#include "app/flag_names.h"
#include "app/option_checks.h"
#include "core/input_error.h"
#include "core/message.h"
#include "core/output_folder.h"

namespace chutelab::app {
namespace {

// Frames of the particle series per simulated second by default: 20 (a quick run of ~2 s gives ~40
// frames, a few MB).
constexpr double kSeriesEvery = 0.05;

struct SimulateCli {
  std::string dataset, condition, out;
  std::optional<double> vtk_every;
  api::SettingsOverrides settings;  // the [dem] settings' flags, --threads and the wear inputs' flags
  std::vector<std::string> effects;
  bool no_cache = false;
};

// The flag of one [dem] setting: its option's flag (flag_for), its help and unit from the table, its
// range as the rule of the value typed; it sets the setting in `into`.
void add_setting_flag(CLI::App& cmd, const api::DemField& f, api::SettingsOverrides& into) {
  const std::string option(f.option);
  std::string help = fmt::format("{}{}", f.help, f.unit.empty() ? "" : ", " + std::string(f.unit));
  if (!f.zero_means.empty()) help += fmt::format(" (0: {})", f.zero_means);
  if (f.kind == api::DemKind::word) help += ": " + f.range_text();
  help += fmt::format("; [dem] {}", f.key);
  if (f.kind == api::DemKind::word) {
    cmd.add_option_function<std::string>(flag_for(option), [&into, option](const std::string& w) { into.set(option, w); }, help)
        ->check(CLI::Validator(
            [&f](std::string& w) -> std::string {
              api::DemValue v;
              v.word = w;
              const auto p = f.problem(v);
              return p ? *p : std::string();
            },
            "", "dem-setting"));
  } else if (f.kind == api::DemKind::whole) {
    with_rule(cmd.add_option_function<std::uint64_t>(flag_for(option),
                                                      [&into, option](std::uint64_t v) { into.set_whole(option, v); }, help),
              f.rule(""));
  } else {
    with_rule(cmd.add_option_function<double>(flag_for(option), [&into, option](double v) { into.set(option, v); }, help),
              f.rule(""));
  }
}

std::string row(const char* label, const api::MeanWithError& e, double scale, const char* unit, int digits) {
  if (!e.ok()) return fmt::format("  {:<34} {:>10}\n", label, "-");
  const std::string se = std::isfinite(e.se) ? fmt::format(" ± {:.{}f}", e.se * scale, digits) : std::string();
  return fmt::format("  {:<34} {:>10.{}f}{} {}\n", label, e.value * scale, digits, se, unit);
}

int run_simulate(const SimulateCli& o) {
  namespace fs = std::filesystem;
  api::SimulateOptions opt;
  opt.dataset = o.dataset;
  opt.default_dataset = default_dataset();
  opt.condition = o.condition;
  opt.settings = o.settings;
  opt.effects = o.effects;
  opt.vtk_every = o.vtk_every;
  opt.default_vtk_every = kSeriesEvery;
  opt.store_in_cache = !o.no_cache;
  opt.progress = true;
  // Series, side view and VTK are staged and placed in --out only when the run has finished.
  std::optional<OutputFolder> out;
  if (!o.out.empty())
    opt.prepare_output = place_output(out, o.out, "simulate", [&](OutputFolder& f, const api::OutputPlan&) {
      if (o.vtk_every) f.check_entry("vtk", true);
      return f.staging();
    });
  const api::SimulateResult res = api::simulate(opt);
  if (out) {
    res.write_files(out->staging());
    out->commit();
  }
  const Setup& setup = res.setup;
  const Station* station = &res.station;
  const api::RunSettings& settings = res.settings;
  const api::StationResult& r = res.run;
  std::cout << fmt::format("DEM run of {} / {} ({} quality, {:.1f} mm {}s, dt {:.3g} s)\n", one_line(setup.name, 80),
                           one_line(station->condition, 80),
                           r.quality, r.diameter * 1e3, r.shape == "clump" ? "two-sphere clump" : "sphere", r.dt);
  std::cout << fmt::format("simulated {:.2f} s in {:.0f} s wall ({} steps, up to {} particles){}\n", r.simulated_time,
                           r.wall_seconds, r.steps, r.peak_particles, r.early_stop ? ", stopped when steady" : "");
  std::cout << fmt::format("steady window {:.2f}-{:.2f} s ({} blocks of {:.1f} s){}\n", r.window.start, r.window.end,
                           r.window.blocks, settings.mean_block, r.window.found ? "" : " — NOT steady");
  std::cout << "steady means ± standard error of the mean:\n";
  std::cout << row("plate normal force R_n", r.normal_force, 1, "N", 3);
  std::cout << row("plate shear force R_s", r.shear_force, 1, "N", 3);
  std::cout << row("resultant R", r.resultant_force, 1, "N", 3);
  std::cout << row("impact point y_R", r.impact_point_y, 1e3, "mm", 1);
  std::cout << row("impact velocity V_p (10-30 mm slab)", r.impact_velocity, 1, "m/s", 3);
  std::cout << row("  free-stream particles only", r.impact_velocity_fast, 1, "m/s", 3);
  std::cout << row("exit velocity V_a", r.exit_velocity, 1, "m/s", 3);
  std::cout << row("layer speed before the pulley", r.layer_speed, 1, "m/s", 3);
  std::cout << row("stream thickness on the belt", r.stream_thickness, 1e3, "mm", 1);
  std::cout << row("layer: mean centre height", r.layer_height, 1e3, "mm", 1);
  std::cout << row("free-stream mass flux (x = Z/2)", r.mass_flux, 1, "kg/s", 3);
  std::cout << row("momentum the stream delivers", r.momentum_balance, 1, "N", 3);
  std::cout << fmt::format("mass: inserted {:.3f} kg = discharged {:.3f} + escaped {:.3f} + in the rig {:.3f} kg\n",
                           r.inserted, r.discharged, r.escaped, r.in_domain);
  if (!r.maps.empty() && !r.maps.front().cells.empty()) {
    const api::PlateMap& m = r.maps.front();
    double peak_p = 0.0, peak_w = 0.0, wear_sum = 0.0, area = 0.0, normal = 0.0;
    for (const auto& c : m.cells) {
      normal += c.pressure() * c.area;
      peak_p = std::max(peak_p, c.pressure());
      const double wr = c.archard_rate(r.wear) + c.finnie_rate(r.wear);
      peak_w = std::max(peak_w, wr);
      wear_sum += wr * c.area;
      area += c.area;
    }
    std::cout << fmt::format(
        "plate map ({} triangles, {:.2f} s): peak pressure {:.3g} kPa at y = {:.1f} mm (profile across the plate), centre of "
        "pressure y = {:.1f} mm, peak wear {:.3g} µm/h, mean {:.3g} µm/h, normal load of the map {:.3f} N\n",
        m.cells.size(), m.duration, peak_p * 1e-3, api::peak_pressure_y(m) * 1e3, api::pressure_centre_y(m) * 1e3,
        peak_w * 3.6e9, area > 0.0 ? wear_sum / area * 3.6e9 : 0.0, normal);
  }
  for (const auto& n : r.notes) std::cout << "note: " << n << "\n";
  for (const auto& d : api::window_drifts(r)) std::cout << "note: " << d.note << "\n";
  for (const auto& n : res.effect_notes) std::cout << "note: " << n << "\n";
  if (!o.out.empty()) std::cout << fmt::format("files: {}\n", o.out);
  return kExitOk;
}

}  // namespace

void add_simulate(CLI::App& app, Action& action) {
  auto o = std::make_shared<SimulateCli>();
  auto* cmd = app.add_subcommand("simulate",
                                 "Run the DEM of one condition of a dataset: progress on stderr, steady means "
                                 "with uncertainties on stdout, CSV series, side view and VTK in --out.");
  cmd->add_option("--dataset", o->dataset, "dataset folder (default: the bundled grima2010 rig)");
  cmd->add_option("--condition", o->condition, "condition (row of conditions.csv)")->required();
  add_quiet_option(*cmd);
  // One flag per [dem] setting with an option (dem/station/settings.h dem_fields()), checked here, by
  // the flag as typed, before the dataset is read; it beats the dataset's [dem] table.
  for (const auto& f : api::dem_fields())
    if (!f.option.empty()) add_setting_flag(*cmd, f, o->settings);
  with_rule(cmd->add_option("--threads", o->settings.threads, "OpenMP threads (results do not depend on it)"),
            options::rules::threads);
  cmd->add_option("--effect", o->effects, "physical effect NAME=VALUE (those with a DEM counterpart act)");
  cmd->add_option("--out", o->out, "output folder: CSV series, steady means, side view, VTK");
  with_rule(cmd->add_option("--vtk-every", o->vtk_every,
                            fmt::format("interval of the particle time series in --out, simulated seconds (default {} "
                                        "s): vtk/particles.pvd, which ParaView opens as one series, lists one VTK XML "
                                        "PolyData file (vtk/particles_NNNNN.vtp, raw binary appended data) per frame "
                                        "with each particle's id, clump, radius, velocity, speed and contact-force "
                                        "magnitude; the last frame is the final state",
                                        kSeriesEvery)),
            options::NumberRule{"", 0.0, 100.0, true, false, false, "s"});
  cmd->add_flag("--no-cache", o->no_cache, "do not store the result in the DEM cache");
  for (const auto& f : api::wear_fields()) {
    std::string flag = std::string("--") + f.key;
    for (auto& ch : flag) ch = ch == '_' ? '-' : ch;
    const std::string key = f.key;
    cmd->add_option_function<double>(flag, [o, key](double v) { o->settings.wear.emplace_back(key, v); },
                                     std::string(f.help) + " ([dem.wear] " + key + ")");
  }
  cmd->callback([o, &action] { action = [o] { return run_simulate(*o); }; });
}

}  // namespace chutelab::app
