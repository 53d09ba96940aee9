// Contact force evaluation. One template per contact-model combination (no virtual call in the loop);
// compute_forces() picks the instantiation at run time.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <type_traits>

#include <omp.h>
#if defined(__AVX512F__)
#include <immintrin.h>
#endif

#include "dem/walls/closest_point.h"
#include "dem/world.h"

namespace chutelab::dem {
namespace {

struct WallGeom {
  Vec3 n;        // unit, from the sphere centre towards the wall
  double delta;  // overlap
  Vec3 point;    // contact point on the wall surface
  TriFeature feature;
};

bool plane_contact(const Plane& p, const Vec3& x, double r, WallGeom& g) {
  const Vec3 rel = x - p.point;
  const double s = rel.dot(p.normal);
  if (s >= r) return false;
  if (std::abs(rel.dot(p.axis_u)) > p.half_u || std::abs(rel.dot(p.axis_v)) > p.half_v) return false;
  g.n = -p.normal;
  g.delta = r - s;
  g.point = x - s * p.normal;
  g.feature = TriFeature::face;
  return true;
}

bool cylinder_contact(const Cylinder& c, const Vec3& x, double r, WallGeom& g) {
  const Vec3 rel = x - c.point;
  const double a = rel.dot(c.axis);
  if (a < c.axial_min || a > c.axial_max) return false;
  const Vec3 radial = rel - a * c.axis;
  const double rho = radial.norm();
  if (!(rho > 0.0)) return false;
  const Vec3 out = radial / rho;
  const double gap = c.inside ? c.radius - rho : rho - c.radius;  // centre to surface
  if (gap >= r) return false;
  g.n = c.inside ? out : Vec3(-out);
  g.delta = r - gap;
  g.point = c.point + a * c.axis + c.radius * out;
  g.feature = TriFeature::face;
  return true;
}

// Raw views of the arrays the pair loop reads. Kept as plain restrict pointers copied into locals, so
// the compiler holds them in registers (a lambda capturing by reference reloads them per contact).
struct PairArrays {
  const Vec3* x;
  const Vec3* v;
  const Vec3* w;
  const double* rad;
  const double* mass;
  const double* inv_inertia;
  const std::int32_t* mat;
  const std::int32_t* row;
  const std::int32_t* nbr;
  const std::int32_t* slot_row;
  Vec3* shear;
  Vec3* roll;
  std::uint8_t* touch;
  const PairCoeffs* coeffs;
  std::size_t nmat;
  double dt;
  const float* gap;  // NeighborList::gap (CHUTELAB_DEM_PAIR_GAPS)
  float gap_limit;   // a slot whose gap exceeds this does not touch
};

// The contact law runs over chunks of touching pairs (their indices collected by the distance test).
// The loop over a chunk has no branch, so the compiler evaluates several contacts per SIMD
// instruction; the distance test before it and the scatter after it keep the row-by-row order of
// every sum, so the forces do not depend on the chunk size or the thread count.
constexpr std::size_t kChunk = 64;

// Two ways to feed the law, with the same arithmetic (so the same results). With vector gathers
// (AVX2) the law can read the particle state by index inside the vectorised loop. Without them (the
// default x86-64 build: SSE2) indexed loads in that loop would stop the vectoriser, so the state is
// first copied into the chunk's structure-of-arrays scratch by a scalar loop. Which is faster
// depends on the CPU's gathers, not only on whether it has them: on an Intel Xeon the gathers won
// (1.10x), on an AMD EPYC (Zen 4) the copy wins by about as much (bench/RESULTS.md), so AVX2 builds
// carry both and choose at run time (gather_in_law()).
#if defined(__AVX2__)
#define CHUTELAB_DEM_GATHER_IN_LAW 1
#else
#define CHUTELAB_DEM_GATHER_IN_LAW 0
#endif

#if CHUTELAB_DEM_GATHER_IN_LAW
struct GatherChunk {
  std::int32_t i[kChunk], j[kChunk], s[kChunk];  // particles and list slot of each touching pair
  double fx[kChunk], fy[kChunk], fz[kChunk];      // force on i
  double tix[kChunk], tiy[kChunk], tiz[kChunk];   // torque on i
  double tjx[kChunk], tjy[kChunk], tjz[kChunk];   // torque on j
};

// Contact c of a chunk through the contact law. The particle state is read straight from the
// particle arrays by index: inside the vectorised loop these become vector gathers, so no scalar
// copy into the chunk is needed.

template <class Model>
CHUTELAB_INLINE void gather_contact(GatherChunk& h, std::size_t c, const double* __restrict x,
                                   const double* __restrict v, const double* __restrict w,
                                   const double* __restrict rad, const double* __restrict mass,
                                   const double* __restrict inv_inertia, double* __restrict sh,
                                   double* __restrict rl, const PairCoeffs& pc, double dt) {
  // int indices: GCC recognises base[int] as a vector gather, not base[size_t] computed from an int.
  const std::int32_t i = h.i[c], j = h.j[c], s = h.s[c];
  const LaneVec d{x[3 * j] - x[3 * i], x[3 * j + 1] - x[3 * i + 1], x[3 * j + 2] - x[3 * i + 2]};
  const double dist = std::sqrt(d.squared_norm());
  const double ri = rad[i], rj = rad[j], mi = mass[i], mj = mass[j];
  const LaneVec wi{w[3 * i], w[3 * i + 1], w[3 * i + 2]}, wj{w[3 * j], w[3 * j + 1], w[3 * j + 2]};
  ContactKinematics k;
  k.n = d * (1.0 / dist);
  k.delta = ri + rj - dist;
  k.r_i = ri;
  k.r_j = rj;
  k.v_rel = LaneVec{v[3 * i] - v[3 * j], v[3 * i + 1] - v[3 * j + 1], v[3 * i + 2] - v[3 * j + 2]} +
            (ri * wi + rj * wj).cross(k.n);
  k.w_rel = wi - wj;
  k.r_eff = ri * rj / (ri + rj);
  k.m_eff = mi * mj / (mi + mj);
  k.inv_inertia_i = inv_inertia[i];
  k.inv_inertia_j = inv_inertia[j];
  k.m_i = mi;
  k.m_j = mj;
  LaneVec shear{sh[3 * s], sh[3 * s + 1], sh[3 * s + 2]};
  LaneVec roll = LaneVec::zero();
  if constexpr (Model::rolling_history) roll = {rl[3 * s], rl[3 * s + 1], rl[3 * s + 2]};
  const ContactForce cf = Model::compute(pc, k, shear, &roll, dt);
  // Each slot s appears once in a chunk, so these stores never collide.
  sh[3 * s] = shear.x, sh[3 * s + 1] = shear.y, sh[3 * s + 2] = shear.z;
  if constexpr (Model::rolling_history) rl[3 * s] = roll.x, rl[3 * s + 1] = roll.y, rl[3 * s + 2] = roll.z;
  h.fx[c] = cf.force.x, h.fy[c] = cf.force.y, h.fz[c] = cf.force.z;
  h.tix[c] = cf.torque_i.x, h.tiy[c] = cf.torque_i.y, h.tiz[c] = cf.torque_i.z;
  h.tjx[c] = cf.torque_j.x, h.tjy[c] = cf.torque_j.y, h.tjz[c] = cf.torque_j.z;
}

// The contacts gathered in h: the law over all of them (vectorised when they share one material
// pair, as they do in a one-material bed), then their forces scattered in gathering order.
template <class Model>
[[gnu::noinline]] void run_chunk(GatherChunk& h, std::size_t n, const PairArrays& a, Vec3* __restrict f,
                                 Vec3* __restrict t) {
  std::int32_t pair_kind = -1;  // the material pair of every contact in the chunk; -2 if mixed
  for (std::size_t c = 0; c < n; ++c) {
    const auto kind = static_cast<std::int32_t>(static_cast<std::size_t>(a.mat[h.i[c]]) * a.nmat +
                                                static_cast<std::size_t>(a.mat[h.j[c]]));
    pair_kind = pair_kind == -1 || pair_kind == kind ? kind : -2;
  }
  const double* x = a.x->data();
  const double* v = a.v->data();
  const double* w = a.w->data();
  const double* rad = a.rad;
  const double* mass = a.mass;
  const double* ii = a.inv_inertia;
  double* sh = a.shear->data();
  double* rl = a.roll->data();
  const double dt = a.dt;
  if (pair_kind >= 0) {
    const PairCoeffs pc = a.coeffs[static_cast<std::size_t>(pair_kind)];
    // ivdep, not omp simd: under omp simd GCC 12 turns the law's small structs into per-lane
    // arrays and gives up; with ivdep it vectorises the whole law.
#if !defined(__clang__)
#pragma GCC ivdep
#endif
    for (std::size_t c = 0; c < n; ++c) gather_contact<Model>(h, c, x, v, w, rad, mass, ii, sh, rl, pc, dt);
  } else {
    for (std::size_t c = 0; c < n; ++c)
      gather_contact<Model>(h, c, x, v, w, rad, mass, ii, sh, rl,
                           a.coeffs[static_cast<std::size_t>(a.mat[h.i[c]]) * a.nmat +
                                    static_cast<std::size_t>(a.mat[h.j[c]])],
                           dt);
  }
  for (std::size_t c = 0; c < n; ++c) {
    const auto i = static_cast<std::size_t>(h.i[c]);
    const auto j = static_cast<std::size_t>(h.j[c]);
    const Vec3 fc(h.fx[c], h.fy[c], h.fz[c]);
    f[i] += fc;
    t[i] += Vec3(h.tix[c], h.tiy[c], h.tiz[c]);
    f[j] -= fc;
    t[j] += Vec3(h.tjx[c], h.tjy[c], h.tjz[c]);
  }
}

#endif

struct ContactChunk {
  std::int32_t i[kChunk], j[kChunk], s[kChunk];
  double dx[kChunk], dy[kChunk], dz[kChunk];      // x_j - x_i
  double ri[kChunk], rj[kChunk], mi[kChunk], mj[kChunk], ii[kChunk], ij[kChunk];
  double vx[kChunk], vy[kChunk], vz[kChunk];      // v_i - v_j
  double wix[kChunk], wiy[kChunk], wiz[kChunk];
  double wjx[kChunk], wjy[kChunk], wjz[kChunk];
  double sx[kChunk], sy[kChunk], sz[kChunk];      // tangential history, in and out
  double qx[kChunk], qy[kChunk], qz[kChunk];      // rolling history, in and out
  double fx[kChunk], fy[kChunk], fz[kChunk];      // force on i
  double tix[kChunk], tiy[kChunk], tiz[kChunk];   // torque on i
  double tjx[kChunk], tjy[kChunk], tjz[kChunk];   // torque on j
};

// Contact c of a chunk through the contact law.
template <class Model>
CHUTELAB_INLINE void chunk_contact(ContactChunk& h, std::size_t c, const PairCoeffs& pc, double dt) {
  const LaneVec d{h.dx[c], h.dy[c], h.dz[c]};
  const double dist = std::sqrt(d.squared_norm());
  const double ri = h.ri[c], rj = h.rj[c], mi = h.mi[c], mj = h.mj[c];
  const LaneVec wi{h.wix[c], h.wiy[c], h.wiz[c]}, wj{h.wjx[c], h.wjy[c], h.wjz[c]};
  ContactKinematics k;
  k.n = d * (1.0 / dist);
  k.delta = ri + rj - dist;
  k.r_i = ri;
  k.r_j = rj;
  k.v_rel = LaneVec{h.vx[c], h.vy[c], h.vz[c]} + (ri * wi + rj * wj).cross(k.n);
  k.w_rel = wi - wj;
  k.r_eff = ri * rj / (ri + rj);
  k.m_eff = mi * mj / (mi + mj);
  k.inv_inertia_i = h.ii[c];
  k.inv_inertia_j = h.ij[c];
  k.m_i = mi;
  k.m_j = mj;
  LaneVec shear{h.sx[c], h.sy[c], h.sz[c]};
  LaneVec roll = LaneVec::zero();
  if constexpr (Model::rolling_history) roll = {h.qx[c], h.qy[c], h.qz[c]};
  const ContactForce cf = Model::compute(pc, k, shear, &roll, dt);
  h.sx[c] = shear.x, h.sy[c] = shear.y, h.sz[c] = shear.z;
  if constexpr (Model::rolling_history) h.qx[c] = roll.x, h.qy[c] = roll.y, h.qz[c] = roll.z;
  h.fx[c] = cf.force.x, h.fy[c] = cf.force.y, h.fz[c] = cf.force.z;
  h.tix[c] = cf.torque_i.x, h.tiy[c] = cf.torque_i.y, h.tiz[c] = cf.torque_i.z;
  h.tjx[c] = cf.torque_j.x, h.tjy[c] = cf.torque_j.y, h.tjz[c] = cf.torque_j.z;
}

// The contacts gathered in h: the law over all of them (vectorised when they share one material
// pair, as they do in a one-material bed), then their forces scattered in gathering order.
template <class Model>
[[gnu::noinline]] void run_chunk(ContactChunk& h, std::size_t n, const PairArrays& a, Vec3* __restrict f,
                                 Vec3* __restrict t) {
  const Vec3* __restrict v = a.v;
  const Vec3* __restrict w = a.w;
  std::int32_t pair_kind = -1;  // the material pair of every contact in the chunk; -2 if mixed
  for (std::size_t c = 0; c < n; ++c) {
    const auto i = static_cast<std::size_t>(h.i[c]);
    const auto j = static_cast<std::size_t>(h.j[c]);
    const auto s = static_cast<std::size_t>(h.s[c]);
    const auto kind = static_cast<std::int32_t>(static_cast<std::size_t>(a.mat[i]) * a.nmat + static_cast<std::size_t>(a.mat[j]));
    pair_kind = pair_kind == -1 || pair_kind == kind ? kind : -2;
    // x_j - x_i and the radii came with the pair from the distance test (pair_rows).
    h.mi[c] = a.mass[i], h.mj[c] = a.mass[j];
    h.ii[c] = a.inv_inertia[i], h.ij[c] = a.inv_inertia[j];
    const Vec3 dv = v[i] - v[j];
    h.vx[c] = dv.x(), h.vy[c] = dv.y(), h.vz[c] = dv.z();
    h.wix[c] = w[i].x(), h.wiy[c] = w[i].y(), h.wiz[c] = w[i].z();
    h.wjx[c] = w[j].x(), h.wjy[c] = w[j].y(), h.wjz[c] = w[j].z();
    const Vec3& sh = a.shear[s];
    h.sx[c] = sh.x(), h.sy[c] = sh.y(), h.sz[c] = sh.z();
    if constexpr (Model::rolling_history) {
      const Vec3& q = a.roll[s];
      h.qx[c] = q.x(), h.qy[c] = q.y(), h.qz[c] = q.z();
    }
  }
  if (pair_kind >= 0) {
    const PairCoeffs pc = a.coeffs[static_cast<std::size_t>(pair_kind)];
    const double dt = a.dt;
    // ivdep, not omp simd: under omp simd GCC 12 turns the law's small structs into per-lane
    // arrays and gives up; with ivdep it vectorises the whole law.
#if !defined(__clang__)  // clang (the fuzz build) does not know the pragma and would warn
#pragma GCC ivdep
#endif
    for (std::size_t c = 0; c < n; ++c) chunk_contact<Model>(h, c, pc, dt);
  } else {
    for (std::size_t c = 0; c < n; ++c)
      chunk_contact<Model>(h, c,
                           a.coeffs[static_cast<std::size_t>(a.mat[h.i[c]]) * a.nmat +
                                    static_cast<std::size_t>(a.mat[h.j[c]])],
                           a.dt);
  }
  for (std::size_t c = 0; c < n; ++c) {
    const auto i = static_cast<std::size_t>(h.i[c]);
    const auto j = static_cast<std::size_t>(h.j[c]);
    const auto s = static_cast<std::size_t>(h.s[c]);
    a.shear[s] = Vec3(h.sx[c], h.sy[c], h.sz[c]);
    if constexpr (Model::rolling_history) a.roll[s] = Vec3(h.qx[c], h.qy[c], h.qz[c]);
    const Vec3 fc(h.fx[c], h.fy[c], h.fz[c]);
    f[i] += fc;
    t[i] += Vec3(h.tix[c], h.tiy[c], h.tiz[c]);
    f[j] -= fc;
    t[j] += Vec3(h.tjx[c], h.tjy[c], h.tjz[c]);
  }
}


// The distance test of one listed pair (rows i < j, list slot s, `was` its touch flag of the last
// evaluation): the pair goes into the next chunk entry and stays there only if it touches (no branch
// on the outcome, which is a coin toss in a dense bed); a full chunk runs.
template <class Model, class Chunk>
CHUTELAB_INLINE void test_slot(const PairArrays& a, std::size_t i, std::size_t j, std::size_t s, std::uint8_t was,
                               Chunk& h, std::size_t& n, Vec3* __restrict f, Vec3* __restrict t) {
  const double* __restrict rad = a.rad;
  const double rs = rad[i] + rad[j];
  const Vec3 d = a.x[j] - a.x[i];
  const bool hit = d.squaredNorm() < rs * rs;
  // A contact that just ended forgets its history. Rare, so predictable as one test; written as
  // `!hit & touch` GCC branched on touch first, a coin toss in a dense bed.
  if (__builtin_expect(was > static_cast<std::uint8_t>(hit), 0)) {
    a.shear[s].setZero();
    if constexpr (Model::rolling_history) a.roll[s].setZero();
  }
  a.touch[s] = hit;
  h.i[n] = static_cast<std::int32_t>(i);
  h.j[n] = static_cast<std::int32_t>(j);
  h.s[n] = static_cast<std::int32_t>(s);
  if constexpr (std::is_same_v<Chunk, ContactChunk>) {
    // The copy variant's scratch takes what the test already holds in registers, so run_chunk
    // does not load both positions and radii again.
    h.dx[n] = d.x(), h.dy[n] = d.y(), h.dz[n] = d.z();
    h.ri[n] = rad[i], h.rj[n] = rad[j];
  }
  n += hit;
  if (n == kChunk) {
    run_chunk<Model>(h, n, a, f, t);
    n = 0;
  }
}

// The distance test of pair_rows in two passes over batches of slots. First, sixteen at a time with
// AVX-512, the slots that cannot touch are set apart by their gap at the rebuild: no particle has
// moved more than max_disp_ since, so a slot whose gap exceeds twice that (NeighborList::gap) is not
// touching now. Such a slot is handled as the test would handle it (not touching; a contact that
// just ended forgets its history) and the others are compressed into a short list (compressed in
// registers and stored whole: a compressing store to memory is microcoded on Zen 4). Then the full
// test on that list, the same as the scalar loop of pair_rows, in slot order, so the chunks hold
// the same contacts in the same order. With a skin of one radius, in a standard V5-44 station run
// 96 % of the slots do not touch and the gap sets 44 % of all slots apart (more just after a
// rebuild); against the unchanged integrator the pair loop, the law and the gaps together cost 32 %
// less. In the dense bench bed (65 % of the slots touch) little is set apart, and the bed runs ~2 %
// slower.
#if CHUTELAB_DEM_PAIR_GAPS
template <class Model, class Chunk>
void screen_slots_avx512(const PairArrays& a, std::size_t s0, std::size_t s1, Chunk& h, Vec3* __restrict f,
                         Vec3* __restrict t) {
  constexpr std::size_t kBatch = 256;
  std::int32_t ci[kBatch + 16], cj[kBatch + 16], cs[kBatch + 16], cw[kBatch + 16];
  std::uint8_t* __restrict touch = a.touch;
  const __m512 limit = _mm512_set1_ps(a.gap_limit);
  const __m512i lane16 = _mm512_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15);
  auto forget = [&](std::size_t slot) {
    a.shear[slot].setZero();
    if constexpr (Model::rolling_history) a.roll[slot].setZero();
  };
  std::size_t n = 0;
  for (std::size_t b0 = s0; b0 < s1; b0 += kBatch) {
    const std::size_t b1 = std::min(b0 + kBatch, s1);
    std::size_t m = 0;
    for (std::size_t s = b0; s < b1; s += 16) {
      const std::size_t rem = b1 - s;
      const auto lanes = static_cast<__mmask16>(rem >= 16 ? 0xFFFFu : (1u << rem) - 1u);
      // Not greater, rather than less or equal: a NaN gap goes to the full test.
      const __mmask16 maybe = _mm512_mask_cmp_ps_mask(lanes, _mm512_maskz_loadu_ps(lanes, a.gap + s), limit, _CMP_NGT_UQ);
      const __m128i was = _mm_maskz_loadu_epi8(lanes, touch + s);
      for (auto ended = static_cast<unsigned>(_mm_test_epi8_mask(was, was) & ~maybe & lanes); ended != 0; ended &= ended - 1)
        forget(s + static_cast<std::size_t>(__builtin_ctz(ended)));
      _mm_mask_storeu_epi8(touch + s, lanes, _mm_setzero_si128());  // the full test sets its hits
      const __m512i vs = _mm512_add_epi32(_mm512_set1_epi32(static_cast<std::int32_t>(s)), lane16);
      _mm512_storeu_si512(cs + m, _mm512_maskz_compress_epi32(maybe, vs));
      _mm512_storeu_si512(ci + m, _mm512_maskz_compress_epi32(maybe, _mm512_maskz_loadu_epi32(lanes, a.slot_row + s)));
      _mm512_storeu_si512(cj + m, _mm512_maskz_compress_epi32(maybe, _mm512_maskz_loadu_epi32(lanes, a.nbr + s)));
      _mm512_storeu_si512(cw + m, _mm512_maskz_compress_epi32(maybe, _mm512_maskz_cvtepu8_epi32(lanes, was)));
      m += static_cast<std::size_t>(__builtin_popcount(maybe));
    }
    // The full test, the same as pair_rows makes it. Vector gathers were no faster here on Zen 4 in
    // a sparse station list, and slower in a dense bed (bench bed: +47 % in this loop).
    for (std::size_t k = 0; k < m; ++k)
      test_slot<Model>(a, static_cast<std::size_t>(ci[k]), static_cast<std::size_t>(cj[k]), static_cast<std::size_t>(cs[k]),
                       static_cast<std::uint8_t>(cw[k]), h, n, f, t);
  }
  if (n > 0) run_chunk<Model>(h, n, a, f, t);
}
#endif

// Pair contacts of rows [i0, i1), scattered row by row into f/t (a block's partial-sum buffers).
template <class Model, class Chunk>
void pair_rows(const PairArrays& a, std::size_t i0, std::size_t i1, Vec3* __restrict f, Vec3* __restrict t) {
  // On the stack, not thread_local: the libraries are position independent (for the Python module),
  // so a thread_local is reached through a TLS call that GCC may not hoist; it was made once per
  // slot, with every live register spilled around it (about a fifth of the pair loop's time).
  Chunk h;
  const auto s0 = static_cast<std::size_t>(a.row[i0]), s1 = static_cast<std::size_t>(a.row[i1]);
#if CHUTELAB_DEM_PAIR_GAPS
  screen_slots_avx512<Model>(a, s0, s1, h, f, t);
#else
  std::size_t n = 0;
  // One flat loop over the slots (the row of a slot from slot_row): a loop per row would mispredict
  // its exit at almost every row, as rows hold only a few pairs.
  for (std::size_t s = s0; s < s1; ++s)
    test_slot<Model>(a, static_cast<std::size_t>(a.slot_row[s]), static_cast<std::size_t>(a.nbr[s]), s, a.touch[s], h, n, f, t);
  if (n > 0) run_chunk<Model>(h, n, a, f, t);
#endif
}

#if !CHUTELAB_DEM_GATHER_IN_LAW
using GatherChunk = ContactChunk;  // never chosen: gather_in_law() is false without AVX2
#endif

// Whether this CPU's vector gathers beat the scalar copy (see above). Decided once per process from
// the vendor; either way the numbers are the same, only the speed differs. CHUTELAB_DEM_GATHER=0/1
// overrides it, for measuring both on one machine.
bool gather_in_law() {
  static const bool g = [] {
#if CHUTELAB_DEM_GATHER_IN_LAW
    if (const char* e = std::getenv("CHUTELAB_DEM_GATHER"); e && (e[0] == '0' || e[0] == '1')) return e[0] == '1';
    __builtin_cpu_init();
    return __builtin_cpu_is("intel") != 0;
#else
    return false;
#endif
  }();
  return g;
}

}  // namespace

