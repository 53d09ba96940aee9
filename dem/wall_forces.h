#pragma once
// The particle-wall contacts through the contact law: the wall contact detector gives the geometry
// (dem/walls/wall_contact_detector.h), and the same contact model as the pairs' gives the force, with
// the wall as body j (infinite mass and inertia, no radius). Included by dem/forces.cpp only.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "dem/contact/kinematics.h"
#include "dem/material.h"
#include "dem/types.h"
#include "dem/walls/wall.h"
#include "dem/walls/wall_contact_detector.h"
#include "dem/walls/wall_contact_list.h"

namespace chutelab::dem {

// A wall's motion at the current time, for the contacts: Wall::velocity_at, angular_velocity and
// to_world(load_point) with their per-wall products taken once per wall and step, not per particle
// near it (the same operations on the same values, so the same numbers).
struct WallFrame {
  Vec3 ww, surf_lin, surf_omega, surf_centre, load_point;
  bool still, surface;
  static WallFrame of(const Wall& wl) {
    WallFrame fr;
    fr.ww = wl.angular_velocity();
    fr.still = !wl.motion.moving() && wl.surface.zero();
    fr.surface = !wl.surface.zero();
    fr.surf_lin = fr.surface ? Vec3(wl.rotation * wl.surface.linear) : Vec3::Zero();
    fr.surf_omega = fr.surface ? Vec3(wl.rotation * wl.surface.omega) : Vec3::Zero();
    fr.surf_centre = fr.surface ? wl.to_world(wl.surface.centre) : Vec3::Zero();
    fr.load_point = wl.to_world(wl.load_point);
    return fr;
  }
  // Wall::velocity_at(pt).
  Vec3 velocity_at(const Wall& wl, const Vec3& pt) const {
    Vec3 vw = wl.motion.velocity + wl.motion.omega.cross(pt - wl.pivot_now);
    if (surface) vw += surf_lin + surf_omega.cross(pt - surf_centre);
    return vw;
  }
};

// What the wall contacts read and write.
template <class Coeffs>
struct WallForceArrays {
  const Vec3* x;
  const Vec3* v;
  const Vec3* w;
  const double* rad;
  const double* mass;  // the contact mass (a clump sphere's body)
  const double* inv_inertia;
  const std::int32_t* mat;
  const Wall* walls;
  const WallFrame* frames;
  const std::uint8_t* observed;  // per wall: 1 if an observer reads its contacts
  const Coeffs* coeffs;          // the contact model's per material pair, row-major
  std::size_t nmat;
  double dt;
  WallContactList* list;
};

// The entries [k, kend) of particle i on one wall, through the contact law Model: each touching
// entry's force, torque, point, the wall's torque, and what an observer reads; a contact that ended
// forgets its history.
template <class Model>
void wall_group_forces(const WallForceArrays<typename Model::Coeffs>& a, std::size_t i, std::size_t k, std::size_t kend, const WallHit* geo,
                       const char* hit) {
  WallContactList& list = *a.list;
  const std::size_t wi = static_cast<std::size_t>(list.wall[k]);
  const Wall& wl = a.walls[wi];
  const WallFrame& fr = a.frames[wi];
  const typename Model::Coeffs& c = a.coeffs[static_cast<std::size_t>(a.mat[i]) * a.nmat + static_cast<std::size_t>(wl.material)];
  const Vec3 x = a.x[i], v = a.v[i], w = a.w[i];
  const double r = a.rad[i], m = a.mass[i];
  for (std::size_t q = k; q < kend; ++q) {
    if (!hit[q - k]) {
      if (list.touch[q]) {
        list.touch[q] = 0;
        list.shear[q].setZero();
        list.roll[q].setZero();
      }
      continue;
    }
    const WallHit& g = geo[q - k];
    ContactKinematics kin;
    kin.n = LaneVec::of(g.n);
    kin.delta = g.delta;
    kin.r_i = r;
    kin.r_j = 0.0;
    Vec3 v_rel = v + (r * w).cross(g.n);
    if (!fr.still) v_rel -= fr.velocity_at(wl, g.point);
    kin.v_rel = LaneVec::of(v_rel);
    kin.w_rel = LaneVec::of(w - fr.ww);
    kin.r_eff = r;
    kin.m_eff = m;
    kin.inv_inertia_i = a.inv_inertia[i];
    kin.inv_inertia_j = 0.0;
    kin.m_i = m;
    kin.m_j = 0.0;
    LaneVec sh = LaneVec::of(list.shear[q]), ro = LaneVec::of(list.roll[q]);
    const ContactForce cf = Model::compute(c, kin, sh, &ro, a.dt);
    list.shear[q] = sh.eigen();
    list.roll[q] = ro.eigen();
    list.touch[q] = 1;
    list.force[q] = cf.force.eigen();
    list.torque[q] = cf.torque_i.eigen();
    list.point[q] = g.point;
    // The wall's torque from this contact, here in the parallel part: the wall loads then only add,
    // in entry order (dem/wall_loads.h).
    const Vec3 fw = -list.force[q];
    const Vec3 towards = (g.point - x).normalized();
    const Vec3 lever = r * towards;
    const Vec3 rolling_couple = list.torque[q] - lever.cross(list.force[q]);  // on the particle
    list.wall_torque[q] = (g.point - fr.load_point).cross(fw) - rolling_couple;
    if (a.observed[wi]) {
      list.observed_normal[q] = towards;
      // The slip velocity the contact law saw: the sphere's surface point against the wall's.
      list.observed_velocity[q] = v + (r * w).cross(towards) - wl.velocity_at(g.point);
    }
  }
}

// The wall contacts of particle i, wall by wall.
template <class Model>
void particle_wall_forces(const WallForceArrays<typename Model::Coeffs>& a, std::size_t i) {
  const WallContactList& list = *a.list;
  const auto b = static_cast<std::size_t>(list.begin[i]);
  const auto e = static_cast<std::size_t>(list.begin[i + 1]);
  thread_local std::vector<WallHit> geo_big;  // only for a particle touching many triangles
  thread_local std::vector<char> hit_big;
  WallHit geo_small[16];
  char hit_small[16];
  for (std::size_t k = b; k < e;) {
    const std::int32_t wall = list.wall[k];
    std::size_t kend = k;
    while (kend < e && list.wall[kend] == wall) ++kend;
    WallHit* geo = geo_small;
    char* hit = hit_small;
    if (kend - k > 16) {
      geo_big.resize(kend - k);
      hit_big.resize(kend - k);
      geo = geo_big.data();
      hit = hit_big.data();
    }
    std::fill(hit, hit + (kend - k), char{0});
    wall_contacts(a.walls[static_cast<std::size_t>(wall)], list.element.data() + k, kend - k, a.x[i], a.rad[i], geo, hit);
    wall_group_forces<Model>(a, i, k, kend, geo, hit);
    k = kend;
  }
}

}  // namespace chutelab::dem
