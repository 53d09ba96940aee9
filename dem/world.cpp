#include "dem/world.h"

#include <algorithm>
#include <cmath>
#include <iostream>
#include <limits>
#include <numbers>

#include <fmt/format.h>
#include <omp.h>

#include "core/input_error.h"
#include "dem/team.h"

namespace chutelab::dem {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

std::string vec_str(const Vec3& v) { return fmt::format("({:.6g}, {:.6g}, {:.6g})", v.x(), v.y(), v.z()); }

}  // namespace

World::World(Settings settings) : settings_(std::move(settings)) {
  if (!(settings_.dt >= 0.0) || !std::isfinite(settings_.dt))
    throw InputError("", 0, "dt", fmt::format("time step must be >= 0 s (0 = automatic), got {}", settings_.dt));
  if (!(settings_.skin >= 0.0)) throw InputError("", 0, "skin", "Verlet skin must be >= 0 m");
  if (!settings_.gravity.allFinite()) throw InputError("", 0, "gravity", "gravity must be finite");
  if (settings_.check_every < 1) throw InputError("", 0, "check_every", "must be >= 1");
  if (settings_.threads < 0) throw InputError("", 0, "threads", "must be >= 0");
}

void World::warn(const std::string& msg) {
  warnings_.push_back(msg);
  if (settings_.on_warning)
    settings_.on_warning(msg);
  else
    std::cerr << "chutelab dem warning: " << msg << '\n';
}

int World::thread_count() const { return settings_.threads > 0 ? settings_.threads : omp_get_max_threads(); }

std::int64_t World::add_particle(const ParticleSpec& s) {
  const std::string field = "particle";
  if (!(s.radius > 0.0) || !std::isfinite(s.radius))
    throw InputError("", 0, field, fmt::format("radius must be > 0 m, got {}", s.radius));
  if (s.material < 0 || s.material >= materials_.size())
    throw InputError("", 0, field, fmt::format("unknown material index {}", s.material));
  if (!s.position.allFinite() || !s.velocity.allFinite() || !s.omega.allFinite())
    throw InputError("", 0, field, "position and velocities must be finite");
  const double rho = s.density > 0.0 ? s.density : materials_.material(s.material).density;
  if (!(rho > 0.0))
    throw InputError("", 0, field,
                     fmt::format("density must be > 0 kg/m^3 (material '{}' has {})",
                                 materials_.material(s.material).name, rho));
  const double m = rho * 4.0 / 3.0 * std::numbers::pi * s.radius * s.radius * s.radius;
  const std::int64_t id = next_id_++;
  p_.push_back(s.position, s.velocity, s.omega, s.radius, m, s.material, id);
  contacts_.dirty = true;
  return id;
}

int World::add_wall(Wall w) {
  const std::string field = fmt::format("wall '{}'", w.name);
  if (w.material < 0 || w.material >= materials_.size())
    throw InputError("", 0, field, fmt::format("unknown material index {}", w.material));
  if (!w.motion.omega.isZero(0.0) && !std::isfinite(reach_from_pivot(w)))
    throw InputError("", 0, field,
                     "an unbounded plane or infinite cylinder cannot rotate (bound it or use a mesh)");
  w.set_time(clock_.time);
  walls_.push_back(std::move(w));
  contacts_.reference.wall_time.push_back(clock_.time);
  contacts_.reference.wall_listed_moving.push_back(0);
  contacts_.dirty = true;
  return static_cast<int>(walls_.size()) - 1;
}