template <class Model>
void World::compute_forces_impl() {
  const std::size_t n = p_.size();
  const int nt = thread_count();
  const double dt = dt_;
  const Vec3 g = settings_.gravity;
  const Vec3* x = p_.x.data();
  const Vec3* v = p_.v.data();
  const Vec3* w = p_.w.data();
  const double* rad = p_.radius.data();
  // Contact laws see a clump sphere's whole body mass (its damping and time scale are those of the body);
  // gravity uses each sphere's share. For free spheres the two are the same number.
  const double* mass = p_.contact_mass.data();
  const double* share = p_.mass.data();
  const double* inv_i = p_.inv_inertia.data();
  const std::int32_t* mat = p_.material.data();
  const std::int32_t* row = nl_.row_begin.data();
  const std::int32_t* nbr = nl_.nbr.data();
  Vec3* shear = nl_.shear.data();
  Vec3* roll = nl_.roll.data();
  std::uint8_t* touch = nl_.touch.data();
  const MaterialTable& mt = materials_;

  const bool gather = gather_in_law();
  // Rounded up: a gap at or below the float limit goes to the full test.
  const double gap_limit = 2.0 * max_disp_ + nl_.gap_eps;
  float gap_limit_f = static_cast<float>(gap_limit);
  if (static_cast<double>(gap_limit_f) < gap_limit) gap_limit_f = std::nextafter(gap_limit_f, std::numeric_limits<float>::infinity());
  PairArrays arrays{x, v, w, rad, mass, inv_i, mat, row, nbr, nl_.slot_row.data(), shear, roll, touch, mt.coeff_table(),
                    static_cast<std::size_t>(mt.size()), dt, nl_.gap.data(), gap_limit_f};
  // Wall::velocity_at, angular_velocity and to_world(load_point) with their per-wall products taken once
  // per wall and step, not per particle near it (the same operations on the same values, so the same
  // numbers): most particles near a wall do not touch it.
  wall_frames_.resize(walls_.size());
  const WallFrame* frames = wall_frames_.data();
  for (std::size_t k = 0; k < walls_.size(); ++k) {
    const Wall& wl = walls_[k];
    WallFrame& fr = wall_frames_[k];
    fr.ww = wl.angular_velocity();
    fr.still = !wl.motion.moving() && wl.surface.zero();
    fr.surface = !wl.surface.zero();
    fr.surf_lin = fr.surface ? Vec3(wl.rotation * wl.surface.linear) : Vec3::Zero();
    fr.surf_omega = fr.surface ? Vec3(wl.rotation * wl.surface.omega) : Vec3::Zero();
    fr.surf_centre = fr.surface ? wl.to_world(wl.surface.centre) : Vec3::Zero();
    fr.load_point = wl.to_world(wl.load_point);
  }
  const std::size_t n_observed = wall_observers_.size();
  if (n_observed > 0) {
    wc_.obs_normal.resize(wc_.wall.size());
    wc_.obs_velocity.resize(wc_.wall.size());
  }
  // Wall contacts of one particle, into per-entry storage. Within one mesh, face contacts win over
  // edge contacts and edges over vertices, so a sphere on a flat or convex seam touches once.
  auto walls_of = [&](std::size_t i) {
    const auto b = static_cast<std::size_t>(wc_.begin[i]);
    const auto e = static_cast<std::size_t>(wc_.begin[i + 1]);
    thread_local std::vector<WallGeom> geo_big;  // only for a particle touching many triangles
    thread_local std::vector<char> hit_big;
    WallGeom geo_small[16];
    char hit_small[16];
    std::size_t k = b;
    while (k < e) {
      const std::size_t wi = static_cast<std::size_t>(wc_.wall[k]);
      std::size_t kend = k;
      while (kend < e && static_cast<std::size_t>(wc_.wall[kend]) == wi) ++kend;
      const Wall& wl = walls_[wi];
      WallGeom* geo = geo_small;
      char* hit = hit_small;
      if (kend - k > 16) {
        geo_big.resize(kend - k);
        hit_big.resize(kend - k);
        geo = geo_big.data();
        hit = hit_big.data();
      }
      std::fill(hit, hit + (kend - k), char{0});
      if (const auto* m = std::get_if<TriangleMesh>(&wl.current)) {
        const double r2 = rad[i] * rad[i];
        for (std::size_t q = k; q < kend; ++q) {
          const auto el = static_cast<std::size_t>(wc_.element[q]);
          const auto& t = m->triangles[el];
          const Vec3& a = m->vertices[static_cast<std::size_t>(t[0])];
          // Many candidates are only within the skin. A sphere farther from the triangle's plane
          // than its radius cannot touch it, and the plane's distance is a dot product where the
          // closest point is a chain of branches. The test leaves a margin (relative 1e-9 of the
          // radius plus the lever) far above the rounding of either distance, and skips slivers
          // (nn = inf), whose normal is inexact, so it rejects only what the full test rejects.
          const Wall::FacePlane& fp = wl.face_plane[el];
          const Vec3 ap = x[i] - a;
          const double s = fp.n.dot(ap);
          const double reach = rad[i] + 1e-9 * (rad[i] + ap.cwiseAbs().sum());
          if (s * s > reach * reach * fp.nn) continue;
          const Vec3& b = m->vertices[static_cast<std::size_t>(t[1])];
          const Vec3& c = m->vertices[static_cast<std::size_t>(t[2])];
          const TriClosest cp = closest_point_on_triangle(x[i], a, b, c);
          const Vec3 d = cp.point - x[i];
          const double d2 = d.squaredNorm();
          if (d2 > r2 * (1.0 + 1e-9)) continue;  // certainly dist > rad[i]: skip the root
          const double dist = std::sqrt(d2);
          WallGeom& gq = geo[q - k];
          if (dist >= rad[i] || !(dist > 0.0)) continue;
          gq.n = d / dist;
          gq.delta = rad[i] - dist;
          gq.point = cp.point;
          gq.feature = cp.feature;
          hit[q - k] = 1;
        }
        // Resolve faces, then edges, then vertices.
        auto tri_has = [&](std::size_t q, std::int32_t vtx) {
          const auto& t = m->triangles[static_cast<std::size_t>(wc_.element[q])];
          return t[0] == vtx || t[1] == vtx || t[2] == vtx;
        };
        auto feature_vertices = [&](std::size_t q, std::int32_t& a, std::int32_t& bb) {
          const auto& t = m->triangles[static_cast<std::size_t>(wc_.element[q])];
          switch (geo[q - k].feature) {
            case TriFeature::edge_ab: a = t[0]; bb = t[1]; break;
            case TriFeature::edge_bc: a = t[1]; bb = t[2]; break;
            case TriFeature::edge_ca: a = t[2]; bb = t[0]; break;
            case TriFeature::vertex_a: a = bb = t[0]; break;
            case TriFeature::vertex_b: a = bb = t[1]; break;
            case TriFeature::vertex_c: a = bb = t[2]; break;
            default: a = bb = -1;
          }
          if (a > bb) std::swap(a, bb);
        };
        for (int pass = 1; pass <= 2; ++pass) {  // 1: edges, 2: vertices
          for (std::size_t q = k; q < kend; ++q) {
            if (!hit[q - k]) continue;
            const TriFeature f = geo[q - k].feature;
            const bool is_edge = f == TriFeature::edge_ab || f == TriFeature::edge_bc || f == TriFeature::edge_ca;
            const bool is_vertex = f == TriFeature::vertex_a || f == TriFeature::vertex_b || f == TriFeature::vertex_c;
            if ((pass == 1 && !is_edge) || (pass == 2 && !is_vertex)) continue;
            std::int32_t a, bb;
            feature_vertices(q, a, bb);
            bool shadowed = false;
            for (std::size_t o = k; o < kend && !shadowed; ++o) {
              if (o == q || !hit[o - k]) continue;
              const TriFeature fo = geo[o - k].feature;
              if (fo == TriFeature::face) {
                shadowed = tri_has(o, a) && tri_has(o, bb);
              } else {
                const bool o_edge = fo == TriFeature::edge_ab || fo == TriFeature::edge_bc || fo == TriFeature::edge_ca;
                std::int32_t oa, ob;
                feature_vertices(o, oa, ob);
                if (pass == 1 && o_edge) shadowed = (oa == a && ob == bb && o < q);
                if (pass == 2 && o_edge) shadowed = (oa == a || ob == a);
                if (pass == 2 && !o_edge) shadowed = (oa == a && o < q);
              }
            }
            if (shadowed) hit[q - k] = 0;
          }
        }
      } else {
        for (std::size_t q = k; q < kend; ++q) {
          WallGeom& gq = geo[q - k];
          if (const auto* p = std::get_if<Plane>(&wl.current))
            hit[q - k] = plane_contact(*p, x[i], rad[i], gq);
          else
            hit[q - k] = cylinder_contact(std::get<Cylinder>(wl.current), x[i], rad[i], gq);
        }
      }
      const PairCoeffs& c = mt.pair(mat[i], wl.material);
      const WallFrame& fr = frames[wi];
      const Vec3& ww = fr.ww;
      const Vec3& load_point = fr.load_point;
      auto wall_velocity_at = [&](const Vec3& pt) {
        Vec3 vw = wl.motion.velocity + wl.motion.omega.cross(pt - wl.pivot_now);
        if (fr.surface) vw += fr.surf_lin + fr.surf_omega.cross(pt - fr.surf_centre);
        return vw;
      };
      for (std::size_t q = k; q < kend; ++q) {
        if (!hit[q - k]) {
          if (wc_.touch[q]) {
            wc_.touch[q] = 0;
            wc_.shear[q].setZero();
            wc_.roll[q].setZero();
          }
          continue;
        }
        const WallGeom& gq = geo[q - k];
        ContactKinematics kin;
        kin.n = LaneVec::of(gq.n);
        kin.delta = gq.delta;
        kin.r_i = rad[i];
        kin.r_j = 0.0;
        Vec3 v_rel = v[i] + (rad[i] * w[i]).cross(gq.n);
        if (!fr.still) v_rel -= wall_velocity_at(gq.point);
        kin.v_rel = LaneVec::of(v_rel);
        kin.w_rel = LaneVec::of(w[i] - ww);
        kin.r_eff = rad[i];
        kin.m_eff = mass[i];
        kin.inv_inertia_i = inv_i[i];
        kin.inv_inertia_j = 0.0;
        kin.m_i = mass[i];
        kin.m_j = 0.0;
        LaneVec sh = LaneVec::of(wc_.shear[q]), ro = LaneVec::of(wc_.roll[q]);
        const ContactForce cf = Model::compute(c, kin, sh, &ro, dt);
        wc_.shear[q] = sh.eigen();
        wc_.roll[q] = ro.eigen();
        wc_.touch[q] = 1;
        wc_.out_f[q] = cf.force.eigen();
        wc_.out_t[q] = cf.torque_i.eigen();
        wc_.out_point[q] = gq.point;
        // The wall's torque from this contact, here in the parallel part: the serial sum below then
        // only adds, in entry order, as it always did (the same numbers at any thread count).
        const Vec3 fw = -wc_.out_f[q];
        const Vec3 towards = (gq.point - x[i]).normalized();
        const Vec3 lever = rad[i] * towards;
        const Vec3 rolling_couple = wc_.out_t[q] - lever.cross(wc_.out_f[q]);  // on the particle
        wc_.out_wall_torque[q] = (gq.point - load_point).cross(fw) - rolling_couple;
        if (wi < n_observed && wall_observers_[wi]) {
          wc_.obs_normal[q] = towards;
          // The slip velocity the contact law saw: the sphere's surface point against the wall's.
          wc_.obs_velocity[q] = v[i] + (rad[i] * w[i]).cross(towards) - wl.velocity_at(gq.point);
        }
      }
      k = kend;
    }
  };

  const std::int32_t* wb = wc_.begin.data();
  const std::uint8_t* wtouch = wc_.touch.data();
  const Vec3* wof = wc_.out_f.data();
  const Vec3* wot = wc_.out_t.data();
  const std::int32_t* owners = wc_.owners.data();
  const std::size_t n_owners = wc_.owners.size();

  // Pair forces into fixed blocks of rows (see world.h), then one pass per particle that adds the
  // block partial sums in block order, its wall contacts and gravity.
  const std::size_t nblocks = nl_.blocks();
  // Each force block also sums the wall loads of its particles' entries, in entry order, into its
  // own share (per wall, and per element touched); the shares are added in block order after the
  // forces. A serial sum over all entries read every entry the other threads had just written
  // (bench bed, 2 threads: their wall contacts 45 % dearer), and fixed blocks, not threads, keep
  // the numbers the same at any thread count.
  const std::size_t nw = walls_.size();
  wall_part_f_.resize(nblocks * nw);
  wall_part_t_.resize(nblocks * nw);
  wall_part_e_.resize(nblocks);
  // A wall of one element (a primitive) needs no shares of its own: its element's sum is its force.
  element_base_.resize(nw);
  bool meshes = false;
  std::size_t slots = 0;
  for (std::size_t k = 0; k < nw; slots += walls_[k].element_force.size(), ++k) {
    element_base_[k] = walls_[k].element_force.size() > 1 ? static_cast<std::int32_t>(slots) : -1;
    meshes = meshes || element_base_[k] >= 0;
  }
  element_slot_.resize(static_cast<std::size_t>(nt));
  for (auto& es : element_slot_)  // every slot a block uses is reset to -1 after it
    if (es.size() != slots) es.assign(slots, -1);
  const std::int32_t* __restrict wall_of = wc_.wall.data();
  const std::int32_t* __restrict element_of = wc_.element.data();
  const Vec3* __restrict wtq = wc_.out_wall_torque.data();
  const std::int32_t* __restrict ebase = element_base_.data();
  Vec3* const part_f = wall_part_f_.data();
  Vec3* const part_t = wall_part_t_.data();
  std::vector<ElementShare>* const part_e = wall_part_e_.data();
  const std::size_t* blo = nl_.block_lo.data();
  const std::size_t* bhi = nl_.block_hi.data();
  const std::size_t* boff = nl_.block_off.data();
  const std::size_t* bfirst = nl_.block_first.data();
  Vec3* bf = nl_.block_f.data();
  Vec3* bt = nl_.block_t.data();
  Vec3* f = p_.f.data();
  Vec3* t = p_.t.data();
  // The particles [lo, hi) of block ob: to each its wall contacts (in entry order) and gravity; from
  // the same entries, the block's share of the wall loads. The shares are summed in the thread's own
  // scratch and stored once at the end: the shares of two threads' blocks may share a cache line,
  // and a store per contact would pass it back and forth.
  auto finish_block = [=](std::size_t ob, std::size_t lo, std::size_t hi, std::int32_t* __restrict slot_of) {
    thread_local std::vector<Vec3> acc;  // allocated by this thread, away from the others' data
    acc.assign(2 * nw, Vec3::Zero());
    Vec3* __restrict sf = acc.data();
    Vec3* __restrict st = acc.data() + nw;
    std::vector<ElementShare> parts = std::move(part_e[ob]);
    parts.clear();
    for (std::size_t i = lo; i < hi; ++i) {
      Vec3 fi = f[i], ti = t[i];
      for (auto q = static_cast<std::size_t>(wb[i]); q < static_cast<std::size_t>(wb[i + 1]); ++q) {
        if (!wtouch[q]) continue;
        fi += wof[q];
        ti += wot[q];
        const auto k = static_cast<std::size_t>(wall_of[q]);
        const Vec3 fw = -wof[q];
        sf[k] += fw;
        st[k] += wtq[q];
      }
      f[i] = fi + share[i] * g;
      t[i] = ti;
    }
    std::copy(sf, sf + nw, part_f + ob * nw);
    std::copy(st, st + nw, part_t + ob * nw);
    if (!meshes) {
      part_e[ob] = std::move(parts);
      return;
    }
    // Apart from the loop above: its rare call (push_back) kept fi and ti on the stack (bench bed,
    // one thread: 3 % slower).
    for (auto q = static_cast<std::size_t>(wb[lo]); q < static_cast<std::size_t>(wb[hi]); ++q) {
      if (!wtouch[q]) continue;
      const std::int32_t base = ebase[wall_of[q]];
      if (base < 0) continue;
      std::int32_t& at = slot_of[base + element_of[q]];
      if (at < 0) {
        at = static_cast<std::int32_t>(parts.size());
        parts.push_back({wall_of[q], element_of[q], Vec3::Zero()});
      }
      parts[static_cast<std::size_t>(at)].f -= wof[q];
    }
    for (const ElementShare& es : parts) slot_of[ebase[es.wall] + es.element] = -1;
    part_e[ob] = std::move(parts);
  };
  // Each thread takes the blocks of its share (cut_, world.h) in every phase: the wall contacts of
  // its particles, its pair blocks, their finishing, and the integrator's passes. So it works on the
  // particles whose state it wrote: on this project's VM a cache line that crosses between the two
  // cores costs ~250-500 ns (bench/core_latency); with dynamic schedules the wall entries and pair
  // blocks changed hands every step (bench bed, 2 threads: 1.30 -> 0.86 s), and a serial sum of the
  // wall loads or wall contacts split by count made a thread read what the other had just written.
  // Which thread takes a block changes no number.
  using Clock = std::chrono::steady_clock;
  cut_.fit(static_cast<std::size_t>(nt), nblocks);
  const bool close = closing_.on;
  closing_.on = false;
  closing_.first_bad.assign(static_cast<std::size_t>(nt), n);
  closing_.maxd2.assign(static_cast<std::size_t>(nt), 0.0);
  const bool timed = nt > 1;
#pragma omp parallel num_threads(nt)
  {
    const auto tn = static_cast<std::size_t>(omp_get_thread_num());
    const auto nth = static_cast<std::size_t>(omp_get_num_threads());
    std::int32_t* slot_of = element_slot_[tn].data();
    const auto [b0, b1] = cut_.blocks(tn, nth, nblocks);
    const auto [r0, r1] = thread_rows(n);
    std::size_t first_bad = n;
    double maxd2 = 0.0;
    const Clock::time_point c0 = timed ? Clock::now() : Clock::time_point{};
    for (const std::int32_t* o = std::lower_bound(owners, owners + n_owners, static_cast<std::int32_t>(r0));
         o < owners + n_owners && static_cast<std::size_t>(*o) < r1; ++o)
      walls_of(static_cast<std::size_t>(*o));
    for (std::size_t b = b0; b < b1; ++b) {
      Vec3* fb = bf + boff[b] - blo[b];  // fb[p] is valid for p in [lo, hi); zero (see below)
      Vec3* tb = bt + boff[b] - blo[b];
      if (gather)
        pair_rows<Model, GatherChunk>(arrays, blo[b], blo[b + 1], fb, tb);
      else
        pair_rows<Model, ContactChunk>(arrays, blo[b], blo[b + 1], fb, tb);
    }
    const Clock::time_point c1 = timed ? Clock::now() : Clock::time_point{};
#pragma omp barrier
    // Per particle the sum is, as always, zero, then the block buffers in block order, then its wall
    // contacts and gravity; here it runs buffer by buffer over the particles of a block, as flat
    // loops. Each buffer entry is read exactly once, by the block that owns its particle, which
    // zeroes it for the next evaluation (layout_blocks zeroes new buffers): no separate pass to
    // clear them. The body force and the held particles follow on the same particles while their
    // forces are in cache (each is per particle, so the split does not change a number).
    const Clock::time_point c2 = timed ? Clock::now() : Clock::time_point{};
    for (std::size_t ob = b0; ob < b1; ++ob) {
      const std::size_t lo = blo[ob], hi = blo[ob + 1];
      // The first buffer that reaches a particle is copied, not added to zero: a buffer never holds
      // -0.0 (it starts at +0.0 and, rounding to nearest, a sum or difference is -0.0 only when it
      // already was), and 0.0 + x is x for every other x. Zero beyond its reach.
      bool first = true;
      for (std::size_t b = bfirst[ob]; b <= ob; ++b) {
        const std::size_t end = std::min(hi, bhi[b]);
        if (end <= lo) continue;
        double* __restrict fs = (bf + boff[b] + (lo - blo[b]))->data();
        double* __restrict ts = (bt + boff[b] + (lo - blo[b]))->data();
        double* __restrict fd = f[lo].data();
        double* __restrict td = t[lo].data();
        const std::size_t m = 3 * (end - lo);
        if (first) {
          for (std::size_t k = 0; k < m; ++k) {
            fd[k] = fs[k];
            td[k] = ts[k];
            fs[k] = 0.0;
            ts[k] = 0.0;
          }
          std::fill(f + end, f + hi, Vec3::Zero());
          std::fill(t + end, t + hi, Vec3::Zero());
          first = false;
          continue;
        }
        for (std::size_t k = 0; k < m; ++k) {
          fd[k] += fs[k];
          td[k] += ts[k];
          fs[k] = 0.0;
          ts[k] = 0.0;
        }
      }
      finish_block(ob, lo, hi, slot_of);
      if (body_force_) body_force_(p_, time_, lo, hi, p_.f);
      // A held particle (Inserter::hold_to_face) feels nothing: with no force the kicks leave its
      // velocity as set, so the drift moves it rigidly. Its partners still feel it.
      for (const std::int32_t h : held_between(lo, hi)) {
        f[static_cast<std::size_t>(h)] = Vec3::Zero();
        t[static_cast<std::size_t>(h)] = Vec3::Zero();
      }
      // After the barrier no thread reads another's particles, so these may move on now.
      if (close) close_rows(lo, hi, closing_.check, closing_.and_drift, first_bad, maxd2);
    }
    if (close) {
      closing_.first_bad[tn] = first_bad;
      closing_.maxd2[tn] = maxd2;
    }
    if (timed) cut_.busy[tn] += std::chrono::duration<double>(c1 - c0 + (Clock::now() - c2)).count();
  }
  if (timed) cut_.step();

  // The wall loads: per wall the sum of the blocks' shares in block order, per element the same.
  for (std::size_t k = 0; k < nw; ++k) {
    Vec3 sf = Vec3::Zero(), st = Vec3::Zero();
    for (std::size_t ob = 0; ob < nblocks; ++ob) {
      sf += wall_part_f_[ob * nw + k];
      st += wall_part_t_[ob * nw + k];
    }
    walls_[k].force = sf;
    walls_[k].torque = st;
    std::fill(walls_[k].element_force.begin(), walls_[k].element_force.end(), element_base_[k] < 0 ? sf : Vec3::Zero());
  }
  for (std::size_t ob = 0; ob < nblocks; ++ob)
    for (const ElementShare& es : wall_part_e_[ob])
      walls_[static_cast<std::size_t>(es.wall)].element_force[static_cast<std::size_t>(es.element)] += es.f;
}

