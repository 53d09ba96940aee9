#include "dem/station/cache.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <functional>
#include <limits>
#include <set>
#include <string_view>
#include <thread>
#include <vector>

#include <fmt/format.h>

#include "core/output_folder.h"

namespace chutelab::dem::station {
namespace {

// Format 6 ends with "end <FNV-1a 64 of everything before that line>", so a file cut short (a
// writer that died, a file system that shows a rename before the data) or changed afterwards is
// refused, not a result with half its series or an edited number. Format 5 ends with a bare "end"
// line (no check sum): the recorded runs of tests/peer/dem-cache are format 5 and too dear to run
// again, so it is still read, under the same strict parse. Any other format is refused (format 2
// had no end line at all, so a file cut at a line end could not be told from a whole one).
constexpr const char* kMagicPrefix = "chutelab-dem-result ";
constexpr const char* kFormat = "6";
constexpr const char* kFormatV5 = "5";
constexpr const char* kMagic = "chutelab-dem-result 6";
constexpr const char* kMagicV5 = "chutelab-dem-result 5";
constexpr const char* kEndV5 = "\nend\n";
// A standard run's entry is ~1 MB; a 400 x 400 map with 50 blocks per cell ~0.5 GB.
constexpr std::size_t kMaxEntryBytes = std::size_t{1} << 31;

std::string num(double v) { return fmt::format("{:.17g}", v); }

void put(std::string& o, const char* name, const Estimate& e) {
  o += fmt::format("scalar {} {} {} {}\n", name, num(e.value), num(e.se), e.n);
}

}  // namespace

std::uint64_t fnv1a64(std::string_view s) {
  std::uint64_t h = 0xcbf29ce484222325ULL;
  for (unsigned char c : s) {
    h ^= c;
    h *= 0x100000001b3ULL;
  }
  return h;
}

std::string canonical(const ExternalInputs& fx) {
  std::string o;
  if (fx.plate_friction) o += fmt::format("plate_friction = {}\n", num(*fx.plate_friction));
  if (!fx.flight_key.empty()) o += fx.flight_key + "\n";
  if (fx.belt_adhesive_stress > 0.0) o += fmt::format("belt_adhesive_stress = {}\n", num(fx.belt_adhesive_stress));
  return o;
}

std::string to_text(const StationResult& r) {
  std::string o;
  o += fmt::format("condition {}\nquality {}\n", r.condition, r.quality);
  if (r.shape != "sphere") o += fmt::format("shape {}\n", r.shape);
  o += fmt::format("run {} {} {} {} {} {} {} {} {} {}", num(r.diameter), num(r.dt), num(r.collision_time),
                   num(r.rayleigh_time), num(r.simulated_time), r.steps, num(r.wall_seconds), r.early_stop ? 1 : 0,
                   r.peak_particles, num(r.side_view_time));
  // The rebuild count came later: entries written before it end the line here (read back as unknown).
  o += r.rebuilds >= 0 ? fmt::format(" {}\n", r.rebuilds) : std::string("\n");
  if (r.restart_time >= 0.0) o += fmt::format("restart {} {}\n", num(r.restart_time), num(r.transient_end));
  o += fmt::format("window {} {} {} {}\n", r.window.found ? 1 : 0, num(r.window.start), num(r.window.end), r.window.blocks);
  o += fmt::format("mass {} {} {} {}\n", num(r.inserted), num(r.discharged), num(r.escaped), num(r.in_domain));
  put(o, "normal_force", r.normal_force);
  put(o, "shear_force", r.shear_force);
  put(o, "resultant_force", r.resultant_force);
  put(o, "impact_point_y", r.impact_point_y);
  put(o, "impact_velocity", r.impact_velocity);
  put(o, "impact_velocity_fast", r.impact_velocity_fast);
  put(o, "exit_velocity", r.exit_velocity);
  put(o, "layer_speed", r.layer_speed);
  put(o, "layer_height", r.layer_height);
  put(o, "stream_thickness", r.stream_thickness);
  put(o, "mass_flux", r.mass_flux);
  put(o, "momentum_balance", r.momentum_balance);
  for (const auto& t : r.trajectory)
    o += fmt::format("traj {} {} {} {} {} {} {} {} {} {}\n", num(t.x), num(t.upper.value), num(t.upper.se), t.upper.n,
                     num(t.lower.value), num(t.lower.se), t.lower.n, num(t.centre.value), num(t.centre.se), t.centre.n);
  for (const auto& f : r.forces)
    o += fmt::format("force {} {} {} {} {} {} {} {}\n", num(f.t), num(f.normal), num(f.shear), num(f.moment),
                     num(f.mass_through), num(f.momentum_in), num(f.momentum_floor), num(f.momentum_content));
  for (const auto& s : r.snapshots)
    o += fmt::format("snap {} {} {} {} {} {} {} {} {} {}\n", num(s.t), s.particles, num(s.vp_sum), s.vp_n,
                     num(s.vp_fast_sum), s.vp_fast_n, num(s.layer_speed_sum), num(s.layer_height_sum), s.layer_n,
                     num(s.stream_thickness));
  for (const auto& p : r.side_view) o += fmt::format("side {} {} {} {}\n", p.x, p.y, p.z, p.speed);
  // The wear inputs are not stored: the maps keep their sums, the reader applies its own inputs.
  for (const auto& m : r.maps) {
    o += fmt::format("map {} {}\n", num(m.duration), m.wall);
    if (m.grid && m.cells.size() == 2 * static_cast<std::size_t>(m.grid->rows * m.grid->cols)) {
      // A grid map: its geometry once, then the cells with a contact (most of a fine map is empty);
      // the reader rebuilds the rest (plate_map.h empty_cell), bit for bit.
      const MapGrid& g = *m.grid;
      const std::size_t nb = m.cells.front().block_normal.size();
      o += fmt::format("grid {} {} {} {} {} {} {} {} {} {} {} {} {} {}\n", num(g.origin.x()), num(g.origin.y()),
                       num(g.origin.z()), num(g.down.x()), num(g.down.y()), num(g.down.z()), num(g.across.x()),
                       num(g.across.y()), num(g.across.z()), num(g.height), num(g.width), g.rows, g.cols, nb);
      const auto tri = g.triangles();
      for (std::size_t b = 0; 2 * b < m.cells.size(); ++b) {
        const MapCell& c = m.cells[2 * b];
        const bool flip = c.normal.dot((tri[2 * b][1] - tri[2 * b][0]).cross(tri[2 * b][2] - tri[2 * b][0])) < 0.0;
        const bool empty = !flip && c.force == Vec3::Zero() && c.impact_power == 0.0 && c.sliding_power == 0.0 &&
                           c.load_slip == 0.0 && c.finnie_measure == 0.0 && c.impacts == 0.0 &&
                           std::all_of(c.block_normal.begin(), c.block_normal.end(), [](double v) { return v == 0.0; }) &&
                           std::all_of(c.block_load_slip.begin(), c.block_load_slip.end(), [](double v) { return v == 0.0; }) &&
                           std::all_of(c.block_finnie.begin(), c.block_finnie.end(), [](double v) { return v == 0.0; });
        if (empty) continue;
        o += fmt::format("gcell {} {} {} {} {} {} {} {} {} {}", b, flip ? 1 : 0, num(c.force.x()), num(c.force.y()),
                         num(c.force.z()), num(c.impact_power), num(c.sliding_power), num(c.load_slip),
                         num(c.finnie_measure), num(c.impacts));
        for (std::size_t k = 0; k < nb; ++k)
          o += fmt::format(" {} {} {}", num(c.block_normal[k]), num(c.block_load_slip[k]), num(c.block_finnie[k]));
        o += "\n";
      }
      continue;
    }
    for (const auto& c : m.cells) {
      o += "cell";
      for (const auto& p : c.corners) o += fmt::format(" {} {} {}", num(p.x()), num(p.y()), num(p.z()));
      o += fmt::format(" {} {} {} {} {} {} {} {} {} {} {} {}", num(c.normal.x()), num(c.normal.y()), num(c.normal.z()),
                       num(c.area), num(c.force.x()), num(c.force.y()), num(c.force.z()), num(c.impact_power),
                       num(c.sliding_power), num(c.load_slip), num(c.finnie_measure), num(c.impacts));
      o += fmt::format(" {}", c.block_normal.size());
      for (std::size_t b = 0; b < c.block_normal.size(); ++b)
        o += fmt::format(" {} {} {}", num(c.block_normal[b]), num(c.block_load_slip[b]), num(c.block_finnie[b]));
      o += "\n";
    }
  }
  for (const auto& n : r.notes) o += "note " + n + "\n";
  return o;
}

namespace {

// A line that cannot be read: what of it, and why (from_text adds the line number).
struct Bad {
  std::string field, problem;
};

// The tokens of one line after its tag, split at the single spaces the writer puts between them,
// each read in full or refused: a number never comes from part of a token, an empty one or a word.
class Fields {
 public:
  Fields(std::string_view tag, std::string_view rest) : tag_(tag) {
    for (std::size_t at = 0;;) {
      const std::size_t sp = rest.find(' ', at);
      tokens_.push_back(rest.substr(at, sp == std::string_view::npos ? std::string_view::npos : sp - at));
      if (sp == std::string_view::npos) break;
      at = sp + 1;
    }
  }
  std::size_t size() const { return tokens_.size(); }
  // The line has exactly `n` tokens (or `m`, a shorter older form).
  void expect(std::size_t n, std::size_t m = 0) const {
    if (size() != n && (m == 0 || size() != m))
      fail("", fmt::format("has {} fields, expected {}{}", size(), n, m ? fmt::format(" or {}", m) : ""));
  }
  [[noreturn]] void fail(std::string_view what, const std::string& problem) const {
    throw Bad{std::string(tag_), what.empty() ? problem : fmt::format("{}: {}", what, problem)};
  }
  std::string_view text(std::size_t i, std::string_view what) const {
    if (i >= tokens_.size() || tokens_[i].empty()) fail(what, "missing");
    return tokens_[i];
  }

