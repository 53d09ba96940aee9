#pragma once
// What every contact law sees: the geometry and relative motion of one contact, and what it returns.
// Convention: body i is a sphere; body j is a sphere or a wall. n is the unit normal from i towards j,
// delta > 0 the overlap, v_rel the velocity of i's surface point at the contact relative to j's.
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

// The normal law's answer: signed normal force (> 0 pushes the bodies apart) and the stiffness and
// damping coefficient the tangential spring uses at this overlap.
struct NormalResult {
  double force;  // N
  double kn;     // tangent normal stiffness dF/d(delta), N/m
  double kt;     // tangential stiffness, N/m
  double ct;     // tangential damping coefficient, N s/m
};

// Force on i (the force on j is its negative) and torques on i and j about their centres.
struct ContactForce {
  LaneVec force;
  LaneVec torque_i;
  LaneVec torque_j;
};

}  // namespace chutelab::dem