void World::compute_forces() { compute_forces_by_model(); }

void World::ThreadCut::fit(std::size_t nt, std::size_t blocks) {
  if (at.size() == nt + 1 && at.back() == blocks) return;
  at.resize(nt + 1);
  for (std::size_t t = 0; t <= nt; ++t) at[t] = blocks * t / nt;
  busy.assign(nt, 0.0);
  steps = 0;
}

std::pair<std::size_t, std::size_t> World::ThreadCut::blocks(std::size_t t, std::size_t nt, std::size_t nblocks) const {
  if (at.size() == nt + 1 && at.back() == nblocks) return {at[t], at[t + 1]};
  return {nblocks * t / nt, nblocks * (t + 1) / nt};  // a team smaller than asked for: even shares
}

// A block moves to the neighbouring thread only when the busier of the two would stay busier after
// giving it (its time exceeds the other's by more than one of its blocks): so a cut never swings
// back and forth, and an even pair stays as it is.
void World::ThreadCut::step() {
  if (++steps < kWindow) return;
  for (std::size_t t = 0; t + 2 < at.size(); ++t) {
    const double a = busy[t], b = busy[t + 1];
    const std::size_t na = at[t + 1] - at[t], nb = at[t + 2] - at[t + 1];
    if (a > b && na > 1 && a - b > a / static_cast<double>(na)) --at[t + 1];
    else if (b > a && nb > 1 && b - a > b / static_cast<double>(nb)) ++at[t + 1];
  }
  std::fill(busy.begin(), busy.end(), 0.0);
  steps = 0;
}

