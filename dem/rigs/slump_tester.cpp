#include "dem/rigs/slump_tester.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>

#include <fmt/format.h>

#include "core/input_error.h"
#include "dem/insertion.h"

namespace chutelab::dem::rigs {
namespace {

constexpr double pi = std::numbers::pi;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Half of a cylinder surface, radius r, axis z through (0, 0), z from z0 to z1, covering the polar
// angles [a0, a1]; `segments` facets.
TriangleMesh half_tube(double r, double z0, double z1, double a0, double a1, int segments) {
  std::vector<std::array<Vec3, 3>> soup;
  for (int k = 0; k < segments; ++k) {
    const double p = a0 + (a1 - a0) * k / segments, q = a0 + (a1 - a0) * (k + 1) / segments;
    const Vec3 b0(r * std::cos(p), r * std::sin(p), z0), b1(r * std::cos(q), r * std::sin(q), z0);
    const Vec3 t0(b0.x(), b0.y(), z1), t1(b1.x(), b1.y(), z1);
    soup.push_back({b0, b1, t1});
    soup.push_back({b0, t1, t0});
  }
  return TriangleMesh::from_soup(soup, "slump tube half");
}

// Highest grain top (centre z + radius) in each cell of a square grid of side `cell`, for sample
// spheres satisfying `use`. Key: (ix, iy).
std::map<std::pair<int, int>, double> surface_cells(const Particles& p, double cell,
                                                   const std::function<bool(std::size_t)>& use) {
  std::map<std::pair<int, int>, double> top;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (!use(i)) continue;
    const std::pair<int, int> key{static_cast<int>(std::floor(p.x[i].x() / cell)),
                                  static_cast<int>(std::floor(p.x[i].y() / cell))};
    const double z = p.x[i].z() + p.radius[i];
    auto it = top.find(key);
    if (it == top.end())
      top.emplace(key, z);
    else
      it->second = std::max(it->second, z);
  }
  return top;
}

Vec3 cell_centre(const std::pair<int, int>& k, double cell) {
  return Vec3((k.first + 0.5) * cell, (k.second + 0.5) * cell, 0.0);
}

// The rig (reference study Fig. 5) for a grain: the split tube over the pipe that holds the glued
// bed, and the jittered lattice the sample is placed on.
struct RigLayout {
  double d = 0.0;           // grain diameter
  double rt = 0.0, rp = 0.0;  // tube and pipe radius
  double z_bed = 0.0;       // crests of the glued bed (centres at d/2)
  double z_tube = 0.0;      // the tube's bottom edge, just clear of the crests
  double pitch = 0.0;       // of the sample's lattice
  std::vector<std::pair<double, double>> layer;  // one lattice layer's (x, y)
  std::size_t n_sample = 0, layers = 0;
  double column_top = 0.0, tube_top = 0.0;
};

constexpr double g_acc = 9.80665;

// Sample size: a loose random packing guess of solid fraction 0.58 fills the aimed height.
RigLayout lay_out_rig(const Grain& g, const SlumpSettings& s) {
  RigLayout L;
  L.d = g.diameter;
  L.rt = 0.5 * s.tube_diameter;
  L.rp = 0.5 * s.pipe_diameter;
  L.z_bed = L.d;
  L.z_tube = L.z_bed + 0.02 * L.d;
  L.n_sample = static_cast<std::size_t>(std::llround(0.58 * pi * L.rt * L.rt * s.fill_height / g.volume()));
  L.pitch = 2.0 * g.bounding_radius() * 1.12;
  const double r_lattice = L.rt - 0.6 * L.pitch;
  for (double x = -r_lattice; x <= r_lattice + 1e-12; x += L.pitch)
    for (double y = -r_lattice; y <= r_lattice + 1e-12; y += L.pitch)
      if (std::hypot(x, y) <= r_lattice) L.layer.emplace_back(x, y);
  L.layers = (L.n_sample + L.layer.size() - 1) / L.layer.size();
  L.column_top = L.z_tube + 0.6 * L.pitch + static_cast<double>(L.layers) * L.pitch;
  L.tube_top = L.column_top + 2.0 * L.d;
  return L;
}

Settings rig_settings(const RigLayout& L, const SlumpSettings& s) {
  Settings st;
  st.gravity = Vec3(0, 0, -g_acc);
  st.rolling = s.rolling;
  st.threads = s.threads;
  st.domain = Box{Vec3(-0.4, -0.4, -0.05), Vec3(0.4, 0.4, L.tube_top + 0.1)};
  st.characteristic_speed = std::max(1.0, std::sqrt(2.0 * g_acc * (L.column_top - L.z_bed)));
  st.skin = 0.25 * L.d;
  st.on_warning = [](const std::string&) {};
  return st;
}

// The bed: a glued hexagonal layer over the pipe, the first particles (ids 0 .. n-1). Returns n.
std::size_t add_glued_bed(World& w, const RigLayout& L, int material, double density) {
  const double d = L.d, rp = L.rp, bed_r = 0.5 * d;
  std::size_t n_bed = 0;
  for (int row = -static_cast<int>(rp / (d * 0.866)) - 1; row * d * 0.866 <= rp + d; ++row) {
    const double y = row * d * std::sqrt(3.0) / 2.0;
    const double shift = (row % 2 != 0) ? 0.5 * d : 0.0;
    for (double x = -rp - d + shift; x <= rp + d; x += d) {
      if (std::hypot(x, y) > rp - bed_r) continue;
      ParticleSpec ps;
      ps.position = Vec3(x, y, bed_r);
      ps.radius = bed_r;
      ps.material = material;
      ps.density = density;
      w.add_particle(ps);
      ++n_bed;
    }
  }
  Particles& p = w.particles();
  for (std::size_t i = 0; i < p.size(); ++i) {
    p.inv_mass[i] = 0.0;  // glued: infinite mass and inertia, never moves
    p.inv_inertia[i] = 0.0;
    p.contact_mass[i] = 1e6 * p.mass[i];  // a grain hitting it meets a fixed body, as at a wall (m* = m)
  }
  return n_bed;
}

// The sample: a jittered lattice in the tube, each grain turned at random. Returns the grains placed.
std::size_t fill_tube(World& w, const RigLayout& L, const Grain& g, const SlumpSettings& s, int material,
                      double density) {
  std::uint64_t rng = s.seed * 0x9e3779b97f4a7c15ULL + 12345;
  std::size_t placed = 0;
  for (std::size_t k = 0; k < L.layers && placed < L.n_sample; ++k)
    for (const auto& [x, y] : L.layer) {
      if (placed == L.n_sample) break;
      const Vec3 jitter = 0.05 * L.pitch * Vec3(uniform01(rng) - 0.5, uniform01(rng) - 0.5, uniform01(rng) - 0.5);
      const Vec3 pos = Vec3(x, y, L.z_tube + 0.6 * L.pitch + static_cast<double>(k) * L.pitch) + jitter;
      // A uniformly random orientation (Shoemake's method) from our own seeded generator.
      const double u1 = uniform01(rng), u2 = 2 * pi * uniform01(rng), u3 = 2 * pi * uniform01(rng);
      const Quat qr(std::sqrt(1 - u1) * std::sin(u2), std::sqrt(1 - u1) * std::cos(u2), std::sqrt(u1) * std::sin(u3),
                    std::sqrt(u1) * std::cos(u3));
      add_grain(w, g, pos, qr, material, density);
      ++placed;
    }
  return placed;
}

// The run's phases: steps in chunks of about 0.01 s until no sample grain moves faster than the
// settle speed (after t_min) or t_max has passed.
class Phases {
 public:
  Phases(World& w, std::int64_t bed_ids, const SlumpSettings& s, const std::function<void(const SlumpProgress&)>& progress)
      : w_(w), bed_ids_(bed_ids), settle_speed_(s.settle_speed), progress_(progress),
        check_every_(std::max<std::int64_t>(1, std::llround(0.01 / w.dt()))) {}

