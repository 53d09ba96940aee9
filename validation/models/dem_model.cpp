#include "validation/models/dem_model.h"

#include "core/rig_needs.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <mutex>
#include <sstream>

#include <fmt/format.h>

#include "core/file_name.h"
#include "core/input_error.h"
#include "core/message.h"
#include "core/campaign.h"
#include "dem/station/cache.h"
#include "dem/station/progress.h"
#include "dem/station/run.h"
#include "validation/gci.h"
#include "validation/models/models.h"

namespace chutelab::validation {
namespace {

namespace st = dem::station;

std::string num(double v) { return fmt::format("{:.17g}", v); }

// File contents enter the key by hash (an edited STL is a different rig).
std::string file_key(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  std::stringstream ss;
  ss << f.rdbuf();
  return fmt::format("{} {:016x}", path, st::fnv1a64(ss.str()));
}

// The DEM's stream limit at x (value and standard error), linear between the grid's rows (10 mm
// apart); none outside the grid or across a gap in it.
std::optional<st::Estimate> trajectory_estimate(const std::vector<st::TrajectoryRow>& rows, Boundary b, double x) {
  auto pick = [&](const st::TrajectoryRow& r) -> const st::Estimate& {
    return b == Boundary::upper ? r.upper : b == Boundary::lower ? r.lower : r.centre;
  };
  for (std::size_t k = 0; k + 1 < rows.size(); ++k) {
    const auto &a = rows[k], &c = rows[k + 1];
    if (x < a.x - 1e-9 || x > c.x + 1e-9) continue;
    if (c.x - a.x > 0.0105) continue;  // a gap in the grid: no stream there
    const auto &ya = pick(a), &yc = pick(c);
    if (!ya.ok() || !yc.ok()) return std::nullopt;
    const double f = (x - a.x) / (c.x - a.x);
    st::Estimate e;
    e.value = ya.value + f * (yc.value - ya.value);
    e.se = std::hypot((1 - f) * ya.se, f * yc.se);
    return e;
  }
  if (rows.size() == 1 && std::abs(rows[0].x - x) < 1e-9 && pick(rows[0]).ok()) return pick(rows[0]);
  return std::nullopt;
}

std::optional<double> trajectory_at(const std::vector<st::TrajectoryRow>& rows, Boundary b, double x) {
  if (const auto e = trajectory_estimate(rows, b, x)) return e->value;
  return std::nullopt;
}

// Results of campaign jobs (validation/campaign_runs.h) by cache key: "cached 0|1\n" + to_text.
// Every rank holds the same texts, so predict() sees the same numbers on every rank.
std::mutex& ready_mutex() {
  static std::mutex m;
  return m;
}
std::map<std::string, std::string>& ready() {
  static std::map<std::string, std::string> r;
  return r;
}

// How a run's result was had, for its note: from the cache, or run now and then cached or not;
// and a damaged entry found in the cache on the way (refused, so the run was made again).
struct CacheOutcome {
  bool from_cache = false;
  std::string refused;    // the refused entry's "FILE:LINE: field: problem"
  std::string unwritten;  // why the run could not be cached
  std::string file;       // the entry's path
};

// A campaign job's result: "cached 0|1\n", "refused TEXT\n" and "unwritten TEXT\n" when set, then
// to_text. The outcome travels with the numbers, so every rank's note says what happened.
std::string result_text(const st::StationResult& r, const CacheOutcome& how) {
  std::string o = how.from_cache ? "cached 1\n" : "cached 0\n";
  if (!how.refused.empty()) o += "refused " + one_line(how.refused) + "\n";
  if (!how.unwritten.empty()) o += "unwritten " + one_line(how.unwritten) + "\n";
  return o + st::to_text(r);
}

std::optional<std::pair<st::StationResult, CacheOutcome>> parse_result(const std::string& text) {
  if (text.rfind("cached ", 0) != 0 || text.size() < 9) return std::nullopt;
  CacheOutcome how;
  how.from_cache = text[7] == '1';
  std::size_t at = 9;
  for (const auto& [tag, to] : {std::pair{std::string_view("refused "), &how.refused},
                                std::pair{std::string_view("unwritten "), &how.unwritten}})
    if (std::string_view(text).substr(at).starts_with(tag)) {
      const std::size_t nl = text.find('\n', at);
      if (nl == std::string::npos) return std::nullopt;
      *to = text.substr(at + tag.size(), nl - at - tag.size());
      at = nl + 1;
    }
  auto r = st::from_text(text.substr(at));
  if (!r) return std::nullopt;
  return std::make_pair(std::move(*r), std::move(how));
}

// The plate map's value at a point of the face (the triangle whose (z, y) projection holds it) and
// its standard error from the cell's block means.
std::pair<std::optional<double>, std::optional<double>> plate_value(const st::StationResult& r, const PlateQuery& q) {
  if (r.maps.empty()) return {};
  for (const auto& c : r.maps.front().cells) {
    const Eigen::Vector2d a(c.corners[0].z(), c.corners[0].y()), b(c.corners[1].z(), c.corners[1].y()),
        d(c.corners[2].z(), c.corners[2].y()), x(q.z, q.y);
    auto cross = [](const Eigen::Vector2d& u, const Eigen::Vector2d& v) { return u.x() * v.y() - u.y() * v.x(); };
    const double s0 = cross(b - a, x - a), s1 = cross(d - b, x - b), s2 = cross(a - d, x - d);
    const bool inside = (s0 >= 0 && s1 >= 0 && s2 >= 0) || (s0 <= 0 && s1 <= 0 && s2 <= 0);
    if (!inside || !(std::abs(cross(b - a, d - a)) > 0.0)) continue;
    const double rate = c.archard_rate(r.wear) + c.finnie_rate(r.wear);
    auto se = [](double v) { return std::isfinite(v) ? std::optional<double>(v) : std::nullopt; };
    if (q.quantity == "plate_pressure_Pa") return {c.pressure(), se(c.pressure_se())};
    if (q.quantity == "plate_shear_stress_Pa") return {c.shear_stress(), std::nullopt};
    if (q.quantity == "wear_rate_um_per_h") return {rate, se(c.wear_rate_se(r.wear))};
    if (q.quantity == "wear_depth_um" && r.wear.exposure_hours > 0.0) {
      const double h = r.wear.exposure_hours * 3600.0;
      const auto u = se(c.wear_rate_se(r.wear));
      return {rate * h, u ? std::optional<double>(*u * h) : std::nullopt};
    }
    return {};
  }
  return {};  // off the plate
}

class DemModel final : public Model {
 public:
  explicit DemModel(DemModelConfig c) : c_(std::move(c)) {}
  std::string name() const override { return "dem"; }
  std::string description() const override {
    return "DEM of the transfer station (chutelab dem/station): Hertz-Mindlin spheres, sensors as the LIGGGHTS rig's";
  }
  bool expensive() const override { return true; }
  // The DEM responds to an effect when the effect changes one of its inputs (feed, belt speed,
  // plate friction, flight force, belt cohesion, the rig as really built): the run's key then differs.
  bool cheaper_signatures() const override { return c_.signature_quality.has_value(); }
  bool represents(const Station& station, const analytical::EffectList& fixed,
                  const analytical::EffectList& with_candidate) const override {
    const DemEffectInputs a = dem_effect_inputs(station, fixed), b = dem_effect_inputs(station, with_candidate);
    return a.key != b.key || canonical_station(a.station) != canonical_station(b.station);
  }

