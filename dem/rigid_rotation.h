#pragma once
// Rotation of a rigid body with a diagonal body-frame inertia (a clump in its principal frame),
// integrated with unit quaternions.
//
// Why this scheme: the torque-free rotation of a non-spherical body (the two-sphere pellet spins and
// tumbles in flight) is not a rotation about a fixed axis, so integrating q' = q w/2 with the angular
// velocity of the start of the step drifts in energy and angular momentum. The symmetric splitting of
// Dullweber, Leimkuhler & McLachlan (1997, J. Chem. Phys. 107, 5840) composes exact rotations about the
// three body axes, x(h/2) y(h/2) z(h) y(h/2) x(h/2): each preserves the body angular momentum's norm
// and the world angular momentum exactly, the composition is symplectic and time-reversible, so energy
// errors stay bounded (O(h^2)) over arbitrarily long runs. With torque, the angular momentum is kicked
// by half steps around it, exactly like velocity Verlet for the centre of mass.
#include <cmath>

#include <Eigen/Geometry>

#include "dem/types.h"

namespace chutelab::dem {

using Quat = Eigen::Quaterniond;

// Angular velocity in the world frame from the world angular momentum L and the body-frame inverse
// principal inertia: w = R I_b^-1 R^T L.
inline Vec3 angular_velocity(const Quat& q, const Vec3& L, const Vec3& inv_inertia_body) {
  const Mat3 R = q.toRotationMatrix();
  return R * (inv_inertia_body.cwiseProduct(R.transpose() * L));
}

// Advances the orientation q (body -> world) of a torque-free body with world angular momentum L
// (constant) over h.
inline void rotate_free(Quat& q, const Vec3& L, const Vec3& inv_inertia_body, double h) {
  Vec3 Lb = q.conjugate() * L;  // body-frame angular momentum
  auto about = [&](int axis, double tau) {
    const double phi = tau * Lb[axis] * inv_inertia_body[axis];
    if (phi == 0.0) return;
    const Vec3 e = Vec3::Unit(axis);
    // The body turns by phi about its own axis e: q <- q * rot(phi, e); seen from the body, the
    // (fixed) world vector L turns the other way.
    q = q * Quat(Eigen::AngleAxisd(phi, e));
    Lb = Eigen::AngleAxisd(-phi, e) * Lb;
  };
  about(0, 0.5 * h);
  about(1, 0.5 * h);
  about(2, h);
  about(1, 0.5 * h);
  about(0, 0.5 * h);
  q.normalize();
}

// Rotational kinetic energy 1/2 L . w.
inline double rotational_energy(const Quat& q, const Vec3& L, const Vec3& inv_inertia_body) {
  return 0.5 * L.dot(angular_velocity(q, L, inv_inertia_body));
}

}  // namespace chutelab::dem
