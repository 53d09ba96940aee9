#include "dem/station/run.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <memory>
#include <optional>

#include <unistd.h>

#include <fmt/format.h>

#include "core/input_error.h"
#include "core/interrupt.h"
#include "dem/io/vtk.h"
#include "dem/io/vtk_series.h"

namespace chutelab::dem::station {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

double now() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

// Mean and snapshot-to-snapshot standard error of the finite values with t in (start, end].
Estimate snapshot_mean(const std::vector<double>& t, const std::vector<double>& v, double start, double end) {
  Estimate e;
  double sum = 0.0, sum2 = 0.0;
  for (std::size_t k = 0; k < t.size(); ++k) {
    if (t[k] <= start || t[k] > end + 1e-12 || !std::isfinite(v[k])) continue;
    sum += v[k];
    sum2 += v[k] * v[k];
    ++e.n;
  }
  if (e.n == 0) return e;
  e.value = sum / e.n;
  if (e.n >= 2) {
    const double var = std::max(0.0, (sum2 - e.n * e.value * e.value) / (e.n - 1));
    e.se = std::sqrt(var / e.n);
  }
  return e;
}

std::ofstream open_out(const std::filesystem::path& p) {
  std::ofstream f(p);
  if (!f) throw InputError(p.string(), 0, "out", "cannot write this file");
  return f;
}

// How a run is cut: steps per sample (the plate load's averaging), samples per snapshot (the
// sensors), and the most steps max_time allows.
struct Schedule {
  long long steps_per_sample = 1;
  double sample_dt = 0.0;  // s
  long long samples_per_snapshot = 1;
  long long max_steps = 0;

  // `duration`: the most simulated time this run may take (from empty: max_time).
  static Schedule of(const RunSettings& s, double dt, double duration) {
    Schedule c;
    c.steps_per_sample = std::max<long long>(1, std::llround(s.sample_interval / dt));
    c.sample_dt = static_cast<double>(c.steps_per_sample) * dt;
    c.samples_per_snapshot = std::max<long long>(1, std::llround(s.snapshot_interval / c.sample_dt));
    c.max_steps = static_cast<long long>(std::ceil(duration / dt - 1e-9));
    return c;
  }
};

// The part of a series after t_cut (a restart's transit): the steady state is looked for there only.
// From empty that is the series itself, not a copy (it is asked at every check, and the face
// particles it holds are never read there); after a restart, the load cell's channels copied into
// `out`.
const StationSeries& after(const StationSeries& series, double t_cut, StationSeries& out) {
  if (t_cut <= 0.0) return series;
  out = StationSeries{};
  out.sample_dt = series.sample_dt;
  for (std::size_t k = 0; k < series.t.size(); ++k) {
    if (series.t[k] <= t_cut + 1e-12) continue;
    out.t.push_back(series.t[k]);
    out.normal.push_back(series.normal[k]);
    out.shear.push_back(series.shear[k]);
    out.moment.push_back(series.moment[k]);
  }
  return out;
}

// Whether a channel the window is judged on still drifts through it (the early stop waits then).
bool load_cell_drifting(const StationSeries& x, const RunSettings& s, const SteadyWindow& w) {
  if (drifting(x.t, x.normal, w.start, w.end, s.mean_block)) return true;
  if (!s.steady_all_loads) return false;
  return drifting(x.t, x.shear, w.start, w.end, s.mean_block) || drifting(x.t, x.moment, w.start, w.end, s.mean_block);
}

// What the result says of the run before it starts: the condition, the particles and the time step.
StationResult describe_run(const Station& st, const RunSettings& s, const Scene& sc) {
  StationResult r;
  r.condition = st.condition;
  r.quality = std::string(name(s.quality));
  r.diameter = sc.diameter;
  r.shape = std::string(name(sc.shape));
  r.dt = sc.dt;
  r.collision_time = sc.collision_time;
  r.rayleigh_time = sc.rayleigh_time;
  r.notes = sc.notes;
  return r;
}

// Maps of the plate and the [dem.stl] walls, from every contact of every step (plate_map.h).
std::vector<std::unique_ptr<PlateMapRecorder>> record_maps(const RunOptions& o, const Schedule& schedule, Scene& sc) {
  const RunSettings& s = o.settings;
  World& w = *sc.world;
  std::vector<int> mapped = {sc.plate_wall};
  mapped.insert(mapped.end(), sc.map_walls.begin(), sc.map_walls.end());
  const auto max_samples = static_cast<std::size_t>(schedule.max_steps / schedule.steps_per_sample + 2);
  // The generated plate, not meshed for the maps, gets the map grid (plate_map.h MapGrid).
  std::optional<MapGrid> grid;
  if (!o.geometry.stl_plate && s.plate_cells == 0 && s.map_cell > 0.0)
    grid = MapGrid::on_face(sc.plate.top_edge, sc.plate.down, sc.plate.height, sc.plate.width, s.map_cell);
  std::vector<std::unique_ptr<PlateMapRecorder>> maps;
  for (int wi : mapped) {
    auto rec = std::make_unique<PlateMapRecorder>(w.walls()[static_cast<std::size_t>(wi)], s.wear.finnie, max_samples,
                                                  wi == sc.plate_wall && grid ? &*grid : nullptr);
    w.observe_wall(wi, [p = rec.get()](const WallContact& c) { p->observe(c); });
    maps.push_back(std::move(rec));
  }
  return maps;
}

// The particles as a ParaView time series (dem/io/vtk_series.h), with each particle's contact
// force: its force less its weight and the flight force (air drag) the run adds.
class ParticleFrames {
 public:
  ParticleFrames(const RunOptions& o, const Scene& sc) : sc_(sc), every_(o.vtk_every) {
    if (o.vtk_dir.empty()) return;
    std::filesystem::create_directories(o.vtk_dir);
    write_vtk_walls((std::filesystem::path(o.vtk_dir) / "walls.vtk").string(), sc.world->walls());
    series_.emplace(o.vtk_dir, "particles");
    if (o.vtk_every > 0.0) next_ = 0.0;
  }
  // After a sample ending at t: a frame, when one is due.
  void after_sample(double t) {
    if (t + 1e-12 < next_) return;
    write();
    next_ += every_;
  }
  // The series ends on the final state (the side view's instant).
  void finish() {
    if (series_ && series_->last_time() < sc_.world->time() - 1e-12) write();
  }