  // The settings a request runs at: the command line's, or for a signature at a cheaper quality
  // that quality's own preset (the dataset's table goes on top in resolve).
  st::SettingsOverrides overrides_for(const PredictRequest& request) const {
    // The seed, the threads and the window's rule stay the user's at any quality (DemField::kept).
    if (request.signature && c_.signature_quality) return c_.overrides.at_quality(*c_.signature_quality);
    return c_.overrides;
  }

  ModelPrediction predict(const Station& station, const analytical::EffectList& effects,
                          const PredictRequest& request) const override {
    require_dem_keys(station, c_.setup_file.empty() ? std::string("setup.toml") : c_.setup_file);
    const st::DemTable& table = c_.dem_table();
    const st::RunSettings settings = st::resolve(table, overrides_for(request));
    const DemEffectInputs fx = dem_effect_inputs(station, effects);
    CacheOutcome how;
    const st::StationResult r = run_or_load(station, fx, settings, table, how);
    if (!c_.output_dir.empty() && campaign::output_rank()) {
      // The condition's name is data ("../../ds"): mapped to one plain folder name (core/file_name.h).
      const auto dir = std::filesystem::path(c_.output_dir) / file_name_for(station.condition);
      st::write_result_files(dir.string(), r);
      st::write_side_view_vtk((dir / "side_view.vtk").string(), r.side_view);
    }
    ModelPrediction p = to_prediction(r, fx, request, how);
    if (request.discretisation && c_.ladder) add_ladder(p, station, effects, fx, settings, table, request);
    return p;
  }

 private:
  // How a run is made: from empty, or continuing the steady state of the run without effects.
  struct Plan {
    std::string key;
    std::optional<st::ChangeAt> restart;
    std::string base_key;  // the run without effects (restarts, and the runs that keep their state)
  };
  Plan plan(const Station& station, const DemEffectInputs& fx, const st::RunSettings& settings,
            const st::DemTable& table) const {
    Plan p;
    p.key = dem_cache_key(fx, settings, table);
    if (!c_.restart) return p;
    const DemEffectInputs base = dem_effect_inputs(station, {});
    p.base_key = dem_cache_key(base, settings, table);
    p.restart = restart_change(base, fx);
    if (p.restart)
      p.key += fmt::format("restart: continues the steady state of the run without effects; the change acts at the {}\n",
                           st::name(*p.restart));
    return p;
  }

  st::ResultCache cache() const {
    return st::ResultCache(c_.cache_dir.empty() ? st::ResultCache::default_dir() : c_.cache_dir);
  }

  // Where the run without effects keeps its final state: beside its result in the cache, or with
  // --no-dem-cache in the temporary folder.
  std::string state_path(const std::string& base_key) const {
    namespace fs = std::filesystem;
    const fs::path result = cache().path_for(base_key);
    fs::path dir = c_.use_cache ? result.parent_path() : fs::temp_directory_path() / "chutelab-dem-states";
    fs::create_directories(dir);
    return (dir / result.filename()).replace_extension(".state").string();
  }

  // The final state of the run without effects, made now when it is not there (the run itself is
  // deterministic: its result equals the cached one, which is kept).
  std::string base_state(const Station& station, const st::RunSettings& settings, const st::DemTable& table,
                         const std::string& base_key) const {
    const std::string path = state_path(base_key);
    const std::lock_guard<std::mutex> lock(state_mutex(path));
    if (std::filesystem::exists(path)) return path;
    const DemEffectInputs base = dem_effect_inputs(station, {});
    st::RunOptions o = run_options(station, base, settings, table, " (steady state to continue)");
    o.save_state = path;
    const st::StationResult r = st::run_station(base.station, o);
    if (c_.use_cache && !cache().load(base_key)) cache().store(base_key, r);
    return path;
  }

