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

// The wall contacts go through the contact law in chunks, as the pairs do (dem/pair_loop.h): the
// detection and the relative motion are per contact, the law then runs over a chunk of touching
// contacts that share one material pair as one vectorised loop, and what follows from its force is
// per contact again. Each contact writes only its own list entry, so the order in which chunks run
// changes no number, and every lane does the operations the one-at-a-time call did (no contraction,
// no reassociation: the same bits). A station's contacts mix the belt's, the pulley's and the
// plate's materials, so a few chunks fill side by side, one per material pair.
constexpr std::size_t kWallChunk = 32;

struct WallChunk {
  std::int32_t q[kWallChunk], i[kWallChunk];  // list entry and particle of each touching contact
  double nx[kWallChunk], ny[kWallChunk], nz[kWallChunk], delta[kWallChunk];
  double vx[kWallChunk], vy[kWallChunk], vz[kWallChunk];  // v_rel
  double wx[kWallChunk], wy[kWallChunk], wz[kWallChunk];  // w_rel
  double r[kWallChunk], m[kWallChunk], ii[kWallChunk];
  double sx[kWallChunk], sy[kWallChunk], sz[kWallChunk];  // tangential history, in and out
  double ox[kWallChunk], oy[kWallChunk], oz[kWallChunk];  // rolling history, in and out
  double fx[kWallChunk], fy[kWallChunk], fz[kWallChunk];  // force on the particle
  double tx[kWallChunk], ty[kWallChunk], tz[kWallChunk];  // torque on the particle
};

// Lane c of a chunk through the contact law, the wall as body j (no radius, infinite mass and inertia).
template <class Model>
CHUTELAB_INLINE void wall_chunk_contact(WallChunk& h, std::size_t c, const typename Model::Coeffs& pc, double dt) {
  ContactKinematics kin;
  kin.n = {h.nx[c], h.ny[c], h.nz[c]};
  kin.delta = h.delta[c];
  kin.r_i = h.r[c];
  kin.r_j = 0.0;
  kin.v_rel = {h.vx[c], h.vy[c], h.vz[c]};
  kin.w_rel = {h.wx[c], h.wy[c], h.wz[c]};
  kin.r_eff = h.r[c];
  kin.m_eff = h.m[c];
  kin.inv_inertia_i = h.ii[c];
  kin.inv_inertia_j = 0.0;
  kin.m_i = h.m[c];
  kin.m_j = 0.0;
  LaneVec sh{h.sx[c], h.sy[c], h.sz[c]}, ro{h.ox[c], h.oy[c], h.oz[c]};
  const ContactForce cf = Model::compute(pc, kin, sh, &ro, dt);
  h.fx[c] = cf.force.x, h.fy[c] = cf.force.y, h.fz[c] = cf.force.z;
  h.tx[c] = cf.torque_i.x, h.ty[c] = cf.torque_i.y, h.tz[c] = cf.torque_i.z;
  h.sx[c] = sh.x, h.sy[c] = sh.y, h.sz[c] = sh.z;
  h.ox[c] = ro.x, h.oy[c] = ro.y, h.oz[c] = ro.z;
}

// The wall contacts of a thread's particles: the chunks being filled, one per material pair.
template <class Model>
class WallContactChunks {
 public:
  explicit WallContactChunks(const WallForceArrays<typename Model::Coeffs>& a) : a_(a) {}
  WallContactChunks(const WallContactChunks&) = delete;
  WallContactChunks& operator=(const WallContactChunks&) = delete;

  // Runs what is left in the chunks; the list's entries are final after it.
  void finish() {
    for (std::size_t k = 0; k < kSlots; ++k) flush(k);
  }