int World::add_inserter(Inserter in) {
  const std::string field = "inserter";
  if (in.region.empty()) throw InputError("", 0, field, "insertion region is empty (need hi > lo on every axis)");
  if (!(in.mass_rate >= 0.0)) throw InputError("", 0, field, "mass rate must be >= 0 kg/s");
  if (!(in.radius_min > 0.0) || !(in.radius_max >= in.radius_min))
    throw InputError("", 0, field, fmt::format("need 0 < radius_min <= radius_max, got {} and {}", in.radius_min, in.radius_max));
  if (in.material < 0 || in.material >= materials_.size()) throw InputError("", 0, field, "unknown material index");
  if (!(materials_.material(in.material).density > 0.0)) throw InputError("", 0, field, "material density must be > 0");
  if (!(in.interval > 0.0)) throw InputError("", 0, field, "interval must be > 0 s");
  double reach = in.radius_max;
  if (in.clump_shape >= 0) {
    if (in.clump_shape >= static_cast<int>(clumps_.shapes.size())) throw InputError("", 0, field, "unknown clump shape index");
    if (in.radius_min != in.radius_max)
      throw InputError("", 0, field, "clumps are inserted at one size: give radius_min = radius_max");
    const ClumpShape& base = clumps_.shapes[static_cast<std::size_t>(in.clump_shape)];
    in.clump_shape = add_clump_shape(base.scaled(in.radius_max / base.largest_sphere_radius()));
    reach = clumps_.shapes[static_cast<std::size_t>(in.clump_shape)].bounding_radius;
  }
  if (in.hold_to_face) {
    if (in.clump_shape >= 0) throw InputError("", 0, field, "a stream inserter (hold_to_face) inserts spheres only");
    if (in.hold_axis < 0 || in.hold_axis > 2) throw InputError("", 0, field, "hold_axis must be 0, 1 or 2");
    if (!(std::abs(in.velocity[in.hold_axis]) > 0.0))
      throw InputError("", 0, field, "a stream inserter (hold_to_face) needs a velocity through its face");
  }
  const Vec3 size = in.region.hi - in.region.lo;
  if (size.minCoeff() < 2.0 * reach)
    throw InputError("", 0, field, "insertion region is narrower than one particle diameter");
  in.rng_state = in.seed;
  in.next_time = in.start_time;
  sources_.inserters.push_back(in);
  return static_cast<int>(sources_.inserters.size()) - 1;
}

int World::add_sink(Sink s) {
  if (!(s.normal.norm() > 0.0)) throw InputError("", 0, "sink", "sink normal must be non-zero");
  s.normal.normalize();
  sources_.sinks.push_back(s);
  return static_cast<int>(sources_.sinks.size()) - 1;
}

void World::remove_particles_if(const std::function<bool(std::size_t)>& pred) {
  const std::size_t n = p_.size();
  std::vector<char> gone(n, 0);
  for (std::size_t i = 0; i < n; ++i) gone[i] = pred(i) ? 1 : 0;
  if (clumps_.size() > 0) remove_whole_clumps(gone);
  std::vector<std::int32_t> keep;
  std::vector<std::int32_t> remap(n, -1);
  keep.reserve(n);
  for (std::size_t i = 0; i < n; ++i)
    if (!gone[i]) {
      remap[i] = static_cast<std::int32_t>(keep.size());
      keep.push_back(static_cast<std::int32_t>(i));
    }
  if (keep.size() == n) return;
  p_.permute(keep);
  if (!sources_.held.empty()) index_held();
  for (auto& m : contacts_.reference.index_map)
    if (m >= 0) m = remap[static_cast<std::size_t>(m)];
  contacts_.dirty = true;
}

double World::source_speed() const {
  double vmax = 0.0;
  for (const auto& vi : p_.v) vmax = std::max(vmax, vi.norm());
  for (const auto& in : sources_.inserters) vmax = std::max(vmax, in.velocity.norm());
  for (const auto& w : walls_) {
    double vw = w.motion.velocity.norm() + w.surface.linear.norm();
    vw += (w.motion.omega.norm() + w.surface.omega.norm()) * std::min(reach_from_pivot(w), 10.0);
    vmax = std::max(vmax, 2.0 * vw);
  }
  return vmax;
}