  static std::mutex& state_mutex(const std::string& path) {
    static std::mutex guard;
    static std::map<std::string, std::unique_ptr<std::mutex>> locks;
    const std::lock_guard<std::mutex> lock(guard);
    auto& m = locks[path];
    if (!m) m = std::make_unique<std::mutex>();
    return *m;
  }

  st::RunOptions run_options(const Station& station, const DemEffectInputs& fx, const st::RunSettings& settings,
                             const st::DemTable& table, const std::string& what) const {
    st::RunOptions o;
    o.settings = settings;
    o.geometry = table;
    o.external = fx.external;
    if (c_.progress)
      o.progress = st::ProgressPrinter(
          settings.particle_diameter > 0 && settings.particle_diameter != station.material.particle_diameter
              ? fmt::format("dem {} ({:.1f} mm){}", station.condition, settings.particle_diameter * 1e3, what)
              : fmt::format("dem {}{}", station.condition, what));
    return o;
  }

  // The run of these inputs: from the cache, or run now (and cached). An entry that is there but
  // damaged is refused, said, and run again; told never to run, that is an error naming the file.
  st::StationResult run_or_load(const Station& station, const DemEffectInputs& fx, const st::RunSettings& settings,
                                const st::DemTable& table, CacheOutcome& out) const {
    const Plan how = plan(station, fx, settings, table);
    const std::string& key = how.key;
    const st::ResultCache cache = this->cache();
    out.file = cache.path_for(key);
    {  // a campaign's result (validation/campaign_runs.h): the same text on every rank
      const std::lock_guard<std::mutex> lock(ready_mutex());
      if (auto it = ready().find(key); it != ready().end())
        if (auto got = parse_result(it->second)) {
          const std::string file = out.file;
          out = std::move(got->second);
          out.file = file;
          return std::move(got->first);
        }
    }
    if (c_.use_cache) {
      st::CacheEntry entry = cache.lookup(key);
      if (entry.result) {
        out.from_cache = true;
        entry.result->wear = settings.wear;  // the cache keeps the maps' sums; the rates use these wear inputs
        return std::move(*entry.result);
      }
      if (entry.refused) {
        if (c_.cache_only)
          throw InputError(entry.file, entry.refused->line, entry.refused->field,
                           fmt::format("{}; the DEM cache entry of condition {} is refused and {} does not run it again",
                                       entry.refused->problem, station.condition, mention("dem.cache_only")));
        out.refused = entry.said();
        warn(fmt::format("DEM cache entry refused, running condition {} again: {}", station.condition, out.refused));
      }
    }
    if (c_.cache_only)
      throw InputError("", 0, "dem.cache_only",
                       fmt::format("no cached DEM run of condition {} ({} mm particles) with these settings and "
                                   "effects in {} (expected {})",
                                   station.condition,
                                   1e3 * (settings.particle_diameter > 0 ? settings.particle_diameter
                                                                         : station.material.particle_diameter),
                                   cache.dir(), cache.path_for(key)));
    st::RunOptions o = run_options(station, fx, settings, table, how.restart ? " (continued)" : "");
    std::unique_lock<std::mutex> keeping;
    if (how.restart) {
      o.restart = st::Restart{base_state(station, settings, table, how.base_key), *how.restart};
    } else if (c_.restart && key == how.base_key) {
      // The run without effects keeps its state for the runs that will continue it.
      o.save_state = state_path(key);
      keeping = std::unique_lock<std::mutex>(state_mutex(o.save_state));
      if (std::filesystem::exists(o.save_state)) o.save_state.clear();
    }
    st::StationResult r = st::run_station(fx.station, o);
    if (c_.use_cache) {
      if (const st::CacheWrite w = cache.store(key, r); !w) {
        out.unwritten = w.problem;
        warn(fmt::format("DEM run of condition {} not cached: {}", station.condition, w.problem));
      }
    } else {
      out.unwritten = "the cache is off";
    }
    // Read back from its text, as a campaign's result is: the same numbers to the last bit.
    if (auto back = st::from_text(st::to_text(r))) return std::move(*back);
    return r;
  }

 public:
  // The runs a prediction of this request needs, as campaign jobs (validation/campaign_runs.h):
  // the run itself and, when it asks for u_num's discretisation part, its ladder's runs.
  std::vector<ModelJob> campaign_jobs(const Station& station, const analytical::EffectList& effects,
                                      const PredictRequest& request) const override {
    require_dem_keys(station, c_.setup_file.empty() ? std::string("setup.toml") : c_.setup_file);
    const st::DemTable& table = c_.dem_table();
    st::SettingsOverrides over = overrides_for(request);
    const st::RunSettings settings = st::resolve(table, over);
    const DemEffectInputs fx = dem_effect_inputs(station, effects);
    std::vector<ModelJob> out;
    if (auto j = job_for(station, fx, settings, table, false, "")) out.push_back(std::move(*j));
    if (!request.discretisation || !c_.ladder) return out;
    const std::vector<Station> carried_from = ladder_subset();
    for (const Ladder& l : ladders(station, settings)) {
      if (l.what == "time-step" && !carried_from.empty()) {
        // The subset's runs and their ladders (each condition lists them; the campaign keeps one).
        for (const Station& s : carried_from) {
          const DemEffectInputs fs = dem_effect_inputs(s, effects);
          if (auto j = job_for(s, fs, settings, table, false, "")) out.push_back(std::move(*j));
          for (const auto& rung : time_step_ladder(settings).coarser)
            if (auto j = job_for(s, fs, rung.second, table, true, rung_words(l.what, rung.second)))
              out.push_back(std::move(*j));
        }
        continue;
      }
      for (const auto& rung : l.coarser)
        if (auto j = job_for(station, fx, rung.second, table, true, rung_words(l.what, rung.second)))
          out.push_back(std::move(*j));
    }
    return out;
  }