 private:
  void write() {
    const World& w = *sc_.world;
    const Particles& p = w.particles();
    std::vector<Vec3> flight(p.size(), Vec3::Zero());
    sc_.flight.add(p, 0, p.size(), flight);
    const Vec3 g = w.settings().gravity;
    std::vector<double> contact(p.size());
    for (std::size_t i = 0; i < p.size(); ++i) contact[i] = (p.f[i] - p.mass[i] * g - flight[i]).norm();
    series_->write(w.time(), p, contact);
  }

  const Scene& sc_;
  double every_;
  double next_ = std::numeric_limits<double>::infinity();
  std::optional<VtkSeries> series_;
};

// What the time loop leaves besides the result's samples and snapshots.
struct Marched {
  StationSeries series;
  std::size_t peak_bodies = 0;  // clumps (peak_particles counts their spheres)
};

// The time loop, a sample at a time: the plate's load averaged over the sample's steps, the maps'
// samples, the plane crossings, the snapshot sensors, frames and progress; until max_time, or until the plate's
// normal load has been steady long enough (steady_state.h).
Marched march(const RunOptions& o, const Schedule& schedule, Scene& sc, Sensors& sensors,
              const std::vector<std::unique_ptr<PlateMapRecorder>>& maps, ParticleFrames& frames, double t_start,
              StationResult& r) {
  const RunSettings& s = o.settings;
  World& w = *sc.world;
  Marched m;
  StationSeries& series = m.series;
  series.sample_dt = schedule.sample_dt;
  const bool restarted = r.restart_time >= 0.0;
  const double t0 = w.time();
  const long long first_step = w.step_count();
  const double budget = static_cast<double>(schedule.max_steps) * sc.dt;
  double next_check = restarted ? r.transient_end + s.min_window : std::max(s.min_time, s.detect_tail + s.min_window);
  double next_progress = 0.0;
  const double progress_step = 0.01 * budget;
  long long sample_index = 0;

  // The plate's load is averaged over every step of a sample, read as each step's loads are final:
  // the sample's steps then run as one call, which lets the integrator fuse its passes.
  Vec3 force = Vec3::Zero();
  double moment = 0.0;
  w.observe_wall_loads([&] {
    const Wall& plate = w.walls()[static_cast<std::size_t>(sc.plate_wall)];
    force += plate.force;
    moment += plate.torque.z();
  });
  const int base_threads = w.threads();
  while (w.step_count() - first_step < schedule.max_steps) {
    interrupt::point();  // a caller that asked to stop (Python's Ctrl-C) is heard between samples
    force = Vec3::Zero();
    moment = 0.0;
    if (s.extra_threads) w.set_threads(base_threads + s.extra_threads->load(std::memory_order_relaxed));
    w.step(schedule.steps_per_sample);
    sc.discharge();
    force /= static_cast<double>(schedule.steps_per_sample);
    moment /= static_cast<double>(schedule.steps_per_sample);
    const double t = w.time();
    for (auto& m : maps) m->end_sample(t);
    series.t.push_back(t);
    series.normal.push_back(force.dot(sc.plate.into));
    series.shear.push_back(force.dot(sc.plate.down));
    series.moment.push_back(moment);
    ForceSample sample{t, series.normal.back(), series.shear.back(), series.moment.back()};
    sensors.count_crossings(w, sample);
    r.forces.push_back(sample);
    ++sample_index;
    if (sample_index % schedule.samples_per_snapshot == 0) {
      r.snapshots.push_back(sensors.measure(w, series.face));
      r.peak_particles = std::max(r.peak_particles, w.particles().size());
      m.peak_bodies = std::max(m.peak_bodies, w.clumps().size());
    }
    frames.after_sample(t);
    if (o.progress && t - t0 >= next_progress) {
      o.progress({t - t0, budget, now() - t_start, w.particles().size(), false});
      next_progress += progress_step;
    }
    if (t + 1e-12 >= next_check) {
      next_check += s.detect_block;
      StationSeries part;
      const StationSeries& settled = after(series, r.transient_end, part);
      const SteadyWindow win = load_cell_window(settled, s);
      if (win.found && win.end - win.start >= s.min_window - 1e-9 && !load_cell_drifting(settled, s, win)) {
        r.early_stop = true;
        break;
      }
    }
  }
  w.observe_wall_loads(nullptr);  // it refers to this function's locals
  return m;
}

// Where the fed mass went: discharged below the plate, escaped through the domain's faces, or
// still in the domain.
void account_mass(const Scene& sc, StationResult& r) {
  const World& w = *sc.world;
  r.inserted = w.inserters()[static_cast<std::size_t>(sc.inserter)].inserted_mass;
  r.discharged = sc.discharged + w.sinks()[static_cast<std::size_t>(sc.plate_sink)].removed_mass;
  for (int k : sc.boundary_sinks) r.escaped += w.sinks()[static_cast<std::size_t>(k)].removed_mass;
  for (double m : w.particles().mass) r.in_domain += m;
}

// The run's summary line, escaped mass and the World's warnings as notes.
void note_run(const Scene& sc, const RunSettings& s, std::size_t peak_bodies, StationResult& r) {
  r.notes.push_back(fmt::format(
      "DEM {}: {}, dt {:.3g} s ({:.2f} of the collision time {:.3g} s, {:.2f} of the Rayleigh time), "
      "{:.2f} s simulated{}, steady window {:.2f}-{:.2f} s ({} blocks of {:.1f} s)",
      r.quality,
      sc.shape == ParticleShape::clump
          ? fmt::format("two-sphere clumps (reference study Fig. 4c) of {:.1f} mm spheres, {} bodies at the peak", r.diameter * 1e3,
                        peak_bodies)
          : fmt::format("{:.1f} mm spheres", r.diameter * 1e3),
      r.dt, r.dt / r.collision_time, r.collision_time, r.dt / r.rayleigh_time,
      r.simulated_time, r.early_stop ? " (stopped when steady)" : "", r.window.start, r.window.end, r.window.blocks,
      s.mean_block));
  if (r.escaped > 0.0)
    r.notes.push_back(fmt::format("{:.3g} kg left the rig through the domain's faces (not the discharge)", r.escaped));
  for (const auto& m : *sc.warnings) r.notes.push_back("DEM warning: " + m);
}

// The averaging window of the steady means: the detected steady window (steady_state.h), or, when
// none long enough was found before the time limit, the run's last min_window (with a note).
void find_window(const StationSeries& series, const RunSettings& s, StationResult& r) {
  StationSeries part;
  const StationSeries& settled = after(series, r.transient_end, part);
  r.window = load_cell_window(settled, s);
  // A window is judged against the mean of the last detect_tail and must be min_window long: a run
  // cut before both fit after its transient (a short --max-time) compares a plate still filling
  // with itself, and a window found there is no steady state.
  const double judged_from = (r.restart_time >= 0.0 ? r.transient_end : 0.0) + s.detect_tail + s.min_window;
  const bool cut_short = r.simulated_time + 1e-9 < judged_from;
  if (cut_short) r.window.found = false;
  if (r.window.found && r.window.end - r.window.start >= s.min_window - 1e-9) return;
  const bool none = !r.window.found;
  const int n = std::max(1, static_cast<int>(std::floor(s.min_window / s.mean_block + 1e-9)));
  r.window.end = r.simulated_time;
  r.window.start = std::max(std::max(0.0, r.restart_time), r.window.end - n * s.mean_block);
  r.window.blocks = static_cast<int>(std::floor((r.window.end - r.window.start) / s.mean_block + 1e-9));
  r.notes.push_back(cut_short ? fmt::format("the run ended at {:.2f} s, before the plate's load could be judged steady "
                                            "(that needs {:.2f} s): means over the last {:.1f} s of a plate that may "
                                            "still be filling, uncertain",
                                            r.simulated_time, judged_from, r.window.end - r.window.start)
                    : none    ? fmt::format("no steady state detected within {:.2f} s: means over the last {:.1f} s, "
                                            "uncertain", r.simulated_time, r.window.end - r.window.start)
                              : fmt::format("steady window shorter than {:.1f} s at the time limit: means over the "
                                            "last {:.1f} s", s.min_window, r.window.end - r.window.start));
}

// The steady window's bounds and the length of its blocks, s.
struct Window {
  double a, b, block;
};

// The plate's load cell: normal and shear force, their resultant, and the impact point from the
// moment about the reference.
void reduce_plate_load(const Scene& sc, const StationSeries& series, const Window& win, StationResult& r) {
  const auto [a, b, blk] = win;
  const std::vector<double>& ts = series.t;
  const std::vector<double> ones(ts.size(), 1.0);
  r.normal_force = block_mean(ts, series.normal, ones, a, b, blk);
  r.shear_force = block_mean(ts, series.shear, ones, a, b, blk);
  if (r.normal_force.ok() && r.shear_force.ok()) {
    const double R = std::hypot(r.normal_force.value, r.shear_force.value);
    r.resultant_force.value = R;
    r.resultant_force.n = r.normal_force.n;
    if (R > 0.0)
      r.resultant_force.se = std::hypot(r.normal_force.value * r.normal_force.se, r.shear_force.value * r.shear_force.se) / R;
  }
  std::vector<double> minus_m(series.moment.size());
  for (std::size_t k = 0; k < series.moment.size(); ++k) minus_m[k] = -series.moment[k];
  const Estimate up = block_ratio(ts, minus_m, series.normal, a, b, blk);  // along the face above the reference
  r.impact_point_y = up;
  if (up.ok()) {
    r.impact_point_y.value = sc.plate.y_at(up.value);
    r.impact_point_y.se = up.se * std::cos(sc.plate.angle);
  }
}

std::vector<double> snapshot_times(const StationResult& r) {
  std::vector<double> tn;
  for (const auto& sn : r.snapshots) tn.push_back(sn.t);
  return tn;
}

// The snapshot sensors' means: impact velocity, the layer's speed and height at the pulley, the
// stream's thickness.
void reduce_snapshots(const Window& win, StationResult& r) {
  const auto [a, b, blk] = win;
  std::vector<double> vp, vpw, vpf, vpfw, ls, lh, lsw, th;
  for (const auto& sn : r.snapshots) {
    vp.push_back(sn.vp_n ? sn.vp_sum / sn.vp_n : kNaN);
    vpw.push_back(sn.vp_n);
    vpf.push_back(sn.vp_fast_n ? sn.vp_fast_sum / sn.vp_fast_n : kNaN);
    vpfw.push_back(sn.vp_fast_n);
    ls.push_back(sn.layer_n ? sn.layer_speed_sum / sn.layer_n : kNaN);
    lh.push_back(sn.layer_n ? sn.layer_height_sum / sn.layer_n : kNaN);
    lsw.push_back(sn.layer_n);
    th.push_back(sn.stream_thickness);
  }
  const std::vector<double> tn = snapshot_times(r);
  const std::vector<double> snap_ones(tn.size(), 1.0);
  r.impact_velocity = block_mean(tn, vp, vpw, a, b, blk);
  r.impact_velocity_fast = block_mean(tn, vpf, vpfw, a, b, blk);
  r.layer_speed = block_mean(tn, ls, lsw, a, b, blk);
  r.layer_height = block_mean(tn, lh, lsw, a, b, blk);
  r.stream_thickness = block_mean(tn, th, snap_ones, a, b, blk);
}

// Plane crossings: the free stream's mass flux and the plate's momentum balance, block by block.
void reduce_plane_crossings(const StationSeries& series, const Window& win, StationResult& r) {
  const auto [a, b, blk] = win;
  std::vector<double> mass_rate, mom_rate;
  for (std::size_t k = 0; k < r.forces.size(); ++k) {
    const ForceSample& f = r.forces[k];
    mass_rate.push_back(f.mass_through / series.sample_dt);
    // Rate of change of the content between samples enters as its difference.
    const double dp = k > 0 ? f.momentum_content - r.forces[k - 1].momentum_content : 0.0;
    mom_rate.push_back((f.momentum_in - f.momentum_floor - dp) / series.sample_dt);
  }
  const std::vector<double> ones(series.t.size(), 1.0);
  r.mass_flux = block_mean(series.t, mass_rate, ones, a, b, blk);
  r.momentum_balance = block_mean(series.t, mom_rate, ones, a, b, blk);
}

// V_a: down the face, 30-150 mm below the impact point, once that is known.
void reduce_exit_velocity(const Scene& sc, const std::vector<FaceParticle>& face, const Window& win, StationResult& r) {
  if (!r.impact_point_y.ok()) return;
  const auto [a, b, blk] = win;
  const double a_imp = (r.impact_point_y.value - sc.plate.reference.y()) / std::cos(sc.plate.angle);
  std::vector<double> tv, vv, wv;
  std::size_t k = 0;
  for (const auto& sn : r.snapshots) {
    double sum = 0.0;
    int n = 0;
    const auto t = static_cast<float>(sn.t);
    for (; k < face.size() && face[k].t <= t; ++k) {
      const FaceParticle& fp = face[k];
      if (fp.t != t) continue;
      if (fp.v_into <= -0.5f || fp.v_into >= 0.3f) continue;
      const double below = a_imp - fp.up;
      if (below < 0.030 || below > 0.150) continue;
      sum += fp.v_down;
      ++n;
    }
    tv.push_back(sn.t);
    vv.push_back(n ? sum / n : kNaN);
    wv.push_back(n);
  }
  r.exit_velocity = block_mean(tv, vv, wv, a, b, blk);
}

// The stream's upper and lower limits and centre line at the sensors' stations, where the stream
// is there in most of the window's snapshots.
void reduce_stream_limits(const Sensors& sensors, const Window& win, StationResult& r) {
  const auto [a, b, blk] = win;
  const std::vector<double> tn = snapshot_times(r);
  const auto& xq = sensors.stations();
  std::size_t in_window = 0;
  for (double t : tn) in_window += (t > a && t <= b + 1e-12);
  for (std::size_t q = 0; q < xq.size(); ++q) {
    std::vector<double> up, lo, ce;
    for (const auto& sn : r.snapshots) {
      up.push_back(sn.upper[q]);
      lo.push_back(sn.lower[q]);
      ce.push_back(sn.centre[q]);
    }
    TrajectoryRow row;
    row.x = xq[q];
    row.upper = snapshot_mean(tn, up, a, b);
    row.lower = snapshot_mean(tn, lo, a, b);
    row.centre = snapshot_mean(tn, ce, a, b);
    // A limit needs the stream in most snapshots, not in a few.
    if (2 * static_cast<std::size_t>(row.centre.n) < in_window) continue;
    r.trajectory.push_back(row);
  }
}

// A layer that does not reach the pulley at belt speed, or a free stream that does not carry the
// feed, says the scene is not what the condition describes.
void note_feed_mismatch(const Scene& sc, StationResult& r) {
  if (r.layer_speed.ok() && std::abs(r.layer_speed.value / sc.belt_speed - 1.0) > 0.02)
    r.notes.push_back(fmt::format("the layer reaches the pulley at {:.3f} m/s, not at belt speed {:.3f} m/s",
                                  r.layer_speed.value, sc.belt_speed));
  if (r.mass_flux.ok() && std::abs(r.mass_flux.value / sc.mass_flow - 1.0) > 0.05)
    r.notes.push_back(fmt::format("free-stream mass flux {:.3f} kg/s differs from the feed {:.3f} kg/s",
                                  r.mass_flux.value, sc.mass_flow));
}

}  // namespace