  // A double as {:.17g} writes it: finite, or NaN where `nan_ok`; never inf.
  double real(std::size_t i, std::string_view what, bool nan_ok = false) const {
    const std::string_view t = text(i, what);
    double v = 0.0;
    const auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), v);
    if (end != t.data() + t.size() || (ec != std::errc() && ec != std::errc::result_out_of_range))
      fail(what, fmt::format("'{}' is not a number", t));
    if (ec == std::errc::result_out_of_range) v = subnormal(t, what);
    if (std::isinf(v) || (std::isnan(v) && !nan_ok)) fail(what, fmt::format("'{}' is not a finite number", t));
    return v;
  }
  double at_least(std::size_t i, std::string_view what, double low, bool nan_ok = false) const {
    const double v = real(i, what, nan_ok);
    if (v < low) fail(what, fmt::format("{} is below {}", tokens_[i], low));
    return v;
  }
  double positive(std::size_t i, std::string_view what) const {
    const double v = real(i, what);
    if (!(v > 0.0)) fail(what, fmt::format("{} is not positive", tokens_[i]));
    return v;
  }
  float single(std::size_t i, std::string_view what) const {
    const std::string_view t = text(i, what);
    float v = 0.0f;
    const auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), v);
    if (end != t.data() + t.size() || ec != std::errc() || !std::isfinite(v))
      fail(what, fmt::format("'{}' is not a finite number", t));
    return v;
  }
  long long whole(std::size_t i, std::string_view what, long long low, long long high) const {
    const std::string_view t = text(i, what);
    long long v = 0;
    const auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), v);
    if (end != t.data() + t.size() || ec != std::errc()) fail(what, fmt::format("'{}' is not a whole number", t));
    if (v < low || v > high) fail(what, fmt::format("{} is outside {}..{}", v, low, high));
    return v;
  }
  long long count(std::size_t i, std::string_view what) const {
    return whole(i, what, 0, std::numeric_limits<int>::max());
  }
  bool flag(std::size_t i, std::string_view what) const { return whole(i, what, 0, 1) == 1; }
  // A mean, its standard error and its count as the DEM makes them (steady_state.h): no values and
  // no mean (NaN) go together; a mean has a finite, non-negative error or none (NaN: too few blocks).
  Estimate estimate(std::size_t i, std::string_view what) const {
    Estimate e;
    e.value = real(i, what, true);
    e.se = at_least(i + 1, what, 0.0, true);
    e.n = static_cast<int>(count(i + 2, what));
    if ((e.n == 0) != std::isnan(e.value))
      fail(what, e.n == 0 ? fmt::format("a mean {} of no values", tokens_[i]) : fmt::format("no mean of {} values", e.n));
    if (std::isnan(e.value) && !std::isnan(e.se)) fail(what, "a standard error without a mean");
    return e;
  }

 private:
  // from_chars calls a subnormal out of range; the writer can write one.
  double subnormal(std::string_view t, std::string_view what) const {
    const std::string s(t);
    char* stop = nullptr;
    const double v = std::strtod(s.c_str(), &stop);
    if (stop != s.c_str() + s.size() || !std::isfinite(v) || std::abs(v) >= std::numeric_limits<double>::min())
      fail(what, fmt::format("'{}' is out of range", t));
    return v;
  }
  std::string_view tag_;
  std::vector<std::string_view> tokens_;
};