 private:
  // One run as a campaign job; none when this process already holds its result. A ladder run that
  // cannot be made (its coarser particles do not fit the rig) is not the command's failure: its
  // job returns no result, and the prediction notes that the part is missing (add_ladder).
  // What a ladder run is, for progress lines: "2 dt", "17.0 mm particles".
  static std::string rung_words(const std::string& what, const st::RunSettings& s) {
    if (what == "time-step") return "2 dt";
    return fmt::format("{:.1f} mm particles", s.particle_diameter * 1e3);
  }

  std::optional<ModelJob> job_for(const Station& station, const DemEffectInputs& fx, const st::RunSettings& settings,
                                  const st::DemTable& table, bool optional_run, const std::string& rung) const {
    const Plan how = plan(station, fx, settings, table);
    const std::string& key = how.key;
    {
      const std::lock_guard<std::mutex> lock(ready_mutex());
      if (ready().count(key)) return std::nullopt;
    }
    ModelJob j;
    j.id = key;
    j.ladder_rung = rung;
    j.job.key = rung.empty() ? fmt::format("dem {}", station.condition)
                             : fmt::format("dem {} ({}, for u_num)", station.condition, rung);
    // Particles in the rig scale with the feed over d^3 and steps with 1/dt ~ 1/d: enough to put
    // the dear runs first; the numbers are never compared with a clock.
    const double d = settings.particle_diameter > 0.0 ? settings.particle_diameter : fx.station.material.particle_diameter;
    j.job.cost = fx.station.mass_flow * settings.max_time / std::pow(d / 0.01, 4.0) *
                 (settings.particle_shape == st::ParticleShape::clump ? 2.7 : 1.0) * (0.1 / settings.dt_fraction);
    // A continued run comes after the run it continues (which keeps its state), when both are jobs.
    if (how.restart) j.job.cost *= 0.5;
    j.job.run = [this, station, fx, settings, table, optional_run](const campaign::JobContext& ctx) -> std::string {
      CacheOutcome how;
      // Runs side by side (ranks, --jobs) each take the threads the campaign gives them unless the
      // user chose; the thread count is not part of the result (nor of the cache key).
      st::RunSettings s = settings;
      if (s.threads == 0) {
        s.threads = ctx.threads;
        s.extra_threads = ctx.idle;
      }
      try {
        const st::StationResult r = run_or_load(station, fx, s, table, how);
        if (how.from_cache && ctx.reused) *ctx.reused = true;
        return result_text(r, how);
      } catch (const InputError&) {
        if (!optional_run || c_.cache_only) throw;
        return std::string();
      }
    };
    j.accept = [key](const std::string& text) {
      if (text.empty()) return;
      const std::lock_guard<std::mutex> lock(ready_mutex());
      ready()[key] = text;
    };
    return j;
  }

  // One one-factor ladder of a run (add_ladder): the run's own refinement parameter h and the
  // coarser runs, each with its h.
  struct Ladder {
    std::string what, label;
    double h_run = 1.0;
    std::vector<std::pair<double, st::RunSettings>> coarser;
  };

  // The ladders of a run at `settings`: twice the time step, always; coarser particles when the
  // run coarse-grains the dataset's, with h = d / d_data - 1 (zero at the dataset's own size).
  static Ladder time_step_ladder(const st::RunSettings& settings) {
    Ladder dt{"time-step", "time step dt, 2 dt", 1.0, {}};
    st::RunSettings s = settings;
    s.dt_fraction *= 2.0;
    s.rayleigh_fraction *= 2.0;
    dt.coarser.emplace_back(2.0, s);
    return dt;
  }

  // The conditions whose time-step ladders are carried to all (DemModelConfig::ladder_conditions):
  // the slowest and the fastest stream and the middle one, by belt speed, then flow. None: every
  // condition ladders itself.
  std::vector<Station> ladder_subset() const {
    const auto& all = c_.ladder_conditions;
    if (c_.ladder_all || all.size() <= 3) return {};
    std::vector<std::size_t> order(all.size());
    for (std::size_t k = 0; k < order.size(); ++k) order[k] = k;
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
      if (all[a].belt_speed != all[b].belt_speed) return all[a].belt_speed < all[b].belt_speed;
      return all[a].mass_flow < all[b].mass_flow;
    });
    return {all[order.front()], all[order[order.size() / 2]], all[order.back()]};
  }

  std::vector<Ladder> ladders(const Station& station, const st::RunSettings& settings) const {
    std::vector<Ladder> out;
    out.push_back(time_step_ladder(settings));
    const double d_data = station.material.particle_diameter;
    const double d1 = settings.particle_diameter > 0 ? settings.particle_diameter : d_data;
    if (d1 > d_data * (1.0 + 1e-9)) {
      const double r = c_.ladder_ratio;
      Ladder size{"particle-size", fmt::format("particle size {:.1f} / {:.1f} / {:.1f} mm towards the dataset's {:.1f} mm",
                                               d1 * 1e3, d1 * r * 1e3, d1 * r * r * 1e3, d_data * 1e3),
                   d1 / d_data - 1.0, {}};
      for (double d : {d1 * r, d1 * r * r}) {
        st::RunSettings c = settings;
        c.particle_diameter = d;
        size.coarser.emplace_back(d / d_data - 1.0, c);
      }
      out.push_back(std::move(size));
    }
    return out;
  }

 private:

