#include "dem/station/run.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <memory>
#include <optional>

#include <fmt/format.h>

#include "core/input_error.h"
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

}  // namespace

StationResult run_station(const Station& st, const RunOptions& o) {
  const RunSettings& s = o.settings;
  Scene sc = build_scene(st, s, o.geometry, o.external);
  World& w = *sc.world;
  Sensors sensors(sc, s.momentum_plane_fraction);
  StationResult r;
  r.condition = st.condition;
  r.quality = std::string(name(s.quality));
  r.diameter = sc.diameter;
  r.shape = std::string(name(sc.shape));
  r.dt = sc.dt;
  r.collision_time = sc.collision_time;
  r.rayleigh_time = sc.rayleigh_time;
  r.notes = sc.notes;
  const double t_start = now();
  w.initialise();

  const long long steps_per_sample = std::max<long long>(1, std::llround(s.sample_interval / sc.dt));
  const double sample_dt = static_cast<double>(steps_per_sample) * sc.dt;
  const long long samples_per_snapshot = std::max<long long>(1, std::llround(s.snapshot_interval / sample_dt));
  const long long max_steps = static_cast<long long>(std::ceil(s.max_time / sc.dt - 1e-9));
  const SteadyParams sp{s.detect_block, s.detect_tail, s.mean_block};

  std::vector<double> ts, fn, fs, mz;
  // Maps of the plate and the [dem.stl] walls, from every contact of every step (plate_map.h).
  std::vector<std::unique_ptr<PlateMapRecorder>> maps;
  {
    std::vector<int> mapped = {sc.plate_wall};
    mapped.insert(mapped.end(), sc.map_walls.begin(), sc.map_walls.end());
    const auto max_samples = static_cast<std::size_t>(max_steps / steps_per_sample + 2);
    // The generated plate, not meshed for the maps, gets the map grid (plate_map.h MapGrid).
    std::optional<MapGrid> grid;
    if (!o.geometry.stl_plate && s.plate_cells == 0 && s.map_cell > 0.0)
      grid = MapGrid::on_face(sc.plate.top_edge, sc.plate.down, sc.plate.height, sc.plate.width, s.map_cell);
    for (int wi : mapped) {
      auto rec = std::make_unique<PlateMapRecorder>(w.walls()[static_cast<std::size_t>(wi)], s.wear.finnie, max_samples,
                                                    wi == sc.plate_wall && grid ? &*grid : nullptr);
      w.observe_wall(wi, [p = rec.get()](const WallContact& c) { p->observe(c); });
      maps.push_back(std::move(rec));
    }
  }
  std::vector<FaceParticle> face;
  namespace fs_ = std::filesystem;
  // The particles as a ParaView time series (dem/io/vtk_series.h), with each particle's contact
  // force: its force less its weight and the flight force (air drag) the run adds.
  std::optional<VtkSeries> series;
  if (!o.vtk_dir.empty()) {
    fs_::create_directories(o.vtk_dir);
    write_vtk_walls((fs_::path(o.vtk_dir) / "walls.vtk").string(), w.walls());
    series.emplace(o.vtk_dir, "particles");
  }
  auto frame = [&] {
    const Particles& p = w.particles();
    std::vector<Vec3> flight(p.size(), Vec3::Zero());
    sc.flight.add(p, 0, p.size(), flight);
    const Vec3 g = w.settings().gravity;
    std::vector<double> contact(p.size());
    for (std::size_t i = 0; i < p.size(); ++i) contact[i] = (p.f[i] - p.mass[i] * g - flight[i]).norm();
    series->write(w.time(), p, contact);
  };
  double next_vtk = series && o.vtk_every > 0.0 ? 0.0 : std::numeric_limits<double>::infinity();
  double next_check = std::max(s.min_time, s.detect_tail + s.min_window);
  double next_progress = 0.0;
  const double progress_step = 0.01 * s.max_time;
  long long sample_index = 0;
  std::size_t peak_bodies = 0;  // clumps (peak_particles counts their spheres)

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
  while (w.step_count() < max_steps) {
    force = Vec3::Zero();
    moment = 0.0;
    if (s.extra_threads) w.set_threads(base_threads + s.extra_threads->load(std::memory_order_relaxed));
    w.step(steps_per_sample);
    sc.discharge();
    force /= static_cast<double>(steps_per_sample);
    moment /= static_cast<double>(steps_per_sample);
    const double t = w.time();
    for (auto& m : maps) m->end_sample(t);
    ts.push_back(t);
    fn.push_back(force.dot(sc.plate.into));
    fs.push_back(force.dot(sc.plate.down));
    mz.push_back(moment);
    ForceSample sample{t, fn.back(), fs.back(), mz.back()};
    sensors.count_crossings(w, sample);
    r.forces.push_back(sample);
    ++sample_index;
    if (sample_index % samples_per_snapshot == 0) {
      r.snapshots.push_back(sensors.measure(w, face));
      r.peak_particles = std::max(r.peak_particles, w.particles().size());
      peak_bodies = std::max(peak_bodies, w.clumps().size());
    }
    if (t + 1e-12 >= next_vtk) {
      frame();
      next_vtk += o.vtk_every;
    }
    if (o.progress && t >= next_progress) {
      o.progress({t, s.max_time, now() - t_start, w.particles().size(), false});
      next_progress += progress_step;
    }
    if (t + 1e-12 >= next_check) {
      next_check += s.detect_block;
      const SteadyWindow win = detect_steady(ts, fn, sp);
      if (win.found && win.end - win.start >= s.min_window - 1e-9 &&
          !drifting(ts, fn, win.start, win.end, s.mean_block)) {
        r.early_stop = true;
        break;
      }
    }
  }
  w.observe_wall_loads(nullptr);  // it refers to this function's locals
  r.simulated_time = w.time();
  r.steps = w.step_count();
  r.rebuilds = w.rebuild_count();
  r.peak_particles = std::max(r.peak_particles, w.particles().size());

  reduce_series(sc, sensors, s, StationSeries{std::move(ts), std::move(fn), std::move(fs), std::move(mz),
                                              std::move(face), sample_dt},
                r);
  const double a = r.window.start, b = r.window.end, blk = s.mean_block;
  // --- maps over the steady window ---
  for (const auto& m : maps) r.maps.push_back(m->reduce(a, b, blk));

  // --- mass accounting ---
  r.inserted = w.inserters()[static_cast<std::size_t>(sc.inserter)].inserted_mass;
  r.discharged = sc.discharged + w.sinks()[static_cast<std::size_t>(sc.plate_sink)].removed_mass;
  for (int k : sc.boundary_sinks) r.escaped += w.sinks()[static_cast<std::size_t>(k)].removed_mass;
  for (double m : w.particles().mass) r.in_domain += m;

  r.side_view = sensors.side_view(w, o.side_view_points);
  r.side_view_time = w.time();
  // The series ends on the final state (the side view's instant).
  if (series && series->last_time() < w.time() - 1e-12) frame();

  // --- notes ---
  r.notes.push_back(fmt::format(
      "DEM {}: {}, dt {:.3g} s ({:.2f} of the collision time {:.3g} s, {:.2f} of the Rayleigh time), "
      "{:.2f} s simulated{}, steady window {:.2f}-{:.2f} s ({} blocks of {:.1f} s)",
      r.quality,
      sc.shape == ParticleShape::clump
          ? fmt::format("two-sphere clumps (reference study Fig. 4c) of {:.1f} mm spheres, {} bodies at the peak", r.diameter * 1e3,
                        peak_bodies)
          : fmt::format("{:.1f} mm spheres", r.diameter * 1e3),
      r.dt, r.dt / r.collision_time, r.collision_time, r.dt / r.rayleigh_time,
      r.simulated_time, r.early_stop ? " (stopped when steady)" : "", a, b, r.window.blocks, blk));
  if (r.escaped > 0.0)
    r.notes.push_back(fmt::format("{:.3g} kg left the rig through the domain's faces (not the discharge)", r.escaped));
  for (const auto& m : *sc.warnings) r.notes.push_back("DEM warning: " + m);

  r.wall_seconds = now() - t_start;
  if (o.progress) o.progress({r.simulated_time, s.max_time, r.wall_seconds, w.particles().size(), true});
  return r;
}