  bool is_sample(std::size_t i) const { return w_.particles().id[i] >= bed_ids_; }

  // Returns the phase's duration and whether it settled.
  std::pair<double, bool> run(const std::string& phase, double t_min, double t_max, const std::function<void()>& each) {
    const double t0 = w_.time();
    double last_report = -1.0;
    for (;;) {
      w_.step(check_every_);
      if (each) each();
      const double el = w_.time() - t0;
      if (progress_ && el - last_report >= 0.05) {
        progress_({phase, el, t_max});
        last_report = el;
      }
      if (el >= t_min && max_speed() < settle_speed_) return std::make_pair(el, true);
      if (el >= t_max) return std::make_pair(el, false);
    }
  }

 private:
  double max_speed() const {
    double v2 = 0.0;
    const Particles& p = w_.particles();
    for (std::size_t i = 0; i < p.size(); ++i)
      if (is_sample(i)) v2 = std::max(v2, p.v[i].squaredNorm());
    return std::sqrt(v2);
  }

  World& w_;
  std::int64_t bed_ids_;
  double settle_speed_;
  const std::function<void(const SlumpProgress&)>& progress_;
  std::int64_t check_every_;
};

// The loose-poured bulk density, fill height and surface height. The poured surface is rough on the
// scale of a grain, so "the level" is defined as a dividing surface: the bulk density is that of the
// core of the column (mass per volume in the tube cross-section between one grain above the tube's
// bottom edge and 1.5 grains below the mean top surface, wall layer included as in the lab tube),
// and the fill height is the height the whole sample would fill at that density. Sphere slabs are
// weighted by each sphere's mass share / its own volume, so overlapping clump spheres are not
// counted twice.
void measure_poured(const World& w, const Phases& phases, const RigLayout& L, const SlumpSettings& s,
                    SlumpResult& res) {
  const Particles& p = w.particles();
  const double d = L.d, rt = L.rt, z_tube = L.z_tube;
  const double cell = 1.5 * d;
  auto in_tube = [&](std::size_t i) { return phases.is_sample(i) && std::hypot(p.x[i].x(), p.x[i].y()) < rt; };
  const auto top = surface_cells(p, cell, in_tube);
  double sum = 0.0;
  int n = 0;
  for (const auto& [k, z] : top)
    if (cell_centre(k, cell).norm() < rt - 0.75 * cell) {
      sum += z;
      ++n;
    }
  const double top_mean = n > 0 ? sum / n : z_tube + s.fill_height;
  const double z_lo = z_tube + d;
  const double z_hi = std::max(top_mean - 1.5 * d, z_lo + d);
  auto slab_mass = [&](std::size_t i, double a, double b) {
    const double r = p.radius[i], c = p.x[i].z();
    const double lo = std::max(a, c - r) - c, hi = std::min(b, c + r) - c;
    if (hi <= lo) return 0.0;
    const double vol = pi * (r * r * (hi - lo) - (hi * hi * hi - lo * lo * lo) / 3.0);
    return p.mass[i] * vol / (4.0 / 3.0 * pi * r * r * r);
  };
  double core = 0.0, above = 0.0, mass = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (!in_tube(i)) continue;
    mass += p.mass[i];
    core += slab_mass(i, z_lo, z_hi);
    above += slab_mass(i, z_tube, 1e9);
  }
  const double area = pi * rt * rt;
  res.sample_mass = mass;
  res.bulk_density = core / (area * (z_hi - z_lo));
  res.fill_height = above / (area * res.bulk_density);
  res.surface_height = top_mean - z_tube;
}