  // The time-step part of u_num,disc carried from the subset's ladders to `p`, per value:
  // - where a ladder there saw no difference beyond its noise, its u_disc is noise too: `p`'s own
  //   statistical part times the largest u_disc / u_stat seen;
  // - where one resolved a difference, that is an integration error, which scales with the value
  //   (each condition's dt is the same fraction of its collision time): the largest u_disc / |f|
  //   seen, times `p`'s value.
  // The larger of the two applies. The stream limits, positions along a boundary whose points differ
  // from condition to condition, take the largest mean over a boundary's points of u_disc / u_stat
  // (resolved or not) times each point's own standard error. None when a run of the subset cannot be
  // made.
  std::optional<LadderUncertainty> carried_time_step(const ModelPrediction& p, const std::vector<Station>& from,
                                                     const analytical::EffectList& effects, const st::RunSettings& settings,
                                                     const st::DemTable& table, const PredictRequest& plain) const {
    std::array<double, kQuantityCount> k_stat{}, k_rel{};
    std::array<double, 3> kb{};  // per boundary (upper, lower, centre): the mean of u_disc / u_stat over its points
    auto bi = [](Boundary b) { return b == Boundary::upper ? 0 : b == Boundary::lower ? 1 : 2; };
    auto noise = [](const std::optional<GciEstimate>& e) { return !e || e->kind == GciCase::noise_dominated; };
    const Ladder l = time_step_ladder(settings);
    for (const Station& s : from) {
      const DemEffectInputs fs = dem_effect_inputs(s, effects);
      ModelPrediction fine, coarse;
      try {
        fine = rung_prediction(s, fs, settings, table, plain);
        coarse = rung_prediction(s, fs, l.coarser.front().second, table, plain);
      } catch (const InputError&) {
        if (c_.cache_only) throw;
        return std::nullopt;
      }
      const std::vector<LadderRun> runs = {{l.h_run, &fine}, {l.coarser.front().first, &coarse}};
      const LadderUncertainty u = ladder_uncertainty(runs);
      for (Quantity q : kAllQuantities) {
        const auto i = static_cast<std::size_t>(q);
        const auto &ud = u.u_disc[q], &us = fine.uncertainty[q], &f = fine.values[q];
        if (!ud) continue;
        if (noise(u.estimate[i])) {
          if (us && *us > 0.0) k_stat[i] = std::max(k_stat[i], *ud / *us);
        } else if (f && *f != 0.0) {
          k_rel[i] = std::max(k_rel[i], *ud / std::abs(*f));
        }
      }
      std::array<double, 3> sum{}, n{};
      for (std::size_t j = 0; j < plain.trajectory.size() && j < u.trajectory.size(); ++j) {
        if (!u.trajectory[j]) continue;
        const int b = bi(plain.trajectory[j].boundary);
        if (j >= fine.trajectory_uncertainty.size() || !fine.trajectory_uncertainty[j] ||
            !(*fine.trajectory_uncertainty[j] > 0.0))
          continue;
        sum[b] += *u.trajectory[j] / *fine.trajectory_uncertainty[j];
        n[b] += 1.0;
      }
      for (int b = 0; b < 3; ++b)
        if (n[b] > 0.0) kb[b] = std::max(kb[b], sum[b] / n[b]);
    }
    std::vector<std::string> names;
    for (const Station& s : from) names.push_back(s.condition);
    LadderUncertainty out;
    for (Quantity q : kAllQuantities) {
      const auto i = static_cast<std::size_t>(q);
      const auto &us = p.uncertainty[q], &f = p.values[q];
      const double by_noise = us ? k_stat[i] * *us : 0.0, by_value = f ? k_rel[i] * std::abs(*f) : 0.0;
      if (!(std::max(by_noise, by_value) > 0.0)) continue;
      out.u_disc[q] = std::max(by_noise, by_value);
      out.methods[i].push_back(
          by_value >= by_noise
              ? fmt::format("time step carried from the ladders at {} (dt, 2 dt): {:.3g} of the value, the largest "
                            "resolved difference's GCI there relative to its value",
                            fmt::join(names, ", "), k_rel[i])
              : fmt::format("time step carried from the ladders at {} (dt, 2 dt): {:.3g} x this run's standard error, "
                            "the largest ratio of u_disc to the standard error where the difference was not resolved "
                            "against the noise",
                            fmt::join(names, ", "), k_stat[i]));
    }
    out.trajectory.resize(plain.trajectory.size());
    out.trajectory_estimate.resize(plain.trajectory.size());
    for (std::size_t j = 0; j < plain.trajectory.size(); ++j) {
      const auto b = static_cast<std::size_t>(bi(plain.trajectory[j].boundary));
      if (j < p.trajectory_uncertainty.size() && p.trajectory_uncertainty[j] && kb[b] > 0.0)
        out.trajectory[j] = kb[b] * *p.trajectory_uncertainty[j];
    }
    return out;
  }