double World::fall_speed() const {
  const double h = settings_.domain.empty() ? 0.0 : (settings_.domain.hi - settings_.domain.lo).norm();
  return std::sqrt(2.0 * settings_.gravity.norm() * h);
}

TimeStepEstimate World::time_step_estimate() const {
  TimeStepEstimate est;
  // Characteristic speed: free fall across the domain, plus boundary and feed speeds.
  double v = settings_.characteristic_speed;
  if (!(v > 0.0)) v = std::max(source_speed() + fall_speed(), 0.1);
  est.speed = v;
  // Smallest particles of each material in the scene (existing and inserted).
  std::vector<double> rmin(static_cast<std::size_t>(materials_.size()), kInf);
  for (std::size_t i = 0; i < p_.size(); ++i) {
    auto& r = rmin[static_cast<std::size_t>(p_.material[i])];
    r = std::min(r, p_.radius[i]);
  }
  for (const auto& in : sources_.inserters) {
    auto& r = rmin[static_cast<std::size_t>(in.material)];
    r = std::min(r, in.radius_min);
  }
  est.rayleigh = kInf;
  est.collision = kInf;
  for (int a = 0; a < materials_.size(); ++a) {
    const double ra = rmin[static_cast<std::size_t>(a)];
    if (!std::isfinite(ra)) continue;
    const Material& ma = materials_.material(a);
    const double rho = ma.density;
    est.rayleigh = std::min(est.rayleigh, rayleigh_time(ra, rho, materials_.shear_modulus(a), ma.poisson_ratio));
    const double m = rho * 4.0 / 3.0 * std::numbers::pi * ra * ra * ra;
    auto consider = [&](int b, double r_eff, double m_eff) {
      const double tc = settings_.normal.visit([&]<class Law>() {
        return Law::collision_time(Law::mix(ma, materials_.material(b), materials_.interaction(a, b)), m_eff, r_eff, v);
      });
      est.collision = std::min(est.collision, tc);
    };
    for (int b = 0; b < materials_.size(); ++b) {
      const double rb = rmin[static_cast<std::size_t>(b)];
      if (std::isfinite(rb)) {
        const double mb = materials_.material(b).density * 4.0 / 3.0 * std::numbers::pi * rb * rb * rb;
        consider(b, ra * rb / (ra + rb), m * mb / (m + mb));
      }
    }
    for (const auto& w : walls_) consider(w.material, ra, m);
  }
  est.recommended = std::min(kDtFractionOfCollision * est.collision, kDtFractionOfRayleigh * est.rayleigh);
  est.unsafe_above = std::min(kUnsafeFractionOfCollision * est.collision, kUnsafeFractionOfRayleigh * est.rayleigh);
  return est;
}

void World::check_contact_law() const {
  auto field = [&](int a, int b) {
    return fmt::format("interaction '{}'-'{}'", materials_.material(a).name, materials_.material(b).name);
  };
  std::vector<char> used(static_cast<std::size_t>(materials_.size()), 0);
  for (auto m : p_.material) used[static_cast<std::size_t>(m)] = 1;
  for (const auto& in : sources_.inserters) used[static_cast<std::size_t>(in.material)] = 1;
  settings_.normal.visit([&]<class Law>() {
    for (int a = 0; a < materials_.size(); ++a)
      for (int b = 0; b < materials_.size(); ++b)
        for (const auto& [key, value] : materials_.interaction(a, b).law.values()) {
          bool declared = false;
          std::string known;
          for (const LawParameter& p : Law::parameters) {
            declared = declared || p.key == key;
            known += (known.empty() ? "" : ", ") + std::string(p.key);
          }
          if (!declared)
            throw InputError("", 0, field(a, b),
                             fmt::format("the {} contact law has no parameter '{}' ({})", Law::key, key,
                                         known.empty() ? "it takes none" : "it takes " + known));
        }
    for (int a = 0; a < materials_.size(); ++a) {
      if (!used[static_cast<std::size_t>(a)]) continue;
      auto check = [&](int b) {
        const std::string why = Law::check(Law::mix(materials_.material(a), materials_.material(b), materials_.interaction(a, b)));
        if (!why.empty()) throw InputError("", 0, field(a, b), fmt::format("the {} contact law {}", Law::key, why));
      };
      for (int b = 0; b < materials_.size(); ++b)
        if (used[static_cast<std::size_t>(b)]) check(b);
      for (const auto& w : walls_) check(w.material);
    }
  });
}