constexpr std::string_view kScalars[] = {"normal_force",   "shear_force",     "resultant_force",      "impact_point_y",
                                         "impact_velocity", "impact_velocity_fast", "exit_velocity", "layer_speed",
                                         "layer_height",   "stream_thickness", "mass_flux",           "momentum_balance"};

Estimate* scalar_of(StationResult& r, std::string_view n) {
  Estimate* all[] = {&r.normal_force,  &r.shear_force,      &r.resultant_force, &r.impact_point_y,
                     &r.impact_velocity, &r.impact_velocity_fast, &r.exit_velocity, &r.layer_speed,
                     &r.layer_height,  &r.stream_thickness, &r.mass_flux,       &r.momentum_balance};
  for (std::size_t k = 0; k < std::size(kScalars); ++k)
    if (kScalars[k] == n) return all[k];
  return nullptr;
}

// What the text held so far: the lines every entry has once, and where the series are.
struct Reading {
  std::set<std::string, std::less<>> once;
  std::optional<double> last_x, last_force_t, last_snap_t;
  long long last_gcell = -1;
};

void read_run(const Fields& f, StationResult& r) {
  // The rebuild count came later: entries written before it end the line there (read back as unknown).
  f.expect(11, 10);
  r.diameter = f.positive(0, "diameter");
  r.dt = f.positive(1, "dt");
  r.collision_time = f.at_least(2, "collision time", 0.0);
  r.rayleigh_time = f.at_least(3, "Rayleigh time", 0.0);
  r.simulated_time = f.at_least(4, "simulated time", 0.0);
  r.steps = f.whole(5, "steps", 0, std::numeric_limits<long long>::max());
  r.wall_seconds = f.at_least(6, "wall time", 0.0);
  r.early_stop = f.flag(7, "early stop");
  r.peak_particles = static_cast<std::size_t>(f.whole(8, "peak particles", 0, std::numeric_limits<long long>::max()));
  r.side_view_time = f.at_least(9, "side view time", 0.0);
  r.rebuilds = f.size() == 11 ? f.whole(10, "rebuilds", 0, std::numeric_limits<long long>::max()) : -1;
}

