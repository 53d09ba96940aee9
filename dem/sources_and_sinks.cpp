// Particle sources and sinks (dem/insertion.h): the sinks' removals, the release of particles a
// stream inserter holds, and the inserters' placements, once per step after the drift.
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include <fmt/format.h>

#include "dem/team.h"
#include "dem/world.h"

namespace chutelab::dem {

void World::insert_and_delete() {
  // Sinks first, so that their mass counts and indices are settled before new particles arrive.
  if (!sources_.sinks.empty() && anything_behind_sinks()) remove_behind_sinks();
  if (!sources_.held.empty()) release_held();
  for (std::size_t k = 0; k < sources_.inserters.size(); ++k) insert_from(k);
}

bool World::anything_behind_sinks() const {
  // Skipping the scan is exact: a particle within contacts_.max_disp of where it stood at the rebuild is
  // still in front of a sink that every particle then cleared by more than that (the 1 nm margin
  // covers the rounding of the dot products). No clearance yet (a checkpoint, a new sink): scan.
  // A sink that cannot be skipped scans only the particles listed within a skin of it at the
  // rebuild (the same margin argument), unless contacts_.max_disp has reached that skin.
  const bool listed = sources_.sink_scan.clearance.size() == sources_.sinks.size();
  bool any = false;
  for (std::size_t k = 0; k < sources_.sinks.size() && !any; ++k) {
    const Sink& s = sources_.sinks[k];
    const double moved = contacts_.max_disp * s.normal.norm();
    if (listed && sources_.sink_scan.clearance[k] - moved > 1e-9) continue;
    if (listed && moved + 1e-9 < sources_.sink_scan.reach[k]) {
      for (const std::int32_t i : sources_.sink_scan.near[k])
        if ((p_.x[static_cast<std::size_t>(i)] - s.point).dot(s.normal) < 0.0) any = true;
    } else {
      for (std::size_t i = 0; i < p_.size() && !any; ++i)
        if ((p_.x[i] - s.point).dot(s.normal) < 0.0) any = true;
    }
  }
  return any;
}

void World::remove_behind_sinks() {
  std::vector<int> sink_of(p_.size(), -1);
  for (std::size_t i = 0; i < p_.size(); ++i)
    for (std::size_t k = 0; k < sources_.sinks.size(); ++k)
      if ((p_.x[i] - sources_.sinks[k].point).dot(sources_.sinks[k].normal) < 0.0) {
        sink_of[i] = static_cast<int>(k);
        break;
      }
  if (clumps_.size() > 0) {  // a clump goes whole, to the sink that caught its first sphere
    std::vector<int> body_sink(clumps_.size(), -1);
    for (std::size_t i = 0; i < p_.size(); ++i)
      if (p_.clump[i] >= 0 && sink_of[i] >= 0 && body_sink[static_cast<std::size_t>(p_.clump[i])] < 0)
        body_sink[static_cast<std::size_t>(p_.clump[i])] = sink_of[i];
    for (std::size_t i = 0; i < p_.size(); ++i)
      if (p_.clump[i] >= 0) sink_of[i] = body_sink[static_cast<std::size_t>(p_.clump[i])];
  }
  for (std::size_t i = 0; i < p_.size(); ++i)
    if (sink_of[i] >= 0) {
      sources_.sinks[static_cast<std::size_t>(sink_of[i])].removed_mass += p_.mass[i];
      ++sources_.sinks[static_cast<std::size_t>(sink_of[i])].removed_count;
    }
  remove_particles_if([&](std::size_t i) { return sink_of[i] >= 0; });
}

// Held particles whose centre has crossed their inserter's face go free with its full velocity.
// Each thread takes the held particles of its share of the integrator (ForceBlocks::thread_rows): a
// particle's lines stay with the core that integrates it.
void World::release_held() {
  const std::size_t np = p_.size();
  std::size_t released = 0;
  auto release_rows = [&](std::size_t& count) {
    const auto [lo, hi] = blocks_.thread_rows(np);
    for (const std::int32_t h : held_between(lo, hi)) {
      const auto i = static_cast<std::size_t>(h);
      const Inserter& in = sources_.inserters[static_cast<std::size_t>(p_.held_by[i])];
      const int a = in.hold_axis;
      const bool through = in.velocity[a] < 0.0 ? p_.x[i][a] <= in.region.lo[a] : p_.x[i][a] >= in.region.hi[a];
      if (!through) continue;
      p_.v[i] = in.velocity;
      p_.held_by[i] = -1;
      ++count;
    }
  };
  const int nt = thread_count();
  if (runs_alone(nt)) {
    release_rows(released);
  } else {
#pragma omp parallel num_threads(nt) reduction(+ : released)
    release_rows(released);
  }
  if (released > 0)  // the released ones now have held_by = -1
    std::erase_if(sources_.held, [&](std::int32_t i) { return p_.held_by[static_cast<std::size_t>(i)] < 0; });
}

void World::insert_from(std::size_t k) {
  Inserter& in = sources_.inserters[k];
  if (clock_.time < in.start_time || clock_.time - clock_.dt >= in.end_time) return;
  in.pending_mass += in.mass_rate * clock_.dt;
  if (clock_.time + 0.5 * clock_.dt < in.next_time) return;
  in.next_time += in.interval;
  // Nearby particles that a new one could overlap.
  std::vector<std::size_t> near;
  Box grow = in.region;
  double rmax = in.radius_max;
  for (double r : p_.radius) rmax = std::max(rmax, r);
  grow.lo.array() -= 2.0 * rmax;
  grow.hi.array() += 2.0 * rmax;
  for (std::size_t i = 0; i < p_.size(); ++i)
    if (grow.contains(p_.x[i])) near.push_back(i);
  while (in.pending_mass > 0.0) {
    const double r = in.clump_shape >= 0 ? 0.0 : in.radius_min + (in.radius_max - in.radius_min) * uniform01(in.rng_state);
    const bool placed = in.clump_shape >= 0 ? try_insert_clump(in, near) : try_insert_sphere(k, r, near);
    if (placed) continue;
    if (!in.warned_full) {
      warn(fmt::format("inserter cannot place particles fast enough at t = {:.4g} s ({:.3g} kg owed): the "
                       "insertion region is full; enlarge it or lower the mass rate",
                       clock_.time, in.pending_mass));
      in.warned_full = true;
    }
    break;
  }
}

bool World::try_insert_sphere(std::size_t k, double r, std::vector<std::size_t>& near) {
  Inserter& in = sources_.inserters[k];
  for (int attempt = 0; attempt < in.max_attempts; ++attempt) {
    Vec3 pos;
    for (int d = 0; d < 3; ++d)
      pos[d] = in.region.lo[d] + r + (in.region.hi[d] - in.region.lo[d] - 2.0 * r) * uniform01(in.rng_state);
    bool free = true;
    for (std::size_t j : near) {
      const double rr = r + p_.radius[j];
      if ((p_.x[j] - pos).squaredNorm() < rr * rr) {
        free = false;
        break;
      }
    }
    if (!free) continue;
    ParticleSpec spec;
    spec.position = pos;
    spec.velocity = in.velocity;
    if (in.hold_to_face) {
      spec.velocity = Vec3::Zero();
      spec.velocity[in.hold_axis] = in.velocity[in.hold_axis];
    }
    spec.radius = r;
    spec.material = in.material;
    add_particle(spec);
    if (in.hold_to_face) {
      p_.held_by.back() = static_cast<std::int32_t>(k);
      sources_.held.push_back(static_cast<std::int32_t>(p_.size() - 1));
    }
    near.push_back(p_.size() - 1);
    const double rho = materials_.material(in.material).density;
    const double m = rho * 4.0 / 3.0 * std::numbers::pi * r * r * r;
    in.pending_mass -= m;
    in.inserted_mass += m;
    return true;
  }
  return false;
}

// How far every particle is from each sink now: until one has moved that far, none can be behind it,
// and insert_and_delete skips its scan (a particle moves at most contacts_.max_disp from
// contacts_.reference.x). The particles within one skin of a sink are listed: until
// contacts_.max_disp reaches the skin no other can be behind it, so the scan, when it cannot be
// skipped, looks at them only.
void World::scan_sinks() {
  const std::size_t n = p_.size();
  sources_.sink_scan.clearance.resize(sources_.sinks.size());
  sources_.sink_scan.near.resize(sources_.sinks.size());
  sources_.sink_scan.reach.resize(sources_.sinks.size());
  for (std::size_t k = 0; k < sources_.sinks.size(); ++k) {
    // A local minimum: stored through the member each time, it was a store-to-load chain per
    // particle (aliasing), about a fifth of a station rebuild's serial time.
    const Vec3 point = sources_.sinks[k].point, normal = sources_.sinks[k].normal;
    const double reach = contacts_.skin * normal.norm();
    double c = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < n; ++i) c = std::min(c, (p_.x[i] - point).dot(normal));
    sources_.sink_scan.clearance[k] = c;
    sources_.sink_scan.reach[k] = reach;
    std::vector<std::int32_t>& near = sources_.sink_scan.near[k];
    near.clear();
    if (c <= reach)  // only a sink some particle is near needs the list
      for (std::size_t i = 0; i < n; ++i)
        if ((p_.x[i] - point).dot(normal) <= reach) near.push_back(static_cast<std::int32_t>(i));
  }
}

}  // namespace chutelab::dem