std::pair<std::size_t, std::size_t> World::thread_rows(std::size_t n) const {
  const auto t = static_cast<std::size_t>(omp_get_thread_num());
  const auto nt = static_cast<std::size_t>(omp_get_num_threads());
  const std::size_t nb = nl_.blocks();
  if (nb == 0) return {n * t / nt, n * (t + 1) / nt};
  // n may differ from the list's rows (particles inserted or removed since the rebuild): the last
  // thread then takes the rows beyond them.
  const auto [b0, b1] = cut_.blocks(t, nt, nb);
  return {std::min(nl_.block_lo[b0], n), b1 == nb ? n : std::min(nl_.block_lo[b1], n)};
}

void World::compute_forces_by_model() {
  using HM = HertzMindlin;
  using LSD = LinearSpringDashpot;
  using CH = CoulombHistorySpring;
  using NT = NoTangential;
  const bool hertz = settings_.normal == NormalModel::hertz_mindlin;
  const bool fric = settings_.tangential == TangentialModel::coulomb_history;
  switch (settings_.rolling) {
    case RollingModel::none:
      if (hertz) fric ? compute_forces_impl<ContactModel<HM, CH, NoRolling>>() : compute_forces_impl<ContactModel<HM, NT, NoRolling>>();
      else fric ? compute_forces_impl<ContactModel<LSD, CH, NoRolling>>() : compute_forces_impl<ContactModel<LSD, NT, NoRolling>>();
      break;
    case RollingModel::constant_torque:
      if (hertz) fric ? compute_forces_impl<ContactModel<HM, CH, RollingConstantTorque>>() : compute_forces_impl<ContactModel<HM, NT, RollingConstantTorque>>();
      else fric ? compute_forces_impl<ContactModel<LSD, CH, RollingConstantTorque>>() : compute_forces_impl<ContactModel<LSD, NT, RollingConstantTorque>>();
      break;
    case RollingModel::epsd:
      if (hertz) fric ? compute_forces_impl<ContactModel<HM, CH, RollingEpsd>>() : compute_forces_impl<ContactModel<HM, NT, RollingEpsd>>();
      else fric ? compute_forces_impl<ContactModel<LSD, CH, RollingEpsd>>() : compute_forces_impl<ContactModel<LSD, NT, RollingEpsd>>();
      break;
  }
}

}  // namespace chutelab::dem