void read_window(const Fields& f, StationResult& r) {
  f.expect(4);
  r.window.found = f.flag(0, "found");
  r.window.start = f.real(1, "start");
  r.window.end = f.real(2, "end");
  r.window.blocks = static_cast<int>(f.count(3, "blocks"));
  if (r.window.start > r.window.end) f.fail("start", "after the end");
}

void read_restart(const Fields& f, StationResult& r) {
  f.expect(2);
  r.restart_time = f.at_least(0, "restart time", 0.0);
  r.transient_end = f.real(1, "transient end");
}

void read_mass(const Fields& f, StationResult& r) {
  f.expect(4);
  r.inserted = f.at_least(0, "inserted", 0.0);
  r.discharged = f.at_least(1, "discharged", 0.0);
  r.escaped = f.at_least(2, "escaped", 0.0);
  r.in_domain = f.at_least(3, "in domain", 0.0);
}

void read_scalar(const Fields& f, StationResult& r, Reading& seen) {
  f.expect(4);
  const std::string_view n = f.text(0, "name");
  Estimate* e = scalar_of(r, n);
  if (!e) f.fail("name", fmt::format("unknown quantity '{}'", n));
  if (!seen.once.insert("scalar " + std::string(n)).second) f.fail(n, "appears twice");
  *e = f.estimate(1, n);
}

// Series in time (or along x) go forward: a line moved or repeated is a damaged file.
void forward(const Fields& f, std::optional<double>& last, double now, std::string_view what) {
  if (last && !(now > *last)) f.fail(what, fmt::format("{:.17g} does not follow {:.17g}", now, *last));
  last = now;
}

void read_trajectory_row(const Fields& f, StationResult& r, Reading& seen) {
  f.expect(10);
  TrajectoryRow t;
  t.x = f.real(0, "x");
  forward(f, seen.last_x, t.x, "x");
  t.upper = f.estimate(1, "upper");
  t.lower = f.estimate(4, "lower");
  t.centre = f.estimate(7, "centre");
  r.trajectory.push_back(t);
}

void read_force_sample(const Fields& f, StationResult& r, Reading& seen) {
  f.expect(8);
  ForceSample s;
  s.t = f.at_least(0, "t", 0.0);
  forward(f, seen.last_force_t, s.t, "t");
  s.normal = f.real(1, "normal");
  s.shear = f.real(2, "shear");
  s.moment = f.real(3, "moment");
  s.mass_through = f.real(4, "mass through");
  s.momentum_in = f.real(5, "momentum in");
  s.momentum_floor = f.real(6, "momentum floor");
  s.momentum_content = f.real(7, "momentum content");
  r.forces.push_back(s);
}

void read_snapshot(const Fields& f, StationResult& r, Reading& seen) {
  f.expect(10);
  SnapshotStats s;
  s.t = f.at_least(0, "t", 0.0);
  forward(f, seen.last_snap_t, s.t, "t");
  s.particles = static_cast<std::size_t>(f.whole(1, "particles", 0, std::numeric_limits<long long>::max()));
  s.vp_sum = f.real(2, "V_p sum");
  s.vp_n = static_cast<int>(f.count(3, "V_p count"));
  s.vp_fast_sum = f.real(4, "fast V_p sum");
  s.vp_fast_n = static_cast<int>(f.count(5, "fast V_p count"));
  s.layer_speed_sum = f.real(6, "layer speed sum");
  s.layer_height_sum = f.real(7, "layer height sum");
  s.layer_n = static_cast<int>(f.count(8, "layer count"));
  s.stream_thickness = f.at_least(9, "stream thickness", 0.0, true);  // NaN: no particles in the window
  r.snapshots.push_back(s);
}