  // u_num's discretisation part: what the run's numerical parameters, the ones it chooses rather
  // than takes from the dataset, change (validation/gci.h). Each is a one-factor ladder, and their
  // parts add in quadrature (one-factor estimates of independent choices):
  // - the time step, always: one more run at twice dt (h = dt / dt_run: 1, 2);
  // - the particle size, only when the run coarse-grains the dataset's particles: two more runs
  //   at r d and r^2 d, with h = d / d_data - 1 (the error vanishes at the dataset's own size, not
  //   at d = 0; a run at the dataset's size has no size error to estimate).
  // The contact modulus is not laddered: a run that softens the dataset's modulus (quick) says so
  // in its notes, and the report lists the part as not estimated.
  void add_ladder(ModelPrediction& p, const Station& station, const analytical::EffectList& effects,
                  const DemEffectInputs& fx,
                  const st::RunSettings& settings, const st::DemTable& table,
                  const PredictRequest& request) const {
    PredictRequest plain = request;
    plain.curves = false;
    auto level = [&](const st::RunSettings& s, const char* what) -> std::optional<ModelPrediction> {
      try {
        return rung_prediction(station, fx, s, table, plain);
      } catch (const InputError& e) {
        if (c_.cache_only) throw;
        p.notes.push_back(fmt::format("no {} part of u_num,disc: its ladder run cannot be made ({})", what, e.what()));
        return std::nullopt;
      }
    };
    std::vector<LadderUncertainty> parts;
    std::vector<std::string> labels;
    const std::vector<Station> carried_from = ladder_subset();
    for (const Ladder& l : ladders(station, settings)) {
      if (l.what == "time-step" && !carried_from.empty())
        if (auto u = carried_time_step(p, carried_from, effects, settings, table, plain)) {
          parts.push_back(std::move(*u));
          std::vector<std::string> names;
          for (const Station& s : carried_from) names.push_back(s.condition);
          labels.push_back(fmt::format("time step dt, 2 dt at {}, carried", fmt::join(names, ", ")));
          continue;
        }
      std::vector<ModelPrediction> coarse;
      for (const auto& rung : l.coarser) {
        auto lv = level(rung.second, l.what.c_str());
        if (!lv) break;
        coarse.push_back(std::move(*lv));
      }
      if (coarse.size() != l.coarser.size()) continue;
      std::vector<LadderRun> runs = {{l.h_run, &p}};
      for (std::size_t k = 0; k < coarse.size(); ++k) runs.push_back({l.coarser[k].first, &coarse[k]});
      parts.push_back(ladder_uncertainty(runs));
      labels.push_back(l.label);
    }
    if (parts.empty()) return;
    apply_discretisation(p, combine_ladders(parts));
    p.notes.push_back(fmt::format("u_num discretisation from the ladders: {}", fmt::join(labels, "; ")));
    if (settings.shear_modulus_scale < 1.0)
      p.notes.push_back(fmt::format("u_num discretisation: the softened contact modulus (x{:g}) is not in it",
                                    settings.shear_modulus_scale));
  }


 private:
  // A ladder run's prediction.
  ModelPrediction rung_prediction(const Station& s, const DemEffectInputs& fx, const st::RunSettings& settings,
                                  const st::DemTable& table, const PredictRequest& plain) const {
    CacheOutcome how;
    return to_prediction(run_or_load(s, fx, settings, table, how), fx, plain, how);
  }

  static ModelPrediction to_prediction(const st::StationResult& r, const DemEffectInputs& fx,
                                       const PredictRequest& request, const CacheOutcome& how) {
    ModelPrediction p = dem_station_prediction(r, fx, request);
    if (!how.refused.empty()) p.notes.push_back(fmt::format("DEM cache entry refused and run again: {}", how.refused));
    if (how.from_cache)
      p.notes.push_back(fmt::format("from the DEM cache ({})", how.file));
    else if (how.unwritten.empty())
      p.notes.push_back(fmt::format("DEM run of {:.0f} s wall time, cached as {}", r.wall_seconds, how.file));
    else
      p.notes.push_back(fmt::format("DEM run of {:.0f} s wall time, not cached ({})", r.wall_seconds, how.unwritten));
    return p;
  }

 private:
  DemModelConfig c_;
};

}  // namespace

ModelPrediction dem_station_prediction(const st::StationResult& r, const DemEffectInputs& fx,
                                       const PredictRequest& request) {
  ModelPrediction p;
  auto set = [&](Quantity q, const st::Estimate& e) {
    if (!e.ok()) return;
    p.values[q] = e.value;
    if (std::isfinite(e.se)) p.uncertainty[q] = e.se;
  };
  set(Quantity::normal_force, r.normal_force);
  set(Quantity::shear_force, r.shear_force);
  set(Quantity::resultant_force, r.resultant_force);
  set(Quantity::impact_velocity, r.impact_velocity);
  set(Quantity::exit_velocity, r.exit_velocity);
  set(Quantity::impact_point_y, r.impact_point_y);
  set(Quantity::belt_layer_velocity, r.layer_speed);
  set(Quantity::stream_mass_flow, r.mass_flux);
  p.trajectory.reserve(request.trajectory.size());
  for (const auto& q : request.trajectory) {
    p.trajectory.push_back(trajectory_at(r.trajectory, q.boundary, q.x));
    // The stream limit's standard error (snapshot to snapshot), u_num's statistical part.
    const auto e = trajectory_estimate(r.trajectory, q.boundary, q.x);
    p.trajectory_uncertainty.push_back(e && std::isfinite(e->se) ? std::optional<double>(e->se) : std::nullopt);
  }
  if (request.curves) {
    for (Boundary b : {Boundary::upper, Boundary::centre, Boundary::lower}) {
      Curve c{b == Boundary::upper ? "upper" : b == Boundary::lower ? "lower" : "centre (mean)", {}};
      for (const auto& row : r.trajectory) {
        const st::Estimate& e = b == Boundary::upper ? row.upper : b == Boundary::lower ? row.lower : row.centre;
        if (e.ok()) c.points.emplace_back(row.x, e.value);
      }
      if (!c.points.empty()) p.curves.push_back(std::move(c));
    }
    // Side view of the steady stream (reference study Fig. 9): particle centres coloured by speed.
    Curve pts{"particles", {}, Curve::Kind::points, {}, "speed (m/s)"};
    for (const auto& s : r.side_view) {
      pts.points.emplace_back(s.x, s.y);
      pts.value.push_back(s.speed);
    }
    if (!pts.points.empty()) p.curves.push_back(std::move(pts));
  }
  // Pressure and wear maps: for the report's pictures, and at the plate points a dataset measured.
  for (const auto& m : r.maps) {
    SurfaceMap sm;
    sm.name = m.wall;
    for (const auto& c : m.cells) {
      sm.cells.push_back({Eigen::Vector2d(c.corners[0].z(), c.corners[0].y()),
                          Eigen::Vector2d(c.corners[1].z(), c.corners[1].y()),
                          Eigen::Vector2d(c.corners[2].z(), c.corners[2].y())});
      sm.pressure.push_back(c.pressure());
      sm.wear_rate.push_back(c.archard_rate(r.wear) + c.finnie_rate(r.wear));
    }
    sm.peak_pressure_y = st::peak_pressure_y(m);
    sm.pressure_centre_y = st::pressure_centre_y(m);
    p.maps.push_back(std::move(sm));
  }
  for (const auto& q : request.plate) {
    const auto [v, u] = plate_value(r, q);
    p.plate.push_back(v);
    p.plate_uncertainty.push_back(u);
  }
  p.notes = r.notes;
  for (auto& d : st::window_drifts(r)) {
    p.notes.push_back(std::move(d.note));
    p.unsteady.push_back(std::move(d.load));
  }
  if (r.impact_velocity_fast.ok())
    p.notes.push_back(fmt::format("free-stream particles alone (v_x > V_b/2) arrive at {:.3f} m/s; the V_p slab lies "
                                  "partly in the layer on the plate", r.impact_velocity_fast.value));
  for (const auto& n : fx.notes) p.notes.push_back(n);
  return p;
}