void World::derive_pair_table() {
  if (law_table_.revision == materials_.revision()) return;
  settings_.normal.visit([&]<class Law>() {
    auto table = pair_table<Law>(materials_);
    law_table_.cohesive = std::any_of(table.begin(), table.end(), [](const PairCoeffs<Law>& c) { return c.cohesion > 0.0; });
    law_table_.pairs = std::move(table);
  });
  law_table_.revision = materials_.revision();
}

void World::initialise() {
  if (initialised_) return;
  if (settings_.domain.empty())
    throw InputError("", 0, "domain", "the simulation domain box is required (hi > lo on every axis)");
  check_contact_law();
  derive_pair_table();
  const TimeStepEstimate est = time_step_estimate();
  if (settings_.dt > 0.0) {
    clock_.dt = settings_.dt;
    if (std::isfinite(est.unsafe_above) && clock_.dt > est.unsafe_above)
      warn(fmt::format(
          "time step {:.3g} s is unsafe: the shortest collision lasts {:.3g} s ({:.1f} steps; need >= 4) and the "
          "Rayleigh time is {:.3g} s (dt/t_R = {:.2f}; need <= {}); recommended dt = {:.3g} s",
          clock_.dt, est.collision, est.collision / clock_.dt, est.rayleigh, clock_.dt / est.rayleigh, kUnsafeFractionOfRayleigh,
          est.recommended));
  } else {
    if (!std::isfinite(est.recommended))
      throw InputError("", 0, "dt", "cannot derive a time step: no particles and no inserters; set dt");
    clock_.dt = est.recommended;
  }
  double rmax = 0.0;
  for (double r : p_.radius) rmax = std::max(rmax, r);
  for (const auto& in : sources_.inserters) rmax = std::max(rmax, in.radius_max);
  contacts_.skin = settings_.skin > 0.0 ? settings_.skin : 0.25 * rmax;
  if (!(contacts_.skin > 0.0)) contacts_.skin = 1e-3;
  if (settings_.max_speed > 0.0) {
    max_speed_ = settings_.max_speed;
  } else {
    // Nothing can move faster than its fastest source of energy allows: the fastest initial, feed or
    // boundary speed plus free fall across the whole domain. Twice that (plus 1 m/s) is "impossible".
    max_speed_ = 2.0 * (source_speed() + fall_speed()) + 1.0;
  }
  initialised_ = true;
  for (auto& w : walls_) w.set_time(clock_.time);
  rebuild();
  compute_forces();
  if (clumps_.size() > 0) clumps_.gather(p_, settings_.gravity);
  check_state();
}

void World::refresh_lists() {
  if (!initialised_ || !contacts_.dirty) return;
  rebuild();
  compute_forces();
}