// All windows end at the series' end, so the latest start is the shortest window.
SteadyWindow load_cell_window(const StationSeries& x, const RunSettings& s) {
  const SteadyParams sp{s.detect_block, s.detect_tail, s.mean_block};
  SteadyWindow w = detect_steady(x.t, x.normal, sp);
  if (!s.steady_all_loads || !w.found) return w;
  for (const std::vector<double>* v : {&x.shear, &x.moment}) {
    const SteadyWindow o = detect_steady(x.t, *v, sp);
    if (!o.found) return o;
    if (o.start > w.start) w = o;
  }
  return w;
}

std::vector<WindowDrift> window_drifts(const StationResult& r) {
  std::vector<WindowDrift> out;
  const SteadyWindow& w = r.window;
  if (r.forces.empty()) return out;
  // No steady window at all: every load's mean is that of a plate that may still be changing.
  if (!w.found) {
    for (const char* load : {"R_n", "R_s", "impact point"})
      out.push_back({load, fmt::format("{}: the run found no steady window; its mean over {:.2f}-{:.2f} s may be that "
                                       "of a plate still filling, and its ± does not include what a longer run would "
                                       "read", load, w.start, w.end)});
    return out;
  }
  if (w.blocks < 3 || !(w.end > w.start)) return out;
  const double block = (w.end - w.start) / w.blocks;
  std::vector<double> t, normal, shear, minus_moment;
  for (const ForceSample& f : r.forces) {
    t.push_back(f.t);
    normal.push_back(f.normal);
    shear.push_back(f.shear);
    minus_moment.push_back(-f.moment);
  }
  const std::string where = fmt::format("through the steady window ({:.2f}-{:.2f} s)", w.start, w.end);
  // The plate's build-up forms more slowly than the load (bench/WINDOW.md): a longer run reads
  // another value, and the standard error of the window's mean does not include the difference.
  const std::string why = "the mean is that of a plate still changing, and its ± does not include what a longer run "
                          "would read";
  auto force_note = [&](const char* name, const std::vector<double>& v) {
    const WindowTrend tr = window_trend(t, v, w.start, w.end, block);
    if (!tr.drifting()) return;
    const double c = tr.change();
    out.push_back({name, fmt::format("{} still {} {}: a straight line through its 0.1 s block means moves {:+.3g} N "
                                     "across it ({:+.0f} % of its mean, {:.1f} standard errors); {}",
                                     name, c > 0.0 ? "rises" : "falls", where, c, 100.0 * c / tr.mean,
                                     std::abs(c) / (tr.se_slope * tr.span), why)});
  };
  force_note("R_n", normal);
  force_note("R_s", shear);
  // A position has no scale of its own to be 5 % of: only the trend's significance counts.
  const WindowTrend tr = window_trend_ratio(t, minus_moment, normal, w.start, w.end, block);
  if (tr.drifting(0.0)) {
    const double c = tr.change();
    out.push_back({"impact point",
                   fmt::format("the impact point still moves {} the face {}: {:.1f} mm across it ({:.1f} standard "
                               "errors); {}",
                               c > 0.0 ? "up" : "down", where, 1e3 * std::abs(c), std::abs(c) / (tr.se_slope * tr.span),
                               why)});
  }
  return out;
}