Vec3 read_vec3(const Fields& f, std::size_t i, std::string_view what) {
  const double x = f.real(i, what), y = f.real(i + 1, what), z = f.real(i + 2, what);  // in order
  return Vec3(x, y, z);
}

void read_map(const Fields& f, std::string_view rest, StationResult& r, Reading& seen) {
  PlateMap m;
  m.duration = f.at_least(0, "duration", 0.0);
  // The wall's name (an STL file) may hold spaces: the rest of the line.
  const std::size_t sp = rest.find(' ');
  if (sp == std::string_view::npos || sp + 1 == rest.size()) f.fail("wall", "missing");
  m.wall = std::string(rest.substr(sp + 1));
  r.maps.push_back(std::move(m));
  seen.last_gcell = -1;
}

// A grid map's geometry: its cells are rebuilt empty, and its gcell lines fill those with a contact.
void read_grid(const Fields& f, StationResult& r) {
  f.expect(14);
  if (r.maps.empty() || r.maps.back().grid || !r.maps.back().cells.empty()) f.fail("", "not right after a map line");
  MapGrid g;
  g.origin = read_vec3(f, 0, "origin");
  g.down = read_vec3(f, 3, "down");
  g.across = read_vec3(f, 6, "across");
  g.height = f.positive(9, "height");
  g.width = f.positive(10, "width");
  g.rows = static_cast<int>(f.whole(11, "rows", 1, 400));
  g.cols = static_cast<int>(f.whole(12, "columns", 1, 400));
  const auto nb = static_cast<std::size_t>(f.whole(13, "blocks", 0, 10000));
  PlateMap& m = r.maps.back();
  m.grid = g;
  for (const auto& t : g.triangles()) m.cells.push_back(empty_cell(t, false, nb));
}

// One grid cell with a contact: its two triangles' sums, cells in order.
void read_grid_cell(const Fields& f, StationResult& r, Reading& seen) {
  if (r.maps.empty() || !r.maps.back().grid) f.fail("", "not in a grid map");
  PlateMap& m = r.maps.back();
  const auto b = static_cast<std::size_t>(f.whole(0, "cell", 0, static_cast<long long>(m.cells.size() / 2) - 1));
  if (static_cast<long long>(b) <= seen.last_gcell) f.fail("cell", fmt::format("{} out of order", b));
  seen.last_gcell = static_cast<long long>(b);
  const std::size_t nb = m.cells[2 * b].block_normal.size();
  f.expect(10 + 3 * nb);
  const bool flip = f.flag(1, "flip");
  const Vec3 force = read_vec3(f, 2, "force");
  const double ip = f.at_least(5, "impact power", 0.0), sp = f.real(6, "sliding power"),
               ls = f.real(7, "load slip"), fm = f.at_least(8, "Finnie measure", 0.0),
               im = f.at_least(9, "impacts", 0.0);
  std::vector<double> bn(nb), bl(nb), bf(nb);
  for (std::size_t k = 0; k < nb; ++k) {
    bn[k] = f.real(10 + 3 * k, "block normal");
    bl[k] = f.real(11 + 3 * k, "block load slip");
    bf[k] = f.real(12 + 3 * k, "block Finnie");
  }
  for (std::size_t t = 2 * b; t < 2 * b + 2; ++t) {
    MapCell& c = m.cells[t];
    if (flip) c.normal = -c.normal;
    c.force = force;
    c.impact_power = ip; c.sliding_power = sp; c.load_slip = ls; c.finnie_measure = fm; c.impacts = im;
    c.block_normal = bn; c.block_load_slip = bl; c.block_finnie = bf;
  }
}

// One triangle of a map of any mesh, with its geometry.
void read_cell(const Fields& f, StationResult& r) {
  if (r.maps.empty() || r.maps.back().grid) f.fail("", "not in a mesh map");
  const auto nb = static_cast<std::size_t>(f.whole(21, "blocks", 0, 10000));
  f.expect(22 + 3 * nb);
  MapCell c;
  for (std::size_t k = 0; k < 3; ++k) c.corners[k] = read_vec3(f, 3 * k, "corner");
  c.normal = read_vec3(f, 9, "normal");
  c.area = f.at_least(12, "area", 0.0);
  c.force = read_vec3(f, 13, "force");
  c.impact_power = f.at_least(16, "impact power", 0.0);
  c.sliding_power = f.real(17, "sliding power");
  c.load_slip = f.real(18, "load slip");
  c.finnie_measure = f.at_least(19, "Finnie measure", 0.0);
  c.impacts = f.at_least(20, "impacts", 0.0);
  for (std::size_t b = 0; b < nb; ++b) {
    c.block_normal.push_back(f.real(22 + 3 * b, "block normal"));
    c.block_load_slip.push_back(f.real(23 + 3 * b, "block load slip"));
    c.block_finnie.push_back(f.real(24 + 3 * b, "block Finnie"));
  }
  r.maps.back().cells.push_back(std::move(c));
}