void World::step(std::int64_t n) {
  initialise();
  // Velocity Verlet (dem/integrator.h). Within one call the closing pass of a step also opens the
  // next (its first half kick and drift), and without clumps that pass runs inside the force
  // evaluation, block by block (BlockClosing). Not with clumps: their bodies gather the spheres'
  // forces before any kick. Not across calls: the caller sees each call end on a full step.
  bool opened = false;  // this step's first half kick and drift were done by the last closing pass
  double maxd2_next = 0.0;
  for (std::int64_t s = 0; s < n; ++s) {
    // Particles added or removed by the caller since the last step (never after an opening pass).
    if (contacts_.dirty) {
      rebuild();
      compute_forces();
    }
    double maxd2 = opened ? maxd2_next : verlet_pass({.open = true}, contacts_.max_disp * contacts_.max_disp).second;
    if (clumps_.size() > 0) clumps_after_drift(clock_.dt, maxd2);
    contacts_.max_disp = std::sqrt(maxd2);
    advance_time();
    if (!sources_.inserters.empty() || !sources_.sinks.empty()) insert_and_delete();
    if (needs_rebuild()) rebuild();
    const bool fused = clumps_.size() == 0;
    opened = fused && s + 1 < n;
    const VerletPass closing{.close = true, .check = (clock_.step + 1) % settings_.check_every == 0, .open = opened};
    std::size_t first_bad = p_.size();
    if (fused) {
      BlockClosing close_block(verlet_state(), closing, state_limits(), static_cast<std::size_t>(thread_count()),
                               p_.size());
      compute_forces(std::ref(close_block));
      first_bad = close_block.first_bad();
      maxd2_next = std::max(contacts_.max_disp * contacts_.max_disp, close_block.maxd2());
    } else {
      compute_forces();
    }
    // The observers read what each contact saw, stored with it: the particles may have moved on.
    if (!hooks_.wall_observers.empty()) report_wall_contacts();
    if (hooks_.load_observer) hooks_.load_observer();
    if (!fused) {
      first_bad = verlet_pass(closing, 0.0).first;
      clumps_after_forces(clock_.dt);
    }
    ++clock_.step;
    if (first_bad < p_.size()) report_bad(first_bad);
  }
}

void World::advance_time() {
  clock_.time = static_cast<double>(clock_.step + 1) * clock_.dt;  // no accumulated round-off in time
  for (auto& w : walls_)
    if (w.motion.moving()) w.set_time(clock_.time);
}

std::pair<std::size_t, double> World::verlet_pass(const VerletPass& pass, double maxd2) {
  const VerletState state = verlet_state();
  const StateLimits limits = state_limits();
  const std::size_t np = p_.size();
  std::size_t first_bad = np;
  const int nt = thread_count();
  if (runs_alone(nt)) {
    const auto [lo, hi] = blocks_.thread_rows(np);
    verlet_rows(state, pass, limits, lo, hi, first_bad, maxd2);
    return {first_bad, maxd2};
  }
#pragma omp parallel num_threads(nt) reduction(min : first_bad) reduction(max : maxd2)
  {
    const auto [lo, hi] = blocks_.thread_rows(np);
    verlet_rows(state, pass, limits, lo, hi, first_bad, maxd2);
  }
  return {first_bad, maxd2};
}

void World::check_state() const {
  const std::size_t np = p_.size();
  const double vlim2 = max_speed_ * max_speed_;
  for (std::size_t i = 0; i < np; ++i)
    if (!(p_.v[i].squaredNorm() <= vlim2 && p_.w[i].allFinite() && settings_.domain.contains(p_.x[i]))) report_bad(i);
}

void World::report_bad(std::size_t i) const {
  const std::string where = fmt::format("DEM stopped at step {} (t = {:.6g} s): particle id {} ", clock_.step, clock_.time, p_.id[i]);
  const TimeStepEstimate est = time_step_estimate();
  const std::string hint = fmt::format(
      " Time step {:.3g} s; collision time {:.3g} s, Rayleigh time {:.3g} s, recommended dt {:.3g} s.", clock_.dt,
      est.collision, est.rayleigh, est.recommended);
  if (!p_.x[i].allFinite() || !p_.v[i].allFinite() || !p_.w[i].allFinite())
    throw SimulationError(where + fmt::format("has a non-finite state (x = {}, v = {}): the integration blew up.",
                                              vec_str(p_.x[i]), vec_str(p_.v[i])) + hint);
  if (p_.v[i].squaredNorm() > max_speed_ * max_speed_)
    throw SimulationError(where + fmt::format("moves at {:.4g} m/s, faster than physically possible here "
                                              "({:.4g} m/s): the contacts are unstable (overlap too deep).",
                                              p_.v[i].norm(), max_speed_) + hint);
  throw SimulationError(where + fmt::format("left the domain at {} (domain {} to {}): a lost particle (it passed "
                                            "through a wall, or the domain/sinks do not cover the scene).",
                                            vec_str(p_.x[i]), vec_str(settings_.domain.lo), vec_str(settings_.domain.hi)) + hint);
}