double restart_transit(const Scene& sc, const RunSettings& s, ChangeAt at) {
  // The stream leaves the pulley at about belt speed and keeps its horizontal speed to the plate.
  const double flight = std::max(0.0, sc.plate.face_x(sc.belt.tangent_point.y()) - sc.belt.tangent_point.x()) / sc.belt_speed;
  switch (at) {
    case ChangeAt::plate: return s.detect_block;
    case ChangeAt::flight: return flight + s.detect_block;
    case ChangeAt::feed: return -sc.feed_s_begin / sc.belt_speed + flight + s.detect_block;
  }
  return 0.0;
}

namespace {

// Continues the steady state `rs.from` in this run's scene: the World's dynamic state, and the
// discharge count the mass balance needs (what was fed and is neither in the rig nor in a sink).
void restore(const Restart& rs, Scene& sc, StationResult& r, const RunSettings& s) {
  World& w = *sc.world;
  const double dt = sc.dt;
  w.load_checkpoint(rs.from);
  if (w.dt() != dt)
    throw InputError(rs.from, 0, "dt",
                     fmt::format("the steady state was run at dt {:.6g} s, this run's inputs give {:.6g} s: it "
                                 "cannot continue it", w.dt(), dt));
  double in_rig = 0.0, sunk = 0.0;
  for (double m : w.particles().mass) in_rig += m;
  for (const auto& k : w.sinks()) sunk += k.removed_mass;
  sc.discharged = w.inserters()[static_cast<std::size_t>(sc.inserter)].inserted_mass - sunk - in_rig;
  r.restart_time = w.time();
  r.transient_end = r.restart_time + restart_transit(sc, s, rs.change);
}

// Writes the World's state where `path` says, whole or not at all.
void save_state(World& w, const std::string& path) {
  w.refresh_lists();
  const std::string tmp = fmt::format("{}.tmp{}", path, static_cast<long long>(::getpid()));
  w.save_checkpoint(tmp);
  std::filesystem::rename(tmp, path);
}

}  // namespace