const st::DemTable& DemModelConfig::dem_table() const {
  std::call_once(table_once->read, [this] {
    if (!setup_file.empty()) table_once->table = st::read_dem_table(setup_file, setup_text ? &*setup_text : nullptr);
  });
  return table_once->table;
}

ModelPtr make_dem_model(const DemModelConfig& c) { return std::make_shared<DemModel>(c); }

std::string dem_cache_key(const DemEffectInputs& fx, const dem::station::RunSettings& settings,
                          const dem::station::DemTable& table) {
  std::string key = std::string(st::kStationModelVersion) + "\n";
  key += canonical_station(fx.station);
  key += st::canonical(settings);
  for (const auto* f : {&table.stl_plate, &table.stl_belt, &table.stl_pulley})
    if (*f) key += "stl " + file_key(**f) + "\n";
  for (const auto& f : table.stl_walls) key += "stl-wall " + file_key(f) + "\n";
  key += fx.key;
  return key;
}

std::optional<dem::station::ChangeAt> restart_change(const DemEffectInputs& base, const DemEffectInputs& fx) {
  Station same_flow = base.station;
  same_flow.mass_flow = fx.station.mass_flow;
  if (canonical_station(same_flow) != canonical_station(fx.station)) return std::nullopt;
  if (fx.station.mass_flow != base.station.mass_flow ||
      fx.external.belt_adhesive_stress != base.external.belt_adhesive_stress)
    return st::ChangeAt::feed;
  if (fx.external.flight_key != base.external.flight_key) return st::ChangeAt::flight;
  if (fx.external.plate_friction != base.external.plate_friction) return st::ChangeAt::plate;
  return std::nullopt;
}

std::string canonical_station(const Station& s) {
  std::string o;
  auto put = [&](const char* k, double v) { o += fmt::format("{} = {}\n", k, num(v)); };
  // The condition's name is a label, not an input: equal rigs share a cached run.
  put("pulley_diameter", s.belt.pulley_diameter);
  put("belt_thickness", s.belt.belt_thickness);
  put("belt_width", s.belt.belt_width);
  put("loaded_width", s.belt.loaded_width);
  put("belt_incline", s.belt.incline);
  put("trough_idler_angle", s.belt.trough.idler_angle);
  put("trough_centre_roll", s.belt.trough.centre_roll);
  put("trough_surcharge_angle", s.belt.trough.surcharge_angle);
  put("plate_width", s.plate.width);
  put("plate_height", s.plate.height);
  put("plate_angle", s.plate.angle);
  const auto& m = s.material;
  put("particle_diameter", m.particle_diameter);
  put("solid_density", m.solid_density);
  // The bulk density is a measurement of the layer the DEM forms, not one of its inputs (it feeds
  // the mass flow by particles of the solid density): left out, like the stream thickness.
  put("youngs_modulus", m.youngs_modulus);
  put("poisson_ratio", m.poisson_ratio);
  put("friction_particle", m.friction_particle);
  put("friction_plate", m.friction_plate);
  put("friction_belt", m.friction_belt);
  put("rolling_friction_particle", m.rolling_friction_particle);
  put("rolling_friction_wall", m.rolling_friction_wall);
  put("restitution_particle", m.restitution_particle);
  put("restitution_plate", m.restitution_plate);
  put("restitution_belt", m.restitution_belt);
  put("friction_side", m.friction_side);
  put("gravity", s.gravity);
  put("belt_speed", s.belt_speed);
  put("mass_flow", s.mass_flow);
  put("plate_distance", s.plate_distance);
  put("plate_top", s.plate_top);
  // stream_thickness is a measurement of the layer, not an input of the DEM: left out.
  return o;
}