// The tube's opening: its halves move apart, and are parked (static, where they are) once clear of
// the pipe.
class TubeOpening {
 public:
  TubeOpening(World& w, std::array<int, 2> halves, const RigLayout& L, double open_speed)
      : w_(w), halves_(halves), open_speed_(open_speed), clear_distance_(L.rp + L.rt + 2 * L.d), t_open_(w.time()) {
    w.wall(halves[0]).motion.velocity = Vec3(open_speed, 0, 0);
    w.wall(halves[1]).motion.velocity = Vec3(-open_speed, 0, 0);
    for (int k : halves) {
      // WallMotion poses are exact functions of time from t = 0: start the motion now by shifting the
      // reference pivot back along the velocity.
      Wall& wl = w.wall(k);
      wl.motion.pivot -= wl.motion.velocity * t_open_;
      wl.set_time(t_open_);
    }
    w.mark_changed();
  }
  double clear_time() const { return clear_distance_ / open_speed_; }
  // After each chunk of steps: parks the halves once they are clear.
  void park_when_clear() {
    if (parked_ || (w_.time() - t_open_) * open_speed_ < clear_distance_) return;
    for (int k : halves_) {
      Wall& wl = w_.wall(k);
      wl.shape = wl.current;
      wl.motion = WallMotion{};
      wl.motion.pivot = wl.pivot_now;
      wl.set_time(w_.time());
    }
    w_.mark_changed();
    parked_ = true;
  }