StationResult run_station(const Station& st, const RunOptions& o) {
  const RunSettings& s = o.settings;
  Scene sc = build_scene(st, s, o.geometry, o.external);
  World& w = *sc.world;
  Sensors sensors(sc, s.momentum_plane_fraction);
  StationResult r = describe_run(st, s, sc);
  const double t_start = now();
  w.initialise();
  if (o.restart) restore(*o.restart, sc, r, s);
  // A restart's budget: its transit and as much time after it as a run from empty has after min_time.
  const double duration = o.restart ? r.transient_end - r.restart_time + (s.max_time - s.min_time) : s.max_time;
  const Schedule schedule = Schedule::of(s, sc.dt, duration);
  const auto maps = record_maps(o, schedule, sc);
  ParticleFrames frames(o, sc);

  const Marched marched = march(o, schedule, sc, sensors, maps, frames, t_start, r);
  r.simulated_time = w.time();
  r.steps = w.step_count();
  r.rebuilds = w.rebuild_count();
  r.peak_particles = std::max(r.peak_particles, w.particles().size());

  reduce_series(sc, sensors, s, marched.series, r);
  for (const auto& m : maps) r.maps.push_back(m->reduce(r.window.start, r.window.end, s.mean_block));
  account_mass(sc, r);
  r.side_view = sensors.side_view(w, o.side_view_points);
  r.side_view_time = w.time();
  frames.finish();
  note_run(sc, s, marched.peak_bodies, r);

  if (!o.save_state.empty()) save_state(w, o.save_state);
  if (r.restart_time >= 0.0)
    r.notes.push_back(fmt::format("continued from a steady state at {:.3f} s with this run's inputs; no window before "
                                  "{:.3f} s, the time the change needs to reach the plate",
                                  r.restart_time, r.transient_end));

  r.wall_seconds = now() - t_start;
  if (o.progress) o.progress({r.simulated_time - std::max(0.0, r.restart_time), duration, r.wall_seconds, w.particles().size(), true});
  return r;
}

