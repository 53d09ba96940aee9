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

// sin and cos of x; a short series for the small angles of one time step (|x| < 0.01: the first
// omitted terms are below 1e-20 relative), which spares the library call that otherwise dominates
// a clump's update.
inline void small_angle_sincos(double x, double& s, double& c) {
  if (std::abs(x) < 1e-2) {
    const double x2 = x * x;
    s = x * (1.0 - x2 / 6.0 * (1.0 - x2 / 20.0 * (1.0 - x2 / 42.0)));
    c = 1.0 - x2 / 2.0 * (1.0 - x2 / 12.0 * (1.0 - x2 / 30.0));
  } else {
    s = std::sin(x);
    c = std::cos(x);
  }
}

// Advances the orientation q (body -> world) of a torque-free body with world angular momentum L
// (constant) over h.
inline void rotate_free(Quat& q, const Vec3& L, const Vec3& inv_inertia_body, double h) {
  Vec3 Lb = q.conjugate() * L;  // body-frame angular momentum
  auto about = [&](int axis, double tau) {
    const double phi = tau * Lb[axis] * inv_inertia_body[axis];
    if (phi == 0.0) return;
    double s, c;  // of phi / 2
    small_angle_sincos(0.5 * phi, s, c);
    // The body turns by phi about its own axis e: q <- q * (cos phi/2, sin phi/2 e) ...
    Quat r(c, 0.0, 0.0, 0.0);
    r.vec()[axis] = s;
    q = q * r;
    // ... and, seen from the body, the (fixed) world vector L turns by -phi about e.
    const double cp = c * c - s * s, sp = 2.0 * s * c;
    const int i = (axis + 1) % 3, j = (axis + 2) % 3;
    const double li = Lb[i], lj = Lb[j];
    Lb[i] = cp * li + sp * lj;
    Lb[j] = -sp * li + cp * lj;
  };
  about(0, 0.5 * h);
  about(1, 0.5 * h);
  about(2, h);
  about(1, 0.5 * h);
  about(0, 0.5 * h);
  // Unit length against round-off: one Newton step for 1/|q| (|q| stays within 1e-15 of 1), without
  // the square root and division of a full normalisation.
  q.coeffs() *= 1.5 - 0.5 * q.squaredNorm();
}

// Rotational kinetic energy 1/2 L . w.
inline double rotational_energy(const Quat& q, const Vec3& L, const Vec3& inv_inertia_body) {
  return 0.5 * L.dot(angular_velocity(q, L, inv_inertia_body));
}

}  // namespace chutelab::dem