void reduce_series(const Scene& sc, const Sensors& sensors, const RunSettings& s, const StationSeries& series,
                   StationResult& r) {
  const std::vector<double>& ts = series.t;
  const std::vector<double>& fn = series.normal;
  const std::vector<double>& fs = series.shear;
  const std::vector<double>& mz = series.moment;
  const std::vector<FaceParticle>& face = series.face;
  const double sample_dt = series.sample_dt;
  const SteadyParams sp{s.detect_block, s.detect_tail, s.mean_block};

  // --- the steady window ---
  r.window = detect_steady(ts, fn, sp);
  if (!r.window.found || r.window.end - r.window.start < s.min_window - 1e-9) {
    const bool none = !r.window.found;
    const int n = std::max(1, static_cast<int>(std::floor(s.min_window / s.mean_block + 1e-9)));
    r.window.end = r.simulated_time;
    r.window.start = std::max(0.0, r.window.end - n * s.mean_block);
    r.window.blocks = static_cast<int>(std::floor((r.window.end - r.window.start) / s.mean_block + 1e-9));
    r.notes.push_back(none ? fmt::format("no steady state detected within {:.2f} s: means over the last {:.1f} s, "
                                         "uncertain", r.simulated_time, r.window.end - r.window.start)
                           : fmt::format("steady window shorter than {:.1f} s at the time limit: means over the "
                                         "last {:.1f} s", s.min_window, r.window.end - r.window.start));
  }
  const double a = r.window.start, b = r.window.end, blk = s.mean_block;

  // --- plate load cell ---
  const std::vector<double> ones(ts.size(), 1.0);
  r.normal_force = block_mean(ts, fn, ones, a, b, blk);
  r.shear_force = block_mean(ts, fs, ones, a, b, blk);
  if (r.normal_force.ok() && r.shear_force.ok()) {
    const double R = std::hypot(r.normal_force.value, r.shear_force.value);
    r.resultant_force.value = R;
    r.resultant_force.n = r.normal_force.n;
    if (R > 0.0)
      r.resultant_force.se = std::hypot(r.normal_force.value * r.normal_force.se, r.shear_force.value * r.shear_force.se) / R;
  }
  {
    std::vector<double> minus_m(mz.size());
    for (std::size_t k = 0; k < mz.size(); ++k) minus_m[k] = -mz[k];
    const Estimate up = block_ratio(ts, minus_m, fn, a, b, blk);  // along the face above the reference
    r.impact_point_y = up;
    if (up.ok()) {
      r.impact_point_y.value = sc.plate.y_at(up.value);
      r.impact_point_y.se = up.se * std::cos(sc.plate.angle);
    }
  }

  // --- maps over the steady window ---
  r.wear = s.wear;

  // --- snapshot sensors ---
  std::vector<double> tn, vp, vpw, vpf, vpfw, ls, lh, lsw, th;
  for (const auto& sn : r.snapshots) {
    tn.push_back(sn.t);
    vp.push_back(sn.vp_n ? sn.vp_sum / sn.vp_n : kNaN);
    vpw.push_back(sn.vp_n);
    vpf.push_back(sn.vp_fast_n ? sn.vp_fast_sum / sn.vp_fast_n : kNaN);
    vpfw.push_back(sn.vp_fast_n);
    ls.push_back(sn.layer_n ? sn.layer_speed_sum / sn.layer_n : kNaN);
    lh.push_back(sn.layer_n ? sn.layer_height_sum / sn.layer_n : kNaN);
    lsw.push_back(sn.layer_n);
    th.push_back(sn.stream_thickness);
  }
  const std::vector<double> snap_ones(tn.size(), 1.0);
  r.impact_velocity = block_mean(tn, vp, vpw, a, b, blk);
  r.impact_velocity_fast = block_mean(tn, vpf, vpfw, a, b, blk);
  r.layer_speed = block_mean(tn, ls, lsw, a, b, blk);
  r.layer_height = block_mean(tn, lh, lsw, a, b, blk);
  r.stream_thickness = block_mean(tn, th, snap_ones, a, b, blk);

  // --- plane crossings: mass flux and momentum balance, block by block ---
  {
    std::vector<double> mass_rate, mom_rate;
    for (std::size_t k = 0; k < r.forces.size(); ++k) {
      const ForceSample& f = r.forces[k];
      mass_rate.push_back(f.mass_through / sample_dt);
      // Rate of change of the content between samples enters as its difference.
      const double dp = k > 0 ? f.momentum_content - r.forces[k - 1].momentum_content : 0.0;
      mom_rate.push_back((f.momentum_in - f.momentum_floor - dp) / sample_dt);
    }
    r.mass_flux = block_mean(ts, mass_rate, ones, a, b, blk);
    r.momentum_balance = block_mean(ts, mom_rate, ones, a, b, blk);
  }

  // V_a: down the face, 30-150 mm below the impact point, once that is known.
  if (r.impact_point_y.ok()) {
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

  // --- stream limits ---
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

  if (r.layer_speed.ok() && std::abs(r.layer_speed.value / sc.belt_speed - 1.0) > 0.02)
    r.notes.push_back(fmt::format("the layer reaches the pulley at {:.3f} m/s, not at belt speed {:.3f} m/s",
                                  r.layer_speed.value, sc.belt_speed));
  if (r.mass_flux.ok() && std::abs(r.mass_flux.value / sc.mass_flow - 1.0) > 0.05)
    r.notes.push_back(fmt::format("free-stream mass flux {:.3f} kg/s differs from the feed {:.3f} kg/s",
                                  r.mass_flux.value, sc.mass_flow));
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
  }
  if (!r.maps.empty()) {
    write_plate_map_csv((d / "plate_map.csv").string(), r.maps, r.wear, r.condition);
    write_plate_map_vtk((d / "plate_map.vtk").string(), r.maps, r.wear);
  }
}

void write_side_view_vtk(const std::string& path, const std::vector<SidePoint>& pts) {
  std::ofstream f(path);
  if (!f) throw InputError(path, 0, "out", "cannot write this file");
  f << "# vtk DataFile Version 3.0\nchutelab DEM transfer station, side view\nASCII\nDATASET POLYDATA\n";
  f << fmt::format("POINTS {} float\n", pts.size());
  for (const auto& p : pts) f << fmt::format("{} {} {}\n", p.x, p.y, p.z);
  f << fmt::format("VERTICES {} {}\n", pts.size(), 2 * pts.size());
  for (std::size_t i = 0; i < pts.size(); ++i) f << "1 " << i << "\n";
  f << fmt::format("POINT_DATA {}\nSCALARS speed float 1\nLOOKUP_TABLE default\n", pts.size());
  for (const auto& p : pts) f << p.speed << "\n";
}

}  // namespace chutelab::dem::station