void reduce_series(const Scene& sc, const Sensors& sensors, const RunSettings& s, const StationSeries& series,
                   StationResult& r) {
  find_window(series, s, r);
  const Window win{r.window.start, r.window.end, s.mean_block};
  reduce_plate_load(sc, series, win, r);
  r.wear = s.wear;
  reduce_snapshots(win, r);
  reduce_plane_crossings(series, win, r);
  reduce_exit_velocity(sc, series.face, win, r);
  reduce_stream_limits(sensors, win, r);
  note_feed_mismatch(sc, r);
}

void write_result_files(const std::string& dir, const StationResult& r) {
  namespace fs = std::filesystem;
  fs::create_directories(dir);
  const fs::path d(dir);
  {
    auto f = open_out(d / "timeseries.csv");
    f << "t_s,normal_force_N,shear_force_N,moment_Nm,impact_point_y_mm,mass_through_kg,momentum_in_Ns,"
         "momentum_floor_Ns,momentum_content_Ns\n";
    for (const auto& s : r.forces)
      f << fmt::format("{:.5f},{:.6g},{:.6g},{:.6g},{},{:.6g},{:.6g},{:.6g},{:.6g}\n", s.t, s.normal, s.shear, s.moment,
                       s.normal > 0.0 ? fmt::format("{:.4g}", -s.moment / s.normal * 1e3) : std::string(),
                       s.mass_through, s.momentum_in, s.momentum_floor, s.momentum_content);
  }
  {
    auto f = open_out(d / "sensors.csv");
    f << "t_s,particles,impact_velocity_mps,impact_velocity_fast_mps,layer_speed_mps,layer_height_mm,"
         "stream_thickness_mm\n";
    auto opt = [](double num, int n, double scale) { return n ? fmt::format("{:.5g}", num / n * scale) : std::string(); };
    for (const auto& s : r.snapshots)
      f << fmt::format("{:.5f},{},{},{},{},{},{}\n", s.t, s.particles, opt(s.vp_sum, s.vp_n, 1),
                       opt(s.vp_fast_sum, s.vp_fast_n, 1), opt(s.layer_speed_sum, s.layer_n, 1),
                       opt(s.layer_height_sum, s.layer_n, 1e3),
                       std::isfinite(s.stream_thickness) ? fmt::format("{:.4g}", s.stream_thickness * 1e3) : "");
  }
  {
    auto f = open_out(d / "steady.csv");
    f << "quantity,value,uncertainty,n\n";
    auto row = [&](const char* q, const Estimate& e, double scale) {
      if (!e.ok()) return;
      f << fmt::format("{},{:.6g},{},{}\n", q, e.value * scale,
                       std::isfinite(e.se) ? fmt::format("{:.3g}", e.se * scale) : std::string(), e.n);
    };
    row("normal_force_N", r.normal_force, 1);
    row("shear_force_N", r.shear_force, 1);
    row("resultant_force_N", r.resultant_force, 1);
    row("impact_velocity_mps", r.impact_velocity, 1);
    row("exit_velocity_mps", r.exit_velocity, 1);
    row("impact_point_y_mm", r.impact_point_y, 1e3);
    row("impact_velocity_fast_mps", r.impact_velocity_fast, 1);
    row("layer_speed_mps", r.layer_speed, 1);
    row("layer_height_mm", r.layer_height, 1e3);
    row("stream_thickness_mm", r.stream_thickness, 1e3);
    row("mass_flux_kgps", r.mass_flux, 1);
    row("momentum_balance_N", r.momentum_balance, 1);
  }
  {
    auto f = open_out(d / "trajectory.csv");
    f << "boundary,x_mm,y_mm,uncertainty_mm,n\n";
    for (const char* b : {"upper", "lower", "centre"})
      for (const auto& t : r.trajectory) {
        const Estimate& e = std::string(b) == "upper" ? t.upper : std::string(b) == "lower" ? t.lower : t.centre;
        if (!e.ok()) continue;
        f << fmt::format("{},{:.1f},{:.2f},{},{}\n", b, t.x * 1e3, e.value * 1e3,
                         std::isfinite(e.se) ? fmt::format("{:.2f}", e.se * 1e3) : std::string(), e.n);
      }
  }
  {
    auto f = open_out(d / "side_view.csv");
    f << "x_mm,y_mm,z_mm,speed_mps\n";
    for (const auto& p : r.side_view)
      f << fmt::format("{:.1f},{:.1f},{:.1f},{:.3f}\n", p.x * 1e3, p.y * 1e3, p.z * 1e3, p.speed);
  }
  {
    auto f = open_out(d / "run.txt");
    f << fmt::format("condition = {}\nquality = {}\nshape = {}\nparticle_diameter_mm = {:.3f}\ndt_s = {:.6g}\n"
                     "collision_time_s = {:.6g}\nrayleigh_time_s = {:.6g}\nsimulated_s = {:.4f}\nsteps = {}\n"
                     "rebuilds = {}\nwall_s = {:.1f}\nearly_stop = {}\npeak_particles = {}\nsteady_found = {}\n"
                     "window_start_s = {:.3f}\nwindow_end_s = {:.3f}\nwindow_blocks = {}\n"
                     "inserted_kg = {:.6g}\ndischarged_kg = {:.6g}\nescaped_kg = {:.6g}\nin_domain_kg = {:.6g}\n",
                     r.condition, r.quality, r.shape, r.diameter * 1e3, r.dt, r.collision_time, r.rayleigh_time,
                     r.simulated_time, r.steps, r.rebuilds >= 0 ? std::to_string(r.rebuilds) : "unknown (not in this DEM cache entry)", r.wall_seconds, r.early_stop, r.peak_particles, r.window.found,
                     r.window.start, r.window.end, r.window.blocks, r.inserted, r.discharged, r.escaped, r.in_domain);
    for (const auto& n : r.notes) f << "note = " << n << "\n";
    for (const auto& d : window_drifts(r)) f << "note = " << d.note << "\n";
  }
  if (!r.maps.empty()) {
    write_plate_map_csv((d / "plate_map.csv").string(), r.maps, r.wear, r.condition);
    write_plate_map_vtk((d / "plate_map.vtk").string(), r.maps, r.wear);
  }
}

void write_side_view_vtk(const std::string& path, const std::vector<SidePoint>& pts) {
  std::ofstream f(path);
  if (!f) throw InputError(path, 0, "out", "cannot write this file");
  f << "# vtk DataFile Version 3.0\nchutelab DEM transfer station, side view; lengths in mm, speed in m/s\nASCII\n"
       "DATASET POLYDATA\n";
  f << fmt::format("POINTS {} float\n", pts.size());
  for (const auto& p : pts) f << fmt::format("{:.1f} {:.1f} {:.1f}\n", p.x * 1e3, p.y * 1e3, p.z * 1e3);
  f << fmt::format("VERTICES {} {}\n", pts.size(), 2 * pts.size());
  for (std::size_t i = 0; i < pts.size(); ++i) f << "1 " << i << "\n";
  f << fmt::format("POINT_DATA {}\nSCALARS speed_mps float 1\nLOOKUP_TABLE default\n", pts.size());
  for (const auto& p : pts) f << p.speed << "\n";
}

}  // namespace chutelab::dem::station