void read_side_point(const Fields& f, StationResult& r) {
  f.expect(4);
  r.side_view.push_back({f.single(0, "x"), f.single(1, "y"), f.single(2, "z"), f.single(3, "speed")});
}

// One line of the text into the result; throws Bad.
void read_line(std::string_view tag, std::string_view rest, StationResult& r, Reading& seen) {
  const Fields f(tag, rest);
  auto single = [&](const char* what) {
    if (!seen.once.insert(what).second) f.fail("", "appears twice");
  };
  auto words = [&](std::string& to) {
    if (rest.empty()) f.fail("", "is empty");
    to = std::string(rest);
  };
  if (tag == "condition") single("condition"), words(r.condition);
  else if (tag == "quality") single("quality"), words(r.quality);
  else if (tag == "shape") {
    single("shape"), words(r.shape);
    if (r.shape != "sphere" && r.shape != "clump") f.fail("", fmt::format("unknown shape '{}'", r.shape));
  } else if (tag == "note") r.notes.emplace_back(rest);
  else if (tag == "run") single("run"), read_run(f, r);
  else if (tag == "window") single("window"), read_window(f, r);
  else if (tag == "restart") single("restart"), read_restart(f, r);
  else if (tag == "mass") single("mass"), read_mass(f, r);
  else if (tag == "scalar") read_scalar(f, r, seen);
  else if (tag == "traj") read_trajectory_row(f, r, seen);
  else if (tag == "force") read_force_sample(f, r, seen);
  else if (tag == "snap") read_snapshot(f, r, seen);
  else if (tag == "map") read_map(f, rest, r, seen);
  else if (tag == "grid") read_grid(f, r);
  else if (tag == "gcell") read_grid_cell(f, r, seen);
  else if (tag == "cell") read_cell(f, r);
  else if (tag == "side") read_side_point(f, r);
  else throw Bad{std::string(tag), "unknown line"};
}

}  // namespace

std::optional<StationResult> from_text(const std::string& text, TextProblem* why) {
  StationResult r;
  Reading seen;
  long line_no = 0;
  auto refuse = [&](long line, std::string field, std::string problem) -> std::optional<StationResult> {
    if (why) *why = {line, std::move(field), std::move(problem)};
    return std::nullopt;
  };
  std::size_t at = 0;
  while (at < text.size()) {
    ++line_no;
    const std::size_t nl = text.find('\n', at);
    if (nl == std::string::npos) return refuse(line_no, "", "the last line does not end: the text is cut short");
    const std::string_view line(text.data() + at, nl - at);
    at = nl + 1;
    const std::size_t sp = line.find(' ');
    const std::string_view tag = line.substr(0, sp);
    const std::string_view rest = sp == std::string_view::npos ? std::string_view() : line.substr(sp + 1);
    try {
      read_line(tag, rest, r, seen);
    } catch (const Bad& b) {
      return refuse(line_no, b.field, b.problem);
    }
  }
  for (const char* required : {"condition", "quality", "run", "window", "mass"})
    if (!seen.once.count(required)) return refuse(0, required, "the line is missing");
  for (std::string_view s : kScalars)
    if (!seen.once.count("scalar " + std::string(s))) return refuse(0, "scalar", fmt::format("{} is missing", s));
  return r;
}

std::string CacheEntry::said() const {
  if (!refused) return {};
  std::string s = file;
  if (refused->line > 0) s += fmt::format(":{}", refused->line);
  if (!refused->field.empty()) s += ": " + refused->field;
  return s + ": " + refused->problem;
}

ResultCache::ResultCache(std::string dir) : dir_(std::move(dir)) {}

std::string ResultCache::default_dir() {
  namespace fs = std::filesystem;
  if (const char* c = std::getenv("CHUTELAB_DEM_CACHE"); c && *c) return c;
  if (const char* x = std::getenv("XDG_CACHE_HOME"); x && *x) return (fs::path(x) / "chutelab" / "dem").string();
  if (const char* h = std::getenv("HOME"); h && *h) return (fs::path(h) / ".cache" / "chutelab" / "dem").string();
  return (fs::temp_directory_path() / "chutelab-dem-cache").string();
}

