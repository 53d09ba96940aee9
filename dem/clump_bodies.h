#pragma once
// The rigid bodies of the clumps in a scene (structure of arrays) and their time integration.
//
// Each member sphere of a clump is an ordinary particle (so neighbour search, contact laws, walls,
// sinks, sensors and VTK output treat it like any sphere); the body owns the dynamics. Per step:
//   kick(dt/2)   V += dt/2 F/M, L += dt/2 T            (with the forces of the last evaluation)
//   drift(dt)    X += dt V, q rotated torque-free (dem/rigid_rotation.h)
//   place        member x = X + R(q) b, v = V + w x (x - X), w = w(q, L)
//   ... contact forces on the member spheres ...
//   gather       F = sum f_k, T = sum (x_k - X) x f_k + t_k  (gravity corrected to act at the centre of mass)
//   kick(dt/2) and place velocities again.
// Summation is over particles in index order, so results do not depend on the number of threads.
#include <cstdint>
#include <memory>
#include <vector>

#include "dem/clump.h"
#include "dem/particles.h"
#include "dem/rigid_rotation.h"
#include "dem/types.h"

namespace chutelab::dem {

struct ClumpBodies {
  std::vector<ClumpShape> shapes;  // templates, referenced by index

  std::vector<Vec3> x;             // centre of mass, m
  std::vector<Vec3> v;             // m/s
  std::vector<Quat> q;             // orientation, body (principal frame) -> world
  std::vector<Mat3> rot;           // R(q), refreshed with q
  std::vector<Vec3> L;             // angular momentum about the centre of mass, world frame, kg m^2/s
  std::vector<Vec3> w;             // angular velocity, world frame (derived from q and L)
  std::vector<Vec3> f, t;          // force and torque about the centre of mass of the last evaluation
  std::vector<double> mass;        // kg
  std::vector<Vec3> inv_inertia;   // 1/(kg m^2), principal, body frame
  std::vector<Vec3> member_moment; // sum of member mass share x offset (body frame), kg m
  std::vector<std::int32_t> shape;
  std::vector<std::int32_t> members;  // number of member spheres
  std::vector<std::int64_t> id;       // persistent body id

  std::size_t size() const { return x.size(); }
  int add_shape(const ClumpShape& s);

  // Appends a body (its member particles are added by the caller); returns its index.
  std::int32_t add(int shape_index, const Vec3& position, const Quat& orientation, const Vec3& velocity,
                   const Vec3& omega, double density, std::int64_t ident);
  // Mass of member k of a body of this shape and density: its sphere's share of the union's mass.
  double member_mass(int shape_index, std::size_t k, double density) const;

  void kick(double half_dt);
  void kick_momenta(double half_dt);  // the same without refreshing w (drift() refreshes it next)
  void drift(double dt);
  // Sets x, v, w of every member from its body; returns the largest distance a member moved.
  double place_members(Particles& p) const;
  // Sets v, w of every member from its body.
  void set_member_velocities(Particles& p) const;
  // Sums the member forces into body forces and torques; gravity (already on the members as m_k g)
  // is moved to act at the centre of mass.
  void gather(const Particles& p, const Vec3& gravity);
  // Keeps the bodies with keep[c] != 0 and renumbers the members' body indices.
  void compact(const std::vector<char>& keep, Particles& p);

  double translational_energy() const;
  double rotational_energy() const;
};

}  // namespace chutelab::dem