DemEffectInputs dem_effect_inputs(const Station& recorded, const analytical::EffectList& effects) {
  DemEffectInputs out;
  // A wrong number in the record: the DEM runs the rig as it really was.
  out.station = analytical::as_really_was(recorded, effects);
  const Station station = out.station;  // as really built, before the operating effects
  double friction = station.material.friction_plate;
  bool friction_changed = false;
  double adhesive_stress = 0.0;
  std::vector<std::shared_ptr<const analytical::Effect>> flight;
  for (const auto& e : effects) {
    const std::string n = e->name();
    std::vector<std::string> honoured, ignored;
    // Operating point: belt speed and mass flow as the physics sees them.
    analytical::OperatingPoint op{out.station.belt_speed, out.station.mass_flow};
    e->adjust_operating_point(op);
    if (op.belt_speed != out.station.belt_speed || op.mass_flow != out.station.mass_flow) {
      honoured.push_back(fmt::format("feed {:.4g} kg/s, belt {:.4g} m/s", op.mass_flow, op.belt_speed));
      out.station.belt_speed = op.belt_speed;
      out.station.mass_flow = op.mass_flow;
    }
    // Plate: the particle-plate friction is the DEM's. The stream restitution is not an input: the
    // DEM's rebound comes from its contacts, and no plate restitution reaches a chosen e_s
    // (effects/plate_rebound.cpp gives the measured range).
    analytical::PlateInteraction pi{friction, 0.0};
    e->adjust_plate(pi);
    if (pi.friction != friction) {
      honoured.push_back(fmt::format("particle-plate friction {:.4g}", pi.friction));
      friction = pi.friction;
      friction_changed = true;
    }
    if (pi.rebound != 0.0)
      ignored.push_back("the DEM resolves the stream's rebound from its particle-plate and particle-particle "
                        "restitution, and its R_n already contains it; no DEM input sets a stream restitution");
    // Flight.
    if (e->has_flight_force()) {
      flight.push_back(e);
      honoured.push_back("body force on particles in flight");
    }
    // Discharge. A holding acceleration inversely proportional to the layer's mass per belt area is
    // an adhesive stress at the belt, sigma_a = a_h m'' (probed at two m''): the DEM holds the layer
    // with particle-belt cohesion. Any other change is an analytical construction of the discharge
    // (slip, a changed radius or gravity) with no DEM input: the DEM's discharge follows from belt
    // friction and contact forces.
    auto probe = [&](double layer_mass_per_area) {
      analytical::DischargeInput di{station.belt.belt_radius(), station.belt_speed, station.belt.incline,
                                    station.gravity, 0.0, layer_mass_per_area};
      e->adjust_discharge(di, station);
      return di;
    };
    const analytical::DischargeInput d1 = probe(1.0), d2 = probe(2.0);
    const bool geometry_changed = d1.radius != station.belt.belt_radius() || d1.incline != station.belt.incline ||
                                  d1.gravity != station.gravity;
    // A slower discharge (belt slip): the DEM's belt and pulley carry the layer at the discharge
    // speed, so the material reaches the pulley and leaves it at (1 - s) V_b, and the layer is as
    // much thicker as continuity asks.
    if (d1.speed != station.belt_speed && !geometry_changed && d1.speed > 0.0 &&
        std::abs(d2.speed - d1.speed) <= 1e-12 * d1.speed) {
      const double ratio = d1.speed / station.belt_speed;
      out.station.belt_speed *= ratio;
      honoured.push_back(fmt::format("the layer is carried and discharged at {:.4g} m/s ({:.4g} x the belt speed)",
                                     out.station.belt_speed, ratio));
    }
    const double stress = d1.holding_accel * 1.0;
    const bool is_stress = std::abs(d2.holding_accel * 2.0 - stress) <= 1e-12 * std::abs(stress);
    if (d1.holding_accel != 0.0 && is_stress) {
      adhesive_stress += stress;
      honoured.push_back(fmt::format("adhesive stress {:.4g} Pa as particle-belt and particle-pulley cohesion "
                                     "(simplified JKR, dem/station/belt_cohesion.h)", stress));
    }
    if (geometry_changed || (d1.holding_accel != 0.0 && !is_stress) ||
        (d1.speed != station.belt_speed && std::abs(d2.speed - d1.speed) > 1e-12 * std::abs(d1.speed)))
      ignored.push_back("it changes the analytical discharge from the pulley; in the DEM the discharge follows "
                        "from belt friction and contact forces");
    for (Boundary b : {Boundary::upper, Boundary::lower}) {
      Eigen::Vector2d v(1.0, 0.0);
      e->adjust_release(b, v);
      if (v != Eigen::Vector2d(1.0, 0.0)) {
        ignored.push_back("it turns the analytical release velocity; the DEM stream spreads by itself");
        break;
      }
    }
    if (!honoured.empty()) out.notes.push_back(fmt::format("effect {} honoured by the DEM: {}", n, fmt::join(honoured, "; ")));
    if (!ignored.empty()) out.notes.push_back(fmt::format("effect {} ignored by the DEM: {}", n, fmt::join(ignored, "; ")));
  }
  if (friction_changed) out.external.plate_friction = friction;
  out.external.belt_adhesive_stress = std::max(0.0, adhesive_stress);
  if (!flight.empty()) {
    const analytical::FlightContext ctx{station.material.particle_diameter, station.material.solid_density};
    out.external.flight = [flight, ctx](const Eigen::Vector2d& v) {
      Eigen::Vector2d a = Eigen::Vector2d::Zero();
      for (const auto& e : flight) a += e->flight_acceleration(v, ctx);
      return a;
    };
    // The key samples the acceleration: equal samples, equal physics for the effects we have.
    std::string k = "flight";
    for (const Eigen::Vector2d& v : {Eigen::Vector2d(1, 0), Eigen::Vector2d(3, -1), Eigen::Vector2d(5, -3),
                                    Eigen::Vector2d(0, -2), Eigen::Vector2d(-1, 0.5)}) {
      const Eigen::Vector2d a = out.external.flight(v);
      k += fmt::format(" {} {}", num(a.x()), num(a.y()));
    }
    out.external.flight_key = k;
  }
  out.key = fmt::format("effective_belt_speed = {}\neffective_mass_flow = {}\n", num(out.station.belt_speed),
                        num(out.station.mass_flow));
  out.key += st::canonical(out.external);
  return out;
}

}  // namespace chutelab::validation