std::string ResultCache::path_for(const std::string& key) const {
  return (std::filesystem::path(dir_) / fmt::format("{:016x}.txt", fnv1a64(key))).string();
}

namespace {

// The whole of a regular file, or why not. Opened without blocking, so a FIFO or a device put where
// an entry belongs is refused at once instead of waiting for a writer that never comes.
std::optional<std::string> read_regular(const std::string& path, std::optional<TextProblem>& refused) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY);
  if (fd < 0) {
    if (errno != ENOENT && errno != ENOTDIR) refused = TextProblem{0, "", fmt::format("cannot be read: {}", std::strerror(errno))};
    return std::nullopt;
  }
  struct Closer {
    int fd;
    ~Closer() { ::close(fd); }
  } closer{fd};
  struct stat st {};
  if (::fstat(fd, &st) != 0) {
    refused = TextProblem{0, "", fmt::format("cannot be read: {}", std::strerror(errno))};
    return std::nullopt;
  }
  if (!S_ISREG(st.st_mode)) {
    refused = TextProblem{0, "", S_ISDIR(st.st_mode) ? "is a folder, not a cache entry"
                                 : S_ISFIFO(st.st_mode) ? "is a FIFO, not a cache entry (not opened for reading)"
                                                        : "is not a regular file (a device or a socket): not read"};
    return std::nullopt;
  }
  if (static_cast<unsigned long long>(st.st_size) > kMaxEntryBytes) {
    refused = TextProblem{0, "", fmt::format("is {} bytes, more than any DEM result ({} at most)", st.st_size, kMaxEntryBytes)};
    return std::nullopt;
  }
  std::string text(static_cast<std::size_t>(st.st_size), '\0');
  std::size_t got = 0;
  while (got < text.size()) {
    const ssize_t n = ::read(fd, text.data() + got, text.size() - got);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) {
      refused = TextProblem{0, "", fmt::format("cannot be read: {}", std::strerror(errno))};
      return std::nullopt;
    }
    if (n == 0) break;
    got += static_cast<std::size_t>(n);
  }
  // A file that changed size while read (another writer replaces entries by rename, never in place).
  char more = 0;
  if (got != text.size() || ::read(fd, &more, 1) > 0) {
    refused = TextProblem{0, "", "changed while it was read"};
    return std::nullopt;
  }
  return text;
}

long lines_in(std::string_view s) { return static_cast<long>(std::count(s.begin(), s.end(), '\n')); }

}  // namespace

CacheEntry ResultCache::lookup(const std::string& key) const {
  CacheEntry e;
  e.file = path_for(key);
  const std::optional<std::string> read = read_regular(e.file, e.refused);
  if (!read) return e;
  const std::string& text = *read;
  auto refuse = [&](long line, std::string field, std::string problem) {
    e.refused = TextProblem{line, std::move(field), std::move(problem)};
    return e;
  };
  // Layout: magic line, "key <bytes>" line, the key, the result's lines, then the end line.
  const std::size_t nl1 = text.find('\n');
  const std::string_view magic(text.data(), nl1 == std::string::npos ? text.size() : nl1);
  if (!magic.starts_with(kMagicPrefix)) return refuse(1, "", "not a DEM cache entry");
  const bool v5 = magic == kMagicV5;
  if (magic != kMagic && !v5)
    return refuse(1, "", fmt::format("format {} is not read by this chutelab (it reads {} and {})",
                                     magic.substr(std::string_view(kMagicPrefix).size()), kFormat, kFormatV5));
  // Where the end line starts, and for format 6 the check sum of everything before it.
  std::size_t body_end = 0;
  if (v5) {
    if (!text.ends_with(kEndV5)) return refuse(0, "end", "the end line is missing: the file is cut short");
    body_end = text.size() - std::string_view(kEndV5).size() + 1;
  } else {
    const std::size_t last = text.size() < 2 || text.back() != '\n' ? std::string::npos : text.rfind('\n', text.size() - 2);
    if (last == std::string::npos || !std::string_view(text).substr(last + 1).starts_with("end "))
      return refuse(0, "end", "the end line is missing: the file is cut short");
    body_end = last + 1;
  }
  const std::size_t nl2 = nl1 == std::string::npos ? std::string::npos : text.find('\n', nl1 + 1);
  if (nl2 == std::string::npos || nl2 > body_end) return refuse(2, "key", "the key line is missing");
  const std::string_view head(text.data() + nl1 + 1, nl2 - nl1 - 1);
  std::size_t bytes = 0;
  const auto [stop, ec] = std::from_chars(head.data() + std::min<std::size_t>(4, head.size()), head.data() + head.size(), bytes);
  if (!head.starts_with("key ") || ec != std::errc() || stop != head.data() + head.size() || head.size() == 4)
    return refuse(2, "key", "not a key length");
  const std::size_t at = nl2 + 1;
  if (bytes > body_end - at) return refuse(2, "key", "the key is longer than the file");
  // Another key's entry (a stale file, or another key with the same hash): a plain miss.
  if (text.compare(at, bytes, key) != 0) return e;
  TextProblem why;
  auto r = from_text(text.substr(at + bytes, body_end - at - bytes), &why);
  if (!r) {
    const long offset = lines_in(std::string_view(text.data(), at + bytes));
    return refuse(why.line > 0 ? why.line + offset : 0, why.field, why.problem);
  }
  // Every line read, in range: the sum says whether they are the lines that were written.
  if (!v5) {
    const std::string_view end_line(text.data() + body_end, text.size() - body_end - 1);
    if (end_line != fmt::format("end {:016x}", fnv1a64(std::string_view(text.data(), body_end))))
      return refuse(lines_in(std::string_view(text.data(), body_end)) + 1, "end",
                    "the check sum does not match: the file was changed or damaged after it was written");
  }
  e.result = std::move(r);
  return e;
}