void World::index_held() {
  sources_.held.clear();
  for (std::size_t i = 0; i < p_.held_by.size(); ++i)
    if (p_.held_by[i] >= 0) sources_.held.push_back(static_cast<std::int32_t>(i));
}

std::size_t World::contact_count() const {
  std::size_t n = 0;
  for (auto t : contacts_.pairs.touch) n += t;
  return n;
}

std::size_t World::wall_contact_count() const {
  std::size_t n = 0;
  for (auto t : contacts_.walls.touch) n += t;
  return n;
}

Energy World::energy() const {
  Energy e;
  e.translational = clumps_.translational_energy();
  e.rotational = clumps_.rotational_energy();
  for (std::size_t c = 0; c < clumps_.size(); ++c) e.gravitational -= clumps_.mass[c] * settings_.gravity.dot(clumps_.x[c]);
  for (std::size_t i = 0; i < p_.size(); ++i) {
    if (p_.clump[i] >= 0) continue;  // counted with its body
    e.translational += 0.5 * p_.mass[i] * p_.v[i].squaredNorm();
    e.rotational += 0.5 / p_.inv_inertia[i] * p_.w[i].squaredNorm();
    e.gravitational -= p_.mass[i] * settings_.gravity.dot(p_.x[i]);
  }
  e.elastic = elastic_energy();
  return e;
}

// The energy in the normal springs of the touching contacts, through the scene's law.
double World::elastic_energy() const {
  return settings_.normal.visit([&]<class Law>() {
    const std::vector<PairCoeffs<Law>> table = pair_table<Law>(materials_);
    const auto nmat = static_cast<std::size_t>(materials_.size());
    auto pair = [&](std::int32_t a, std::int32_t b) -> const typename Law::Coeffs& {
      return table[static_cast<std::size_t>(a) * nmat + static_cast<std::size_t>(b)].normal;
    };
    double sum = 0.0;
    for (std::size_t i = 0; i + 1 < contacts_.pairs.row_begin.size(); ++i)
      for (auto s = contacts_.pairs.row_begin[i]; s < contacts_.pairs.row_begin[i + 1]; ++s) {
        const auto j = static_cast<std::size_t>(contacts_.pairs.neighbor[static_cast<std::size_t>(s)]);
        const double rs = p_.radius[i] + p_.radius[j];
        const double delta = rs - (p_.x[j] - p_.x[i]).norm();
        if (delta <= 0.0) continue;
        const double r_eff = p_.radius[i] * p_.radius[j] / rs;
        sum += Law::elastic_energy(pair(p_.material[i], p_.material[j]), delta, r_eff);
      }
    for (std::size_t q = 0; q < contacts_.walls.touch.size(); ++q) {
      if (!contacts_.walls.touch[q]) continue;
      const auto i = static_cast<std::size_t>(contacts_.walls.owner[q]);
      const double delta = p_.radius[i] - (contacts_.walls.point[q] - p_.x[i]).norm();
      if (delta <= 0.0) continue;
      const Wall& w = walls_[static_cast<std::size_t>(contacts_.walls.wall[q])];
      sum += Law::elastic_energy(pair(p_.material[i], w.material), delta, p_.radius[i]);
    }
    return sum;
  });
}

}  // namespace chutelab::dem