 private:
  World& w_;
  std::array<int, 2> halves_;
  double open_speed_, clear_distance_, t_open_;
  bool parked_ = false;
};

// The pile: its height at the axis, its radial profile (every grid cell inside the pipe counts,
// an empty one as bare bed) and the angle of repose of its flank.
void measure_pile(const World& w, const Phases& phases, const RigLayout& L, SlumpResult& res) {
  const Particles& p = w.particles();
  const double d = L.d, rp = L.rp, z_bed = L.z_bed;
  double top = z_bed;
  for (std::size_t i = 0; i < p.size(); ++i)
    if (phases.is_sample(i) && std::hypot(p.x[i].x(), p.x[i].y()) < 2.0 * d) top = std::max(top, p.x[i].z() + p.radius[i]);
  res.peak_height = top - z_bed;
  const double cell = 1.5 * d;
  const auto cells = surface_cells(p, cell, [&](std::size_t i) { return phases.is_sample(i) && p.x[i].z() > 0.0; });
  const int nbins = static_cast<int>(std::ceil(rp / cell));
  std::vector<double> sum(static_cast<std::size_t>(nbins), 0.0);
  std::vector<int> cnt(static_cast<std::size_t>(nbins), 0), occupied(static_cast<std::size_t>(nbins), 0);
  const int span = static_cast<int>(std::ceil(rp / cell)) + 1;
  for (int ix = -span; ix <= span; ++ix)
    for (int iy = -span; iy <= span; ++iy) {
      const double r = cell_centre({ix, iy}, cell).norm();
      const int b = static_cast<int>(r / cell);
      if (b >= nbins) continue;
      const auto it = cells.find({ix, iy});
      const double h = it == cells.end() ? 0.0 : std::max(it->second - z_bed, 0.0);
      sum[static_cast<std::size_t>(b)] += h;
      ++cnt[static_cast<std::size_t>(b)];
      if (it != cells.end()) ++occupied[static_cast<std::size_t>(b)];
    }
  res.pile_radius = 0.0;
  for (int b = 0; b < nbins; ++b) {
    const auto bs = static_cast<std::size_t>(b);
    if (cnt[bs] == 0) continue;
    ProfilePoint pp{(b + 0.5) * cell, sum[bs] / cnt[bs], cnt[bs]};
    res.profile.push_back(pp);
    if (pp.h >= d) res.pile_radius = (b + 1) * cell;
  }
  // Flank: profile points between 20 % and 80 % of the pile height, least-squares line h(r).
  double sr = 0, sh = 0, srr = 0, srh = 0;
  int n = 0;
  for (const auto& pp : res.profile)
    if (pp.h >= 0.2 * res.peak_height && pp.h <= 0.8 * res.peak_height) {
      sr += pp.r;
      sh += pp.h;
      srr += pp.r * pp.r;
      srh += pp.r * pp.h;
      ++n;
    }
  const double den = n * srr - sr * sr;
  if (n >= 3 && den > 0.0) {
    const double slope = (n * srh - sr * sh) / den;
    res.repose_angle_deg = std::atan(-slope) * 180.0 / pi;
    res.pile_height = (sh - slope * sr) / n;  // the flank line at r = 0: the cone's apex
  } else {
    res.repose_angle_deg = kNaN;
    res.pile_height = res.peak_height;
  }
}

}  // namespace