CacheWrite ResultCache::store(const std::string& key, const StationResult& r) const {
  namespace fs = std::filesystem;
  std::error_code ec;
  fs::create_directories(dir_, ec);
  if (ec) return {false, fmt::format("cannot make the cache folder {}: {}", dir_, ec.message())};
  const std::string path = path_for(key);
  // A name no other writer uses, even ranks of one job on other hosts sharing the folder (host, pid,
  // thread, a counter), then an atomic rename: a reader sees the old file or the new one, whole.
  static std::atomic<unsigned> counter{0};
  char host[256] = "host";
  ::gethostname(host, sizeof host - 1);
  const std::string tmp = path + fmt::format(".{}.{}.{:x}.{}.tmp", host, static_cast<long>(::getpid()),
                                             std::hash<std::thread::id>{}(std::this_thread::get_id()), counter++);
  sweep_dead_temporaries(host);
  // A signal while it is written removes it (core/output_folder.h); a SIGKILL's is swept above by
  // the next store on this host.
  register_temporary(tmp);
  struct Unregister {
    std::string p;
    ~Unregister() { unregister_temporary(p); }
  } unregister{tmp};
  // Never an entry the reader would refuse (it would be run again every time): the text is checked first.
  const std::string body = to_text(r);
  if (TextProblem why; !from_text(body, &why))
    return {false, fmt::format("the result does not pass the cache's own check (line {}, {}: {})", why.line, why.field,
                               why.problem)};
  std::string text = fmt::format("{}\nkey {}\n", kMagic, key.size());
  text += key;
  text += body;
  text += fmt::format("end {:016x}\n", fnv1a64(text));
  const auto failed = [&](const std::string& what) {
    const std::string why = fmt::format("cannot write {}: {}", path, what);
    fs::remove(tmp, ec);
    return CacheWrite{false, why};
  };
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
  if (fd < 0) return failed(std::strerror(errno));
  for (std::size_t done = 0; done < text.size();) {
    const ssize_t n = ::write(fd, text.data() + done, text.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      const std::string why = n < 0 ? std::strerror(errno) : "nothing written";
      ::close(fd);
      return failed(why);
    }
    done += static_cast<std::size_t>(n);
  }
  // On the disk before the rename: a full disk or a failing one shows here, not as a short entry later.
  if (::fsync(fd) != 0) {
    const std::string why = std::strerror(errno);
    ::close(fd);
    return failed(why);
  }
  if (::close(fd) != 0) return failed(std::strerror(errno));
  fs::rename(tmp, path, ec);
  if (ec) return failed(ec.message());
  return {true, {}};
}

void ResultCache::sweep_dead_temporaries(const std::string& host) const {
  // NAME.txt.HOST.PID.THREAD.N.tmp of a process of this host that is gone: its write never finished.
  namespace fs = std::filesystem;
  std::error_code ec;
  const std::string mark = ".txt." + host + ".";
  std::vector<fs::path> dead;
  for (fs::directory_iterator it(dir_, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string n = it->path().filename().string();
    const auto at = n.find(mark);
    if (at == std::string::npos || !n.ends_with(".tmp")) continue;
    const std::string rest = n.substr(at + mark.size());
    char* stop = nullptr;
    const long pid = std::strtol(rest.c_str(), &stop, 10);
    if (stop == rest.c_str() || *stop != '.' || pid <= 0 || pid == static_cast<long>(::getpid())) continue;
    if (::kill(static_cast<pid_t>(pid), 0) != 0 && errno == ESRCH) dead.push_back(it->path());
  }
  for (const auto& p : dead) fs::remove(p, ec);
}

}  // namespace chutelab::dem::station
