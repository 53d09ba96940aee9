#pragma once
// What every contact law sees: the geometry and relative motion of one contact, and what it returns.
// Convention: body i is a sphere; body j is a sphere or a wall. n is the unit normal from i towards j,
// delta > 0 the overlap, v_rel the velocity of i's surface point at the contact relative to j's.
#include <cmath>

#include "dem/contact/lane_vec.h"
#include "dem/material.h"
#include "dem/types.h"

namespace chutelab::dem {

struct ContactKinematics {
  LaneVec n;
  double delta;
  LaneVec v_rel;   // (v_i + w_i x R_i n) - (v_j + w_j x (-R_j n))
  LaneVec w_rel;   // w_i - w_j
  double r_i;   // lever arm of i (its radius)
  double r_j;   // lever arm of j (0 for a wall)
  double r_eff; // R* = R_i R_j / (R_i + R_j); R_i for a wall
  double m_eff; // m* = m_i m_j / (m_i + m_j); m_i for a wall
  double inv_inertia_i;
  double inv_inertia_j;  // 0 for a wall (infinite inertia)
  double m_i;
  double m_j;            // 0 means infinite (wall)
};

// The kinematics of a contact between spheres i and j from d = x_j - x_i (the pair touches, so
// |d| > 0), their radii, contact masses, inverse moments of inertia, v_i - v_j and spins.
CHUTELAB_INLINE ContactKinematics sphere_pair_kinematics(const LaneVec& d, double ri, double rj, double mi, double mj,
                                                         double inv_inertia_i, double inv_inertia_j, const LaneVec& dv,
                                                         const LaneVec& wi, const LaneVec& wj) {
  const double dist = std::sqrt(d.squared_norm());
  ContactKinematics k;
  k.n = d * (1.0 / dist);
  k.delta = ri + rj - dist;
  k.r_i = ri;
  k.r_j = rj;
  k.v_rel = dv + (ri * wi + rj * wj).cross(k.n);
  k.w_rel = wi - wj;
  k.r_eff = ri * rj / (ri + rj);
  k.m_eff = mi * mj / (mi + mj);
  k.inv_inertia_i = inv_inertia_i;
  k.inv_inertia_j = inv_inertia_j;
  k.m_i = mi;
  k.m_j = mj;
  return k;
}

// The normal law's answer: signed normal force (> 0 pushes the bodies apart) and the stiffness and
// damping coefficient the tangential spring uses at this overlap.
struct NormalResult {
  double force;  // N
  double kn;     // tangent normal stiffness dF/d(delta), N/m
  double kt;     // tangential stiffness, N/m
  double ct;     // tangential damping coefficient, N s/m
};

// The two parts of a normal law (spring_and_damping.h): a spring's answer at an overlap.
struct SpringForce {
  double force;             // elastic normal force, N (> 0 pushes the bodies apart)
  double kn;                // tangent normal stiffness dF/d(delta), N/m
  double kt;                // tangential stiffness, N/m
  double tangential_ratio;  // sqrt(kt / kn), when the spring keeps it per pair (fixed_tangential_ratio)
};

// A damping part's answer at an overlap: the dashpots' coefficients, N s/m.
struct Dashpot {
  double cn;  // normal: F_d = cn d(delta)/dt
  double ct;  // tangential, for the tangential spring
};

// Force on i (the force on j is its negative) and torques on i and j about their centres.
struct ContactForce {
  LaneVec force;
  LaneVec torque_i;
  LaneVec torque_j;
};

}  // namespace chutelab::dem