SlumpSettings slump_preset(RigQuality q) {
  SlumpSettings s;
  if (q == RigQuality::quick) {
    // ~800 spheres of 5.6 mm (~1400 clumps of 2 x 4.4 mm): a column 3/4 as tall as the tube is wide, so
    // that it really slumps (a 30 mm column is already close to its own pile and hardly feels mu_r);
    // E/100 lets the time step grow 10x (dt ~ E^-1/2 through the Rayleigh limit); the reference study
    // found mean flow quantities insensitive to G x10 and /10 (Table 6).
    s.fill_height = 0.045;
    s.modulus_scale = 0.01;
    s.max_settle_time = 0.5;
    s.max_pile_time = 0.9;
  } else {
    s.fill_height = 0.060;
    s.modulus_scale = 0.1;
    s.max_settle_time = 0.8;
    s.max_pile_time = 1.5;
  }
  return s;
}

SlumpResult run_slump_test(const chutelab::Material& m, double solid_density, double rolling_friction, const Grain& g,
                           const SlumpSettings& s, const std::function<void(const SlumpProgress&)>& progress) {
  const auto wall_start = std::chrono::steady_clock::now();
  if (!(solid_density > 0.0)) throw InputError("", 0, "density", fmt::format("must be > 0 kg/m^3, got {}", solid_density));
  if (!(rolling_friction >= 0.0)) throw InputError("", 0, "rolling friction", fmt::format("must be >= 0, got {}", rolling_friction));
  if (!(s.tube_diameter > 4.0 * g.bounding_radius()) || !(s.pipe_diameter > s.tube_diameter))
    throw InputError("", 0, "slump tester", "need tube diameter > 2 grain sizes and pipe diameter > tube diameter");
  if (!(s.fill_height > 2.0 * g.bounding_radius())) throw InputError("", 0, "fill height", "must exceed one grain");

  chutelab::Material mat = m;
  mat.rolling_friction_particle = rolling_friction;
  const RigLayout L = lay_out_rig(g, s);
  World w(rig_settings(L, s));
  const double wall_friction =
      s.wall_friction >= 0.0 ? s.wall_friction : (m.friction_side > 0.0 ? m.friction_side : m.friction_plate);
  const double wall_rolling = m.rolling_friction_wall > 0.0 ? m.rolling_friction_wall : rolling_friction;
  const RigMaterials rm = add_rig_materials(w, mat, solid_density, s.modulus_scale, wall_friction, wall_rolling);

  const std::size_t n_bed = add_glued_bed(w, L, rm.pellet, solid_density);
  // The split tube: two halves meeting in the plane x = 0.
  const int segs = 24;
  const std::array<int, 2> halves = {
      w.add_wall(Wall::mesh("tube +x", half_tube(L.rt, L.z_tube, L.tube_top, -0.5 * pi, 0.5 * pi, segs), rm.wall)),
      w.add_wall(Wall::mesh("tube -x", half_tube(L.rt, L.z_tube, L.tube_top, 0.5 * pi, 1.5 * pi, segs), rm.wall))};
  const std::size_t placed = fill_tube(w, L, g, s, rm.pellet, solid_density);
  w.add_sink(Sink{Vec3(0, 0, -0.02), Vec3::UnitZ()});

  w.initialise();
  SlumpResult res;
  res.grain = g.label();
  res.bed_grains = n_bed;
  res.particles = placed;
  res.dt = w.dt();
  Phases phases(w, static_cast<std::int64_t>(n_bed), s, progress);

  const auto [t_settle, settled] = phases.run("pour", s.min_settle_time, s.max_settle_time, {});
  res.settle_time = t_settle;
  measure_poured(w, phases, L, s, res);

  TubeOpening opening(w, halves, L, s.open_speed);
  const auto [t_pile, piled] = phases.run("slump", std::max(s.min_pile_time, opening.clear_time()), s.max_pile_time,
                                          [&] { opening.park_when_clear(); });
  res.pile_time = t_pile;
  res.settled = settled && piled;
  res.lost_mass = w.sinks()[0].removed_mass;
  measure_pile(w, phases, L, res);

  res.steps = w.step_count();
  res.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  return res;
}

}  // namespace chutelab::dem::rigs
