#include "dem/station/cache.h"

#include <algorithm>
#include <atomic>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <thread>
#include <unistd.h>
#include <csignal>
#include <cerrno>
#include <vector>
#include <fstream>
#include <sstream>
#include <string_view>

#include <fmt/format.h>

#include "core/output_folder.h"

namespace chutelab::dem::station {
namespace {

// Version 5 ends with an "end" line, so a file cut short (a writer that died, a file system that
// shows a rename before the data) is a miss, not a result with half its series, and carries the
// plate maps with their block means. Version 2 files (no end line, no maps, written by an atomic
// rename only) are still read: a standard or paper run is too dear to repeat for a picture
// (--no-dem-cache does). Any other version is a miss.
constexpr const char* kMagic = "chutelab-dem-result 5";
constexpr const char* kMagicV2 = "chutelab-dem-result 2";
constexpr const char* kEnd = "end\n";

std::string num(double v) { return fmt::format("{:.17g}", v); }

void put(std::string& o, const char* name, const Estimate& e) {
  o += fmt::format("scalar {} {} {} {}\n", name, num(e.value), num(e.se), e.n);
}

bool read_estimate(std::istringstream& in, Estimate& e) {
  std::string v, s;
  in >> v >> s >> e.n;
  if (!in) return false;
  e.value = std::strtod(v.c_str(), nullptr);
  e.se = std::strtod(s.c_str(), nullptr);
  return true;
}

double rd(std::istringstream& in) {
  std::string v;
  in >> v;
  return std::strtod(v.c_str(), nullptr);
}

}  // namespace

std::uint64_t fnv1a64(const std::string& s) {
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

// The readers of from_text, one per line tag: each reads the rest of its line into the result and
// returns false when the line cannot be read (the entry is then a miss).
using LineReader = bool (*)(std::istringstream& in, const std::string& rest, StationResult& r);

bool read_run(std::istringstream& in, const std::string&, StationResult& r) {
  int early = 0;
  r.diameter = rd(in); r.dt = rd(in); r.collision_time = rd(in); r.rayleigh_time = rd(in);
  r.simulated_time = rd(in);
  in >> r.steps;
  r.wall_seconds = rd(in);
  in >> early >> r.peak_particles;
  r.side_view_time = rd(in);
  r.early_stop = early != 0;
  if (!(in >> r.rebuilds)) r.rebuilds = -1;
  return true;
}

bool read_window(std::istringstream& in, const std::string&, StationResult& r) {
  int found = 0;
  in >> found;
  r.window.start = rd(in); r.window.end = rd(in);
  in >> r.window.blocks;
  r.window.found = found != 0;
  return true;
}

bool read_restart(std::istringstream& in, const std::string&, StationResult& r) {
  r.restart_time = rd(in);
  r.transient_end = rd(in);
  return true;
}

bool read_mass(std::istringstream& in, const std::string&, StationResult& r) {
  r.inserted = rd(in); r.discharged = rd(in); r.escaped = rd(in); r.in_domain = rd(in);
  return true;
}

bool read_scalar(std::istringstream& in, const std::string&, StationResult& r) {
  std::string n;
  in >> n;
  Estimate* e = n == "normal_force" ? &r.normal_force : n == "shear_force" ? &r.shear_force
              : n == "resultant_force" ? &r.resultant_force : n == "impact_point_y" ? &r.impact_point_y
              : n == "impact_velocity" ? &r.impact_velocity : n == "impact_velocity_fast" ? &r.impact_velocity_fast
              : n == "exit_velocity" ? &r.exit_velocity : n == "layer_speed" ? &r.layer_speed
              : n == "stream_thickness" ? &r.stream_thickness : n == "mass_flux" ? &r.mass_flux
              : n == "layer_height" ? &r.layer_height : n == "momentum_balance" ? &r.momentum_balance
              : nullptr;
  return e && read_estimate(in, *e);
}

bool read_trajectory_row(std::istringstream& in, const std::string&, StationResult& r) {
  TrajectoryRow t;
  t.x = rd(in);
  if (!read_estimate(in, t.upper) || !read_estimate(in, t.lower) || !read_estimate(in, t.centre)) return false;
  r.trajectory.push_back(t);
  return true;
}

bool read_force_sample(std::istringstream& in, const std::string&, StationResult& r) {
  ForceSample f;
  f.t = rd(in); f.normal = rd(in); f.shear = rd(in); f.moment = rd(in);
  f.mass_through = rd(in); f.momentum_in = rd(in); f.momentum_floor = rd(in); f.momentum_content = rd(in);
  r.forces.push_back(f);
  return true;
}

bool read_snapshot(std::istringstream& in, const std::string&, StationResult& r) {
  SnapshotStats s;
  s.t = rd(in);
  in >> s.particles;
  s.vp_sum = rd(in);
  in >> s.vp_n;
  s.vp_fast_sum = rd(in);
  in >> s.vp_fast_n;
  s.layer_speed_sum = rd(in);
  s.layer_height_sum = rd(in);
  in >> s.layer_n;
  s.stream_thickness = rd(in);
  if (!in) return false;
  r.snapshots.push_back(s);
  return true;
}

Vec3 read_vec3(std::istringstream& in) {
  const double x = rd(in), y = rd(in), z = rd(in);  // in order: function arguments are evaluated in no fixed order
  return Vec3(x, y, z);
}

bool read_map(std::istringstream& in, const std::string&, StationResult& r) {
  PlateMap m;
  m.duration = rd(in);
  in >> std::ws;
  std::getline(in, m.wall);
  r.maps.push_back(std::move(m));
  return true;
}

// A grid map's geometry: its cells are rebuilt empty, and its gcell lines fill those with a contact.
bool read_grid(std::istringstream& in, const std::string&, StationResult& r) {
  if (r.maps.empty()) return false;
  MapGrid g;
  g.origin = read_vec3(in);
  g.down = read_vec3(in);
  g.across = read_vec3(in);
  g.height = rd(in);
  g.width = rd(in);
  std::size_t nb = 0;
  in >> g.rows >> g.cols >> nb;
  if (!in || g.rows < 1 || g.cols < 1 || g.rows > 400 || g.cols > 400 || nb > 10000) return false;
  PlateMap& m = r.maps.back();
  m.grid = g;
  for (const auto& t : g.triangles()) m.cells.push_back(empty_cell(t, false, nb));
  return true;
}

// One grid cell with a contact: its two triangles' sums.
bool read_grid_cell(std::istringstream& in, const std::string&, StationResult& r) {
  if (r.maps.empty() || !r.maps.back().grid) return false;
  PlateMap& m = r.maps.back();
  std::size_t b = 0;
  int flip = 0;
  in >> b >> flip;
  if (!in || 2 * b + 1 >= m.cells.size()) return false;
  const double fx = rd(in), fy = rd(in), fz = rd(in);
  const double ip = rd(in), sp = rd(in), ls = rd(in), fm = rd(in), im = rd(in);
  const std::size_t nb = m.cells[2 * b].block_normal.size();
  std::vector<double> bn(nb), bl(nb), bf(nb);
  for (std::size_t k = 0; k < nb; ++k) bn[k] = rd(in), bl[k] = rd(in), bf[k] = rd(in);
  if (!in) return false;
  for (std::size_t t = 2 * b; t < 2 * b + 2; ++t) {
    MapCell& c = m.cells[t];
    if (flip) c.normal = -c.normal;
    c.force = Vec3(fx, fy, fz);
    c.impact_power = ip; c.sliding_power = sp; c.load_slip = ls; c.finnie_measure = fm; c.impacts = im;
    c.block_normal = bn; c.block_load_slip = bl; c.block_finnie = bf;
  }
  return true;
}

// One triangle of a map of any mesh, with its geometry.
bool read_cell(std::istringstream& in, const std::string&, StationResult& r) {
  if (r.maps.empty()) return false;
  MapCell c;
  for (auto& p : c.corners) p = read_vec3(in);
  c.normal = read_vec3(in);
  c.area = rd(in);
  c.force = read_vec3(in);
  c.impact_power = rd(in); c.sliding_power = rd(in); c.load_slip = rd(in); c.finnie_measure = rd(in);
  c.impacts = rd(in);
  std::size_t nb = 0;
  in >> nb;
  if (!in || nb > 10000) return false;
  for (std::size_t b = 0; b < nb; ++b) {
    const double fn = rd(in), ls = rd(in), fi = rd(in);
    c.block_normal.push_back(fn);
    c.block_load_slip.push_back(ls);
    c.block_finnie.push_back(fi);
  }
  if (!in) return false;
  r.maps.back().cells.push_back(c);
  return true;
}

bool read_side_point(std::istringstream& in, const std::string&, StationResult& r) {
  SidePoint p{};
  in >> p.x >> p.y >> p.z >> p.speed;
  if (!in) return false;
  r.side_view.push_back(p);
  return true;
}

struct TaggedReader {
  std::string_view tag;
  LineReader read;
};

constexpr TaggedReader kReaders[] = {
    {"condition", [](std::istringstream&, const std::string& rest, StationResult& r) { r.condition = rest; return true; }},
    {"quality", [](std::istringstream&, const std::string& rest, StationResult& r) { r.quality = rest; return true; }},
    {"shape", [](std::istringstream&, const std::string& rest, StationResult& r) { r.shape = rest; return true; }},
    {"note", [](std::istringstream&, const std::string& rest, StationResult& r) { r.notes.push_back(rest); return true; }},
    {"run", read_run},
    {"window", read_window},
    {"restart", read_restart},
    {"mass", read_mass},
    {"scalar", read_scalar},
    {"traj", read_trajectory_row},
    {"force", read_force_sample},
    {"snap", read_snapshot},
    {"map", read_map},
    {"grid", read_grid},
    {"gcell", read_grid_cell},
    {"cell", read_cell},
    {"side", read_side_point},
};

}  // namespace

std::optional<StationResult> from_text(const std::string& text) {
  StationResult r;
  std::istringstream all(text);
  std::string line;
  while (std::getline(all, line)) {
    if (line.empty()) continue;
    const auto sp = line.find(' ');
    const std::string tag = line.substr(0, sp);
    const std::string rest = sp == std::string::npos ? std::string() : line.substr(sp + 1);
    const auto reader = std::find_if(std::begin(kReaders), std::end(kReaders),
                                     [&](const TaggedReader& t) { return t.tag == tag; });
    if (reader == std::end(kReaders)) return std::nullopt;  // a file of another version: a miss
    std::istringstream in(rest);
    if (!reader->read(in, rest, r)) return std::nullopt;
  }
  return r;
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

std::optional<StationResult> ResultCache::load(const std::string& key) const {
  std::ifstream f(path_for(key));
  if (!f) return std::nullopt;
  std::stringstream ss;
  ss << f.rdbuf();
  const std::string text = ss.str();
  // Layout: magic line, "key <bytes>" line, the key, then the result.
  std::istringstream in(text);
  std::string magic, head;
  if (!std::getline(in, magic) || (magic != kMagic && magic != kMagicV2) || !std::getline(in, head) ||
      head.rfind("key ", 0) != 0)
    return std::nullopt;
  const std::size_t bytes = std::strtoull(head.c_str() + 4, nullptr, 10);
  const std::size_t at = static_cast<std::size_t>(in.tellg());
  if (at + bytes > text.size() || text.compare(at, bytes, key) != 0) return std::nullopt;
  std::size_t body_end = text.size();
  if (magic == kMagic) {
    const std::size_t end_len = std::char_traits<char>::length(kEnd);
    if (text.size() < at + bytes + end_len || text.compare(text.size() - end_len, end_len, kEnd) != 0) return std::nullopt;
    body_end -= end_len;
  }
  return from_text(text.substr(at + bytes, body_end - at - bytes));
}

bool ResultCache::store(const std::string& key, const StationResult& r) const {
  namespace fs = std::filesystem;
  std::error_code ec;
  fs::create_directories(dir_, ec);
  if (ec) return false;
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
  {
    std::ofstream f(tmp, std::ios::binary);
    if (!f) return false;
    f << kMagic << "\nkey " << key.size() << "\n" << key << to_text(r) << kEnd;
    f.close();
    if (!f) {
      fs::remove(tmp, ec);
      return false;
    }
  }
  fs::rename(tmp, path, ec);
  if (!ec) return true;
  fs::remove(tmp, ec);
  return false;
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
