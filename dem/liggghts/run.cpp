#include "dem/liggghts/run.h"

#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>

#include <fmt/format.h>

#include "core/input_error.h"
#include "core/number.h"
#include "dem/liggghts/output.h"

namespace chutelab::dem::liggghts {
namespace {

namespace st = station;

double now() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

std::string quoted(const std::string& s) {
  std::string o = "'";
  for (char c : s) o += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return o + "'";
}

// OpenMPI refuses to start as root unless told; CI containers run as root.
std::string root_env() {
  return geteuid() == 0 ? "OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 " : "";
}

}  // namespace

std::string launcher(const Options& o) {
  if (!o.command.empty()) return o.command;
  return fmt::format("mpirun -n {} liggghts", std::max(1, o.ranks));
}

std::string program_of(const std::string& command) {
  std::istringstream is(command);
  std::string w, last;
  while (is >> w) last = w;
  return last;
}

std::string version(const std::string& program) {
  if (program.empty()) return "";
  // -log none: LIGGGHTS opens log.liggghts in the working directory before it reads -h.
  FILE* p = popen((quoted(program) + " -log none -h </dev/null 2>/dev/null").c_str(), "r");
  if (!p) return "";
  std::string first;
  char buf[512];
  while (std::fgets(buf, sizeof buf, p)) {
    std::string line(buf);
    while (!line.empty() && (line.back() == '\n' || line.back() == '\r')) line.pop_back();
    if (first.empty() && !line.empty()) first = line;
  }
  pclose(p);  // `liggghts -h` exits with status 1 after printing its help
  if (first.find("LIGGGHTS") == std::string::npos) return "";
  return first;
}

Deck deck_for(const Station& st, const Options& o) {
  const st::Scene sc = st::build_scene(st, o.settings, o.geometry, o.external);
  return make_deck(st, sc, o.settings, o.sim_time > 0.0 ? o.sim_time : o.settings.max_time);
}

st::StationResult run_station(const Station& station, const Options& o) {
  namespace fs = std::filesystem;
  const st::RunSettings& s = o.settings;
  if (o.work_dir.empty()) throw InputError("", 0, "liggghts", "no folder to run the LIGGGHTS deck in");
  st::Scene sc = st::build_scene(station, s, o.geometry, o.external);
  const double sim_time = o.sim_time > 0.0 ? o.sim_time : s.max_time;
  const Deck deck = make_deck(station, sc, s, sim_time);
  const std::string cmd = launcher(o);
  const std::string program = program_of(cmd);
  const std::string ver = version(program);
  if (ver.empty())
    throw InputError("", 0, "models",
                     fmt::format("the liggghts model needs LIGGGHTS, but '{}' does not run (install the Debian "
                                 "package liggghts, or name the program with {})",
                                 program, mention("dem.liggghts_command")));
  const fs::path dir(o.work_dir);
  std::error_code ec;
  for (const char* f : {Deck::plate_file, Deck::dump_file, Deck::log_file}) fs::remove(dir / f, ec);
  write_deck(deck, o.work_dir);

  const double t_start = now();
  if (o.progress) o.progress({0.0, sim_time, 0.0, 0, false});
  const std::string line = fmt::format("cd {} && {}{} -echo none -in {} -log {} 2>stderr.txt", quoted(dir.string()),
                                       root_env(), cmd, Deck::input_file, Deck::log_file);
  FILE* pipe = popen(line.c_str(), "r");
  if (!pipe) throw InputError(dir.string(), 0, "liggghts", fmt::format("cannot start '{}'", cmd));
  {
    // Screen output: thermo lines "step atoms" give the progress.
    char buf[4096];
    bool thermo = false;
    double next = 0.0;
    while (std::fgets(buf, sizeof buf, pipe)) {
      std::istringstream is(buf);
      std::string a, b, extra;
      if (!(is >> a >> b)) continue;
      if (a == "Step" && b == "Atoms") {
        thermo = true;
        continue;
      }
      const auto step = parse_number(a), atoms = parse_number(b);
      if (!thermo || !step || !atoms || (is >> extra)) continue;
      const double t = *step * deck.dt;
      if (o.progress && t >= next) {
        o.progress({t, sim_time, now() - t_start, static_cast<std::size_t>(*atoms), false});
        next = t + 0.01 * sim_time;
      }
    }
  }
  const int status = pclose(pipe);
  const std::string log_path = (dir / Deck::log_file).string();
  const LogSummary log = read_log(log_path);
  if (status != 0 || !log.error.empty())
    throw InputError(log_path, 0, "liggghts",
                     fmt::format("'{}' failed (exit status {}){}; the deck is {}", cmd, status,
                                 log.error.empty() ? "" : ": " + log.error, (dir / Deck::input_file).string()));
  st::StationResult r = measure_run(station, o, o.work_dir);
  r.wall_seconds = now() - t_start;
  if (o.progress) o.progress({r.simulated_time, sim_time, r.wall_seconds, log.final_atoms, true});
  return r;
}

st::StationResult measure_run(const Station& station, const Options& o, const std::string& run_dir) {
  namespace fs = std::filesystem;
  const st::RunSettings& s = o.settings;
  st::Scene sc = st::build_scene(station, s, o.geometry, o.external);
  const Deck deck = make_deck(station, sc, s, o.sim_time > 0.0 ? o.sim_time : s.max_time);
  const fs::path dir(run_dir);
  const std::string log_path = (dir / Deck::log_file).string();
  const LogSummary log = read_log(log_path);
  const std::string ver = log.version.empty() ? "LIGGGHTS" : log.version;
  const std::vector<PlateSample> plate = read_plate_file((dir / Deck::plate_file).string());
  DumpReader dump((dir / Deck::dump_file).string());
  st::Sensors sensors(sc, s.momentum_plane_fraction);
  st::StationResult r;
  r.condition = station.condition;
  r.quality = std::string(st::name(s.quality));
  r.diameter = sc.diameter;
  r.shape = std::string(st::name(sc.shape));
  r.dt = sc.dt;
  r.collision_time = sc.collision_time;
  r.rayleigh_time = sc.rayleigh_time;
  r.notes = sc.notes;

  st::StationSeries series;
  series.sample_dt = static_cast<double>(deck.steps_per_sample) * deck.dt;
  Frame frame, last;
  bool have_frame = false, have_last = false;
  auto view = [&](const Frame& f) {
    return st::ParticleView{static_cast<double>(f.step) * deck.dt, f.id.size(), f.x.data(), f.v.data(),
                            f.mass.data(), f.id.data()};
  };
  for (const PlateSample& ps : plate) {
    if (ps.step <= 0 || ps.step % deck.steps_per_sample != 0) continue;
    while (!have_frame || frame.step < ps.step) {
      if (!dump.next(frame))
        throw InputError((dir / Deck::dump_file).string(), 0, "",
                         fmt::format("no particle frame for step {} of the plate series", ps.step));
      have_frame = true;
    }
    if (frame.step != ps.step)
      throw InputError((dir / Deck::dump_file).string(), 0, "", fmt::format("no particle frame at step {}", ps.step));
    const double t = static_cast<double>(ps.step) * deck.dt;
    series.t.push_back(t);
    series.normal.push_back(ps.force.dot(sc.plate.into));
    series.shear.push_back(ps.force.dot(sc.plate.down));
    series.moment.push_back(ps.torque.z());
    st::ForceSample sample{t, series.normal.back(), series.shear.back(), series.moment.back()};
    const st::ParticleView pv = view(frame);
    sensors.count_crossings(pv, sample);
    r.forces.push_back(sample);
    if ((ps.step / deck.steps_per_sample) % deck.samples_per_snapshot == 0)
      r.snapshots.push_back(sensors.measure(pv, series.face));
    last = frame;
    have_last = true;
  }
  if (series.t.empty())
    throw InputError((dir / Deck::plate_file).string(), 0, "", "LIGGGHTS wrote no plate samples");
  r.simulated_time = series.t.back();
  r.steps = plate.empty() ? 0 : plate.back().step;
  r.peak_particles = log.peak_atoms;
  st::reduce_series(sc, sensors, s, series, r);

  r.inserted = log.inserted_mass;
  r.in_domain = static_cast<double>(log.final_atoms) * sc.particle_mass;
  r.discharged = std::max(0.0, r.inserted - r.in_domain);
  if (have_last) {
    r.side_view = sensors.side_view(view(last), o.side_view_points);
    r.side_view_time = static_cast<double>(last.step) * deck.dt;
  }
  r.notes.push_back(fmt::format(
      "LIGGGHTS {}: {} ({}), {:.1f} mm spheres, dt {:.3g} s ({:.2f} of the collision time {:.3g} s, {:.2f} of the "
      "Rayleigh time), {:.2f} s simulated, steady window {:.2f}-{:.2f} s ({} blocks of {:.1f} s); run in {}",
      r.quality, ver, launcher(o), r.diameter * 1e3, r.dt, r.dt / r.collision_time, r.collision_time,
      r.dt / r.rayleigh_time, r.simulated_time, r.window.start, r.window.end, r.window.blocks, s.mean_block,
      dir.string()));
  return r;
}

}  // namespace chutelab::dem::liggghts