  // The entries [k, kend) of particle i on one wall, with their detected geometry: a touching
  // entry joins its material pair's chunk; a contact that ended forgets its history.
  void add_group(std::size_t i, std::size_t k, std::size_t kend, const WallHit* geo, const char* hit) {
    WallContactList& list = *a_.list;
    const std::size_t wi = static_cast<std::size_t>(list.wall[k]);
    const Wall& wl = a_.walls[wi];
    const WallFrame& fr = a_.frames[wi];
    const auto kind = static_cast<std::int32_t>(static_cast<std::size_t>(a_.mat[i]) * a_.nmat + static_cast<std::size_t>(wl.material));
    const Vec3 v = a_.v[i], w = a_.w[i];
    const double r = a_.rad[i];
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
      const std::size_t s = slot_for(kind);
      WallChunk& h = chunk_[s];
      const std::size_t c = n_[s]++;
      h.q[c] = static_cast<std::int32_t>(q);
      h.i[c] = static_cast<std::int32_t>(i);
      h.nx[c] = g.n.x(), h.ny[c] = g.n.y(), h.nz[c] = g.n.z();
      h.delta[c] = g.delta;
      Vec3 v_rel = v + (r * w).cross(g.n);
      if (!fr.still) v_rel -= fr.velocity_at(wl, g.point);
      h.vx[c] = v_rel.x(), h.vy[c] = v_rel.y(), h.vz[c] = v_rel.z();
      const Vec3 w_rel = w - fr.ww;
      h.wx[c] = w_rel.x(), h.wy[c] = w_rel.y(), h.wz[c] = w_rel.z();
      h.r[c] = r;
      h.m[c] = a_.mass[i];
      h.ii[c] = a_.inv_inertia[i];
      const Vec3& sh = list.shear[q];
      h.sx[c] = sh.x(), h.sy[c] = sh.y(), h.sz[c] = sh.z();
      const Vec3& ro = list.roll[q];
      h.ox[c] = ro.x(), h.oy[c] = ro.y(), h.oz[c] = ro.z();
      list.point[q] = g.point;
      if (n_[s] == kWallChunk) flush(s);
    }
  }

 private:
  static constexpr std::size_t kSlots = 4;

  // The chunk of this material pair; else an empty one, else the fullest is run first and reused.
  std::size_t slot_for(std::int32_t kind) {
    std::size_t empty = kSlots, fullest = 0;
    for (std::size_t s = 0; s < kSlots; ++s) {
      if (n_[s] > 0 && kind_[s] == kind) return s;
      if (n_[s] == 0 && empty == kSlots) empty = s;
      if (n_[s] > n_[fullest]) fullest = s;
    }
    const std::size_t s = empty < kSlots ? empty : fullest;
    if (n_[s] > 0) flush(s);
    kind_[s] = kind;
    return s;
  }

  void flush(std::size_t s) {
    const std::size_t n = n_[s];
    if (n == 0) return;
    n_[s] = 0;
    WallChunk& h = chunk_[s];
    const typename Model::Coeffs pc = a_.coeffs[static_cast<std::size_t>(kind_[s])];
    const double dt = a_.dt;
#if !defined(__clang__)  // clang (the fuzz build) does not know the pragma and would warn
#pragma GCC ivdep
#endif
    for (std::size_t c = 0; c < n; ++c) wall_chunk_contact<Model>(h, c, pc, dt);
    WallContactList& list = *a_.list;
    for (std::size_t c = 0; c < n; ++c) {
      const auto q = static_cast<std::size_t>(h.q[c]);
      const auto i = static_cast<std::size_t>(h.i[c]);
      const std::size_t wi = static_cast<std::size_t>(list.wall[q]);
      const Wall& wl = a_.walls[wi];
      const WallFrame& fr = a_.frames[wi];
      list.shear[q] = Vec3(h.sx[c], h.sy[c], h.sz[c]);
      list.roll[q] = Vec3(h.ox[c], h.oy[c], h.oz[c]);
      list.touch[q] = 1;
      list.force[q] = Vec3(h.fx[c], h.fy[c], h.fz[c]);
      list.torque[q] = Vec3(h.tx[c], h.ty[c], h.tz[c]);
      // The wall's torque from this contact, here in the parallel part: the wall loads then only
      // add, in entry order (dem/wall_loads.h).
      const Vec3& point = list.point[q];
      const Vec3 x = a_.x[i];
      const double r = a_.rad[i];
      const Vec3 fw = -list.force[q];
      const Vec3 towards = (point - x).normalized();
      const Vec3 lever = r * towards;
      const Vec3 rolling_couple = list.torque[q] - lever.cross(list.force[q]);  // on the particle
      list.wall_torque[q] = (point - fr.load_point).cross(fw) - rolling_couple;
      if (a_.observed[wi]) {
        list.observed_normal[q] = towards;
        // The slip velocity the contact law saw: the sphere's surface point against the wall's.
        list.observed_velocity[q] = a_.v[i] + (r * a_.w[i]).cross(towards) - wl.velocity_at(point);
      }
    }
  }

  const WallForceArrays<typename Model::Coeffs>& a_;
  WallChunk chunk_[kSlots];
  std::size_t n_[kSlots] = {};
  std::int32_t kind_[kSlots] = {};
};

// The wall contacts of particle i, wall by wall, into the thread's chunks.
template <class Model>
void particle_wall_forces(WallContactChunks<Model>& chunks, const WallForceArrays<typename Model::Coeffs>& a, std::size_t i) {
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
    chunks.add_group(i, k, kend, geo, hit);
    k = kend;
  }
}

}  // namespace chutelab::dem
