#pragma once
// Sphere state as a structure of arrays: each field is one contiguous array so the contact loop reads
// only what it needs (position and radius for the distance test, velocities for the forces). Index
// order changes when the neighbour list sorts particles spatially; id is the persistent identity.
#include <cstdint>
#include <vector>

#include "dem/types.h"
#include "dem/team.h"

namespace chutelab::dem {

struct Particles {
  std::vector<Vec3> x;       // position, m
  std::vector<Vec3> v;       // velocity, m/s
  std::vector<Vec3> w;       // angular velocity, rad/s
  std::vector<Vec3> f;       // force of the last evaluation, N
  std::vector<Vec3> t;       // torque of the last evaluation, N m
  std::vector<double> radius;       // m
  std::vector<double> mass;         // kg
  std::vector<double> inv_mass;     // 1/kg
  std::vector<double> inv_inertia;  // 1/(kg m^2), solid sphere I = 2/5 m R^2
  std::vector<std::int32_t> material;
  std::vector<std::int64_t> id;
  // Rigid multi-sphere particles (dem/clump_bodies.h): the body a sphere belongs to (-1: a free sphere)
  // and its centre in the body's principal frame. A member's x, v, w are set from its body every step;
  // its mass is its share of the body's mass (so sums over spheres give the right totals).
  std::vector<std::int32_t> clump;
  std::vector<Vec3> body_offset;
  std::vector<double> contact_mass;  // kg the contact laws use: the sphere's mass, or its clump's
  // >= 0: held by that inserter (Inserter::hold_to_face): moved at its velocity v, never kicked.
  std::vector<std::int32_t> held_by;

  std::size_t size() const { return x.size(); }

  void push_back(const Vec3& pos, const Vec3& vel, const Vec3& omega, double r, double m, int mat,
                 std::int64_t ident) {
    x.push_back(pos);
    v.push_back(vel);
    w.push_back(omega);
    f.push_back(Vec3::Zero());
    t.push_back(Vec3::Zero());
    radius.push_back(r);
    mass.push_back(m);
    inv_mass.push_back(1.0 / m);
    inv_inertia.push_back(1.0 / (0.4 * m * r * r));
    material.push_back(mat);
    id.push_back(ident);
    clump.push_back(-1);
    body_offset.push_back(Vec3::Zero());
    contact_mass.push_back(m);
    held_by.push_back(-1);
  }

  // Reorders every array: out[k] = in[order[k]] (order may also drop entries). threads > 1 gathers
  // in parallel; the result does not depend on it.
  void permute(const std::vector<std::int32_t>& order, int threads = 1) {
    gather(x, spare_vec3_, order, threads);
    gather(v, spare_vec3_, order, threads);
    gather(w, spare_vec3_, order, threads);
    gather(f, spare_vec3_, order, threads);
    gather(t, spare_vec3_, order, threads);
    gather(radius, spare_double_, order, threads);
    gather(mass, spare_double_, order, threads);
    gather(inv_mass, spare_double_, order, threads);
    gather(inv_inertia, spare_double_, order, threads);
    gather(material, spare_int_, order, threads);
    gather(id, spare_id_, order, threads);
    gather(clump, spare_int_, order, threads);
    gather(body_offset, spare_vec3_, order, threads);
    gather(contact_mass, spare_double_, order, threads);
    gather(held_by, spare_int_, order, threads);
  }

 private:
  // Each array is gathered into a spare one of its type, which then takes its place; the old one is
  // the spare for the next. Kept between rebuilds: a fresh array each time is first zero-filled by
  // one thread, and the reordering does not scale (bench bed, 2 threads: 17-19 ms with fresh arrays,
  // 8.4 ms with the spares; bench/log/RESULTS.md).
  std::vector<Vec3> spare_vec3_;
  std::vector<double> spare_double_;
  std::vector<std::int32_t> spare_int_;
  std::vector<std::int64_t> spare_id_;

  template <class T>
  static void gather(std::vector<T>& a, std::vector<T>& spare, const std::vector<std::int32_t>& order, int threads) {
    const std::size_t n = order.size();
    if (n > spare.capacity()) {  // the old block goes first: the two are never held together
      spare = std::vector<T>();
      spare.reserve(n + n / 16);
    }
    spare.resize(n);
    T* __restrict out = spare.data();
    const T* __restrict in = a.data();
    const std::int32_t* __restrict ord = order.data();
    on_team(threads, [&] {
#pragma omp for schedule(static)
      for (std::size_t k = 0; k < n; ++k) out[k] = in[static_cast<std::size_t>(ord[k])];
    });
    a.swap(spare);
  }
};

}  // namespace chutelab::dem
