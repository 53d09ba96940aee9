#include "dem/clump_bodies.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace chutelab::dem {

int ClumpBodies::add_shape(const ClumpShape& s) {
  shapes.push_back(s);
  return static_cast<int>(shapes.size()) - 1;
}

double ClumpBodies::member_mass(int shape_index, std::size_t k, double density) const {
  const ClumpShape& s = shapes.at(static_cast<std::size_t>(shape_index));
  double sum = 0.0;
  for (const auto& sp : s.spheres) sum += sp.radius * sp.radius * sp.radius;
  const double r = s.spheres.at(k).radius;
  return density * s.volume * (r * r * r / sum);
}

std::int32_t ClumpBodies::add(int shape_index, const Vec3& position, const Quat& orientation, const Vec3& velocity,
                              const Vec3& omega, double density, std::int64_t ident) {
  const ClumpShape& s = shapes.at(static_cast<std::size_t>(shape_index));
  const Quat qn = orientation.normalized();
  const Mat3 R = qn.toRotationMatrix();
  const Vec3 inertia = density * s.principal_inertia;
  x.push_back(position);
  v.push_back(velocity);
  q.push_back(qn);
  rot.push_back(R);
  L.push_back(R * inertia.cwiseProduct(R.transpose() * omega));
  w.push_back(omega);
  f.push_back(Vec3::Zero());
  t.push_back(Vec3::Zero());
  mass.push_back(density * s.volume);
  inv_inertia.push_back(inertia.cwiseInverse());
  Vec3 mm = Vec3::Zero();
  for (std::size_t k = 0; k < s.spheres.size(); ++k) mm += member_mass(shape_index, k, density) * s.spheres[k].offset;
  member_moment.push_back(mm);
  shape.push_back(shape_index);
  members.push_back(static_cast<std::int32_t>(s.spheres.size()));
  id.push_back(ident);
  return static_cast<std::int32_t>(x.size()) - 1;
}

void ClumpBodies::kick(double half_dt) {
  for (std::size_t c = 0; c < size(); ++c) {
    v[c] += (half_dt / mass[c]) * f[c];
    L[c] += half_dt * t[c];
    w[c] = rot[c] * inv_inertia[c].cwiseProduct(rot[c].transpose() * L[c]);
  }
}

void ClumpBodies::kick_momenta(double half_dt) {
  for (std::size_t c = 0; c < size(); ++c) {
    v[c] += (half_dt / mass[c]) * f[c];
    L[c] += half_dt * t[c];
  }
}

void ClumpBodies::drift(double dt) {
  for (std::size_t c = 0; c < size(); ++c) {
    x[c] += dt * v[c];
    rotate_free(q[c], L[c], inv_inertia[c], dt);
    rot[c] = q[c].toRotationMatrix();
    w[c] = rot[c] * inv_inertia[c].cwiseProduct(rot[c].transpose() * L[c]);
  }
}

double ClumpBodies::place_members(Particles& p) const {
  double maxd2 = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const auto c = p.clump[i];
    if (c < 0) continue;
    const auto cs = static_cast<std::size_t>(c);
    const Vec3 arm = rot[cs] * p.body_offset[i];
    const Vec3 xn = x[cs] + arm;
    maxd2 = std::max(maxd2, (xn - p.x[i]).squaredNorm());
    p.x[i] = xn;
    p.v[i] = v[cs] + w[cs].cross(arm);
    p.w[i] = w[cs];
  }
  return std::sqrt(maxd2);
}

void ClumpBodies::set_member_velocities(Particles& p) const {
  for (std::size_t i = 0; i < p.size(); ++i) {
    const auto c = p.clump[i];
    if (c < 0) continue;
    const auto cs = static_cast<std::size_t>(c);
    p.v[i] = v[cs] + w[cs].cross(p.x[i] - x[cs]);
    p.w[i] = w[cs];
  }
}

void ClumpBodies::gather(const Particles& p, const Vec3& gravity) {
  std::fill(f.begin(), f.end(), Vec3::Zero());
  std::fill(t.begin(), t.end(), Vec3::Zero());
  for (std::size_t i = 0; i < p.size(); ++i) {
    const auto c = p.clump[i];
    if (c < 0) continue;
    const auto cs = static_cast<std::size_t>(c);
    f[cs] += p.f[i];
    t[cs] += p.t[i] + (p.x[i] - x[cs]).cross(p.f[i]);
  }
  // The members carry m_k g at their own centres; their mass-weighted centre need not be the union's
  // centre of mass, so remove the spurious gravity torque (R sum m_k b_k) x g.
  for (std::size_t c = 0; c < size(); ++c) t[c] -= (rot[c] * member_moment[c]).cross(gravity);
}

void ClumpBodies::compact(const std::vector<char>& keep, Particles& p) {
  std::vector<std::int32_t> remap(size(), -1);
  std::size_t n = 0;
  for (std::size_t c = 0; c < size(); ++c) {
    if (!keep[c]) continue;
    remap[c] = static_cast<std::int32_t>(n);
    if (n != c) {
      x[n] = x[c]; v[n] = v[c]; q[n] = q[c]; rot[n] = rot[c]; L[n] = L[c]; w[n] = w[c];
      f[n] = f[c]; t[n] = t[c]; mass[n] = mass[c]; inv_inertia[n] = inv_inertia[c];
      member_moment[n] = member_moment[c]; shape[n] = shape[c]; members[n] = members[c]; id[n] = id[c];
    }
    ++n;
  }
  auto cut = [n](auto& a) { a.resize(n); };
  cut(x); cut(v); cut(q); cut(rot); cut(L); cut(w); cut(f); cut(t); cut(mass); cut(inv_inertia);
  cut(member_moment); cut(shape); cut(members); cut(id);
  for (auto& c : p.clump)
    if (c >= 0) c = remap[static_cast<std::size_t>(c)];
}

double ClumpBodies::translational_energy() const {
  double e = 0.0;
  for (std::size_t c = 0; c < size(); ++c) e += 0.5 * mass[c] * v[c].squaredNorm();
  return e;
}

double ClumpBodies::rotational_energy() const {
  double e = 0.0;
  for (std::size_t c = 0; c < size(); ++c) e += 0.5 * L[c].dot(w[c]);
  return e;
}

}  // namespace chutelab::dem
