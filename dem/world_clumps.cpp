// The World's share of rigid multi-sphere particles (dem/clump.h, dem/clump_bodies.h): adding bodies,
// the two integration hooks around the sphere update in World::step, whole-body removal and insertion.
// Kept apart from world.cpp so the sphere core stays as it was; world.cpp calls these only when the
// scene has clumps.
#include <algorithm>
#include <cmath>
#include <numbers>

#include <fmt/format.h>

#include "core/input_error.h"
#include "dem/world.h"

namespace chutelab::dem {

int World::add_clump_shape(const ClumpShape& shape) {
  if (shape.spheres.empty() || !(shape.volume > 0.0))
    throw InputError("", 0, fmt::format("clump shape '{}'", shape.name), "a clump shape needs spheres and a volume > 0");
  return clumps_.add_shape(shape);
}

std::int64_t World::add_clump(const ClumpSpec& s) {
  const std::string field = "clump";
  if (s.shape < 0 || s.shape >= static_cast<int>(clumps_.shapes.size()))
    throw InputError("", 0, field, fmt::format("unknown clump shape index {}", s.shape));
  if (s.material < 0 || s.material >= materials_.size())
    throw InputError("", 0, field, fmt::format("unknown material index {}", s.material));
  if (!s.position.allFinite() || !s.velocity.allFinite() || !s.omega.allFinite() || !s.orientation.coeffs().allFinite() ||
      !(s.orientation.norm() > 0.0))
    throw InputError("", 0, field, "position, orientation and velocities must be finite (orientation non-zero)");
  const double rho = s.density > 0.0 ? s.density : materials_.material(s.material).density;
  if (!(rho > 0.0)) throw InputError("", 0, field, fmt::format("density must be > 0 kg/m^3, got {}", rho));
  const std::int64_t body_id = next_clump_id_++;
  const std::int32_t c = clumps_.add(s.shape, s.position, s.orientation, s.velocity, s.omega, rho, body_id);
  const auto cs = static_cast<std::size_t>(c);
  const ClumpShape& shape = clumps_.shapes[static_cast<std::size_t>(s.shape)];
  // The members' rotational inverse inertia only enters the rolling-friction cap (the torque that stops
  // a relative spin within one step); the body's largest 1/I keeps that cap on the safe side.
  const double inv_i = clumps_.inv_inertia[cs].maxCoeff();
  for (std::size_t k = 0; k < shape.spheres.size(); ++k) {
    const Vec3 arm = clumps_.rot[cs] * shape.spheres[k].offset;
    const double mk = clumps_.member_mass(s.shape, k, rho);
    p_.push_back(s.position + arm, clumps_.v[cs] + clumps_.w[cs].cross(arm), clumps_.w[cs], shape.spheres[k].radius, mk,
                 s.material, next_id_++);
    p_.clump.back() = c;
    p_.body_offset.back() = shape.spheres[k].offset;
    p_.inv_inertia.back() = inv_i;
    p_.contact_mass.back() = clumps_.mass[cs];
  }
  contacts_.dirty = true;
  return body_id;
}

void World::clumps_after_drift(double dt, double& maxd2) {
  clumps_.kick_momenta(0.5 * dt);
  clumps_.drift(dt);
  clumps_.place_members(p_);
  for (std::size_t i = 0; i < p_.size(); ++i)
    if (p_.clump[i] >= 0) maxd2 = std::max(maxd2, (p_.x[i] - contacts_.reference.x[i]).squaredNorm());
}

void World::clumps_after_forces(double dt) {
  clumps_.gather(p_, settings_.gravity);
  clumps_.kick(0.5 * dt);
  clumps_.set_member_velocities(p_);
}

void World::remove_whole_clumps(std::vector<char>& gone) {
  std::vector<char> keep(clumps_.size(), 1);
  bool any = false;
  for (std::size_t i = 0; i < p_.size(); ++i)
    if (gone[i] && p_.clump[i] >= 0) {
      keep[static_cast<std::size_t>(p_.clump[i])] = 0;
      any = true;
    }
  if (!any) return;
  for (std::size_t i = 0; i < p_.size(); ++i)
    if (p_.clump[i] >= 0 && !keep[static_cast<std::size_t>(p_.clump[i])]) gone[i] = 1;
  clumps_.compact(keep, p_);
}

bool World::try_insert_clump(Inserter& in, std::vector<std::size_t>& near) {
  const ClumpShape& sh = clumps_.shapes[static_cast<std::size_t>(in.clump_shape)];
  const double rb = sh.bounding_radius;
  for (int attempt = 0; attempt < in.max_attempts; ++attempt) {
    Vec3 pos;
    for (int d = 0; d < 3; ++d)
      pos[d] = in.region.lo[d] + rb + (in.region.hi[d] - in.region.lo[d] - 2.0 * rb) * uniform01(in.rng_state);
    // Uniformly random orientation (Shoemake 1992) from the inserter's own generator.
    const double u1 = uniform01(in.rng_state), u2 = 2.0 * std::numbers::pi * uniform01(in.rng_state),
                 u3 = 2.0 * std::numbers::pi * uniform01(in.rng_state);
    const Quat q(std::sqrt(1 - u1) * std::sin(u2), std::sqrt(1 - u1) * std::cos(u2), std::sqrt(u1) * std::sin(u3),
                 std::sqrt(u1) * std::cos(u3));
    const Mat3 R = q.toRotationMatrix();
    bool free = true;
    for (const auto& sp : sh.spheres) {
      const Vec3 xs = pos + R * sp.offset;
      for (std::size_t j : near) {
        const double rr = sp.radius + p_.radius[j];
        if ((p_.x[j] - xs).squaredNorm() < rr * rr) {
          free = false;
          break;
        }
      }
      if (!free) break;
    }
    if (!free) continue;
    ClumpSpec spec;
    spec.shape = in.clump_shape;
    spec.position = pos;
    spec.orientation = q;
    spec.velocity = in.velocity;
    spec.material = in.material;
    add_clump(spec);
    for (std::size_t k = 0; k < sh.spheres.size(); ++k) near.push_back(p_.size() - 1 - k);
    const double m = clumps_.mass.back();
    in.pending_mass -= m;
    in.inserted_mass += m;
    return true;
  }
  return false;
}

}  // namespace chutelab::dem
