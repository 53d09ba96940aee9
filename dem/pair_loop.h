#pragma once
// The pair loop: the particle-particle contacts of a force block's rows, through the contact law, into
// the block's partial-sum buffers (dem/force_blocks.h). Included by dem/forces.cpp only: one
// instantiation per contact model (no virtual call and no branch on the model in the loop).
//
// The distance test of every listed pair collects the touching ones in chunks of 64; the law runs
// over a chunk as one vectorised loop; the forces are then scattered in list order. With AVX-512 the
// slots whose gap at the rebuild exceeds twice the largest displacement since are set apart before
// the test (NeighborList::gap).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <type_traits>

#if defined(__AVX512F__)
#include <immintrin.h>
#endif

#include "dem/contact/kinematics.h"
#include "dem/material.h"
#include "dem/types.h"

namespace chutelab::dem::pair_loop {

// Raw views of the arrays the pair loop reads. Kept as plain restrict pointers copied into locals, so
// the compiler holds them in registers (a lambda capturing by reference reloads them per contact).
template <class Coeffs>
struct PairArrays {
  const Vec3* x;
  const Vec3* v;
  const Vec3* w;
  const double* rad;
  const double* mass;
  const double* inv_inertia;
  const std::int32_t* mat;
  const std::int32_t* row;
  const std::int32_t* neighbor;
  const std::int32_t* slot_row;
  Vec3* shear;
  Vec3* roll;
  std::uint8_t* touch;
  const Coeffs* coeffs;  // the contact model's per material pair, row-major
  std::size_t nmat;
  double dt;
  const float* gap;  // NeighborList::gap (CHUTELAB_DEM_PAIR_GAPS)
  float gap_limit;   // a slot whose gap exceeds this does not touch
  bool gather;       // feed the law by vector gathers (gather_in_law())
};

// The contact law runs over chunks of touching pairs (their indices collected by the distance test).
// The loop over a chunk has no branch, so the compiler evaluates several contacts per SIMD
// instruction; the distance test before it and the scatter after it keep the row-by-row order of
// every sum, so the forces do not depend on the chunk size or the thread count.
constexpr std::size_t kChunk = 64;

// A contact's force and torques into lane c of a chunk's outputs.
template <class Chunk>
CHUTELAB_INLINE void store_force(Chunk& h, std::size_t c, const ContactForce& cf) {
  h.fx[c] = cf.force.x, h.fy[c] = cf.force.y, h.fz[c] = cf.force.z;
  h.tix[c] = cf.torque_i.x, h.tiy[c] = cf.torque_i.y, h.tiz[c] = cf.torque_i.z;
  h.tjx[c] = cf.torque_j.x, h.tjy[c] = cf.torque_j.y, h.tjz[c] = cf.torque_j.z;
}

// Folds the material pair of contact (i, j) into the chunk's: the pair all contacts so far share
// (an index of a.coeffs; -1 before the first), or -2 once they differ.
template <class Arrays>
CHUTELAB_INLINE void fold_pair_kind(std::int32_t& pair_kind, const Arrays& a, std::size_t i, std::size_t j) {
  const auto kind = static_cast<std::int32_t>(static_cast<std::size_t>(a.mat[i]) * a.nmat + static_cast<std::size_t>(a.mat[j]));
  pair_kind = pair_kind == -1 || pair_kind == kind ? kind : -2;
}

// The chunk's forces and torques added to i and j, in gathering order.
template <class Chunk>
CHUTELAB_INLINE void scatter(const Chunk& h, std::size_t c, Vec3* __restrict f, Vec3* __restrict t) {
  const auto i = static_cast<std::size_t>(h.i[c]);
  const auto j = static_cast<std::size_t>(h.j[c]);
  const Vec3 fc(h.fx[c], h.fy[c], h.fz[c]);
  f[i] += fc;
  t[i] += Vec3(h.tix[c], h.tiy[c], h.tiz[c]);
  f[j] -= fc;
  t[j] += Vec3(h.tjx[c], h.tjy[c], h.tjz[c]);
}

// Two ways to feed the law, with the same arithmetic (so the same results). With vector gathers
// (AVX2) the law can read the particle state by index inside the vectorised loop. Without them (the
// default x86-64 build: SSE2) indexed loads in that loop would stop the vectoriser, so the state is
// first copied into the chunk's structure-of-arrays scratch by a scalar loop. Which is faster
// depends on the CPU's gathers, not only on whether it has them: on an Intel Xeon the gathers won
// (1.10x), on an AMD EPYC (Zen 4) the copy wins by about as much (bench/log/RESULTS.md), so AVX2 builds
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
                                   double* __restrict rl, const typename Model::Coeffs& pc, double dt) {
  // int indices: GCC recognises base[int] as a vector gather, not base[size_t] computed from an int.
  const std::int32_t i = h.i[c], j = h.j[c], s = h.s[c];
  const ContactKinematics k = sphere_pair_kinematics(
      {x[3 * j] - x[3 * i], x[3 * j + 1] - x[3 * i + 1], x[3 * j + 2] - x[3 * i + 2]}, rad[i], rad[j], mass[i], mass[j],
      inv_inertia[i], inv_inertia[j], {v[3 * i] - v[3 * j], v[3 * i + 1] - v[3 * j + 1], v[3 * i + 2] - v[3 * j + 2]},
      {w[3 * i], w[3 * i + 1], w[3 * i + 2]}, {w[3 * j], w[3 * j + 1], w[3 * j + 2]});
  LaneVec shear{sh[3 * s], sh[3 * s + 1], sh[3 * s + 2]};
  LaneVec roll = LaneVec::zero();
  if constexpr (Model::rolling_history) roll = {rl[3 * s], rl[3 * s + 1], rl[3 * s + 2]};
  store_force(h, c, Model::compute(pc, k, shear, &roll, dt));
  // Each slot s appears once in a chunk, so these stores never collide.
  sh[3 * s] = shear.x, sh[3 * s + 1] = shear.y, sh[3 * s + 2] = shear.z;
  if constexpr (Model::rolling_history) rl[3 * s] = roll.x, rl[3 * s + 1] = roll.y, rl[3 * s + 2] = roll.z;
}

// The contacts gathered in h: the law over all of them (vectorised when they share one material
// pair, as they do in a one-material bed), then their forces scattered in gathering order.
template <class Model>
[[gnu::noinline]] void run_chunk(GatherChunk& h, std::size_t n, const PairArrays<typename Model::Coeffs>& a, Vec3* __restrict f,
                                 Vec3* __restrict t) {
  std::int32_t pair_kind = -1;  // the material pair of every contact in the chunk; -2 if mixed
  for (std::size_t c = 0; c < n; ++c)
    fold_pair_kind(pair_kind, a, static_cast<std::size_t>(h.i[c]), static_cast<std::size_t>(h.j[c]));
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
    const typename Model::Coeffs pc = a.coeffs[static_cast<std::size_t>(pair_kind)];
    // ivdep, not omp simd: under omp simd GCC 12 turns the law's small structs into per-lane
    // arrays and gives up; with ivdep it vectorises the whole law.
#if !defined(__clang__)  // clang (the fuzz build) does not know the pragma and would warn
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
  for (std::size_t c = 0; c < n; ++c) scatter(h, c, f, t);
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
CHUTELAB_INLINE void chunk_contact(ContactChunk& h, std::size_t c, const typename Model::Coeffs& pc, double dt) {
  const ContactKinematics k =
      sphere_pair_kinematics({h.dx[c], h.dy[c], h.dz[c]}, h.ri[c], h.rj[c], h.mi[c], h.mj[c], h.ii[c], h.ij[c],
                             {h.vx[c], h.vy[c], h.vz[c]}, {h.wix[c], h.wiy[c], h.wiz[c]}, {h.wjx[c], h.wjy[c], h.wjz[c]});
  LaneVec shear{h.sx[c], h.sy[c], h.sz[c]};
  LaneVec roll = LaneVec::zero();
  if constexpr (Model::rolling_history) roll = {h.qx[c], h.qy[c], h.qz[c]};
  store_force(h, c, Model::compute(pc, k, shear, &roll, dt));
  h.sx[c] = shear.x, h.sy[c] = shear.y, h.sz[c] = shear.z;
  if constexpr (Model::rolling_history) h.qx[c] = roll.x, h.qy[c] = roll.y, h.qz[c] = roll.z;
}

// The contacts gathered in h: the law over all of them (vectorised when they share one material
// pair, as they do in a one-material bed), then their forces scattered in gathering order.
template <class Model>
[[gnu::noinline]] void run_chunk(ContactChunk& h, std::size_t n, const PairArrays<typename Model::Coeffs>& a, Vec3* __restrict f,
                                 Vec3* __restrict t) {
  const Vec3* __restrict v = a.v;
  const Vec3* __restrict w = a.w;
  std::int32_t pair_kind = -1;  // the material pair of every contact in the chunk; -2 if mixed
  for (std::size_t c = 0; c < n; ++c) {
    const auto i = static_cast<std::size_t>(h.i[c]);
    const auto j = static_cast<std::size_t>(h.j[c]);
    const auto s = static_cast<std::size_t>(h.s[c]);
    fold_pair_kind(pair_kind, a, i, j);
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
    const typename Model::Coeffs pc = a.coeffs[static_cast<std::size_t>(pair_kind)];
    const double dt = a.dt;
    // ivdep, not omp simd: under omp simd GCC 12 turns the law's small structs into per-lane
    // arrays and gives up; with ivdep it vectorises the whole law.
#if !defined(__clang__)
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
    const auto s = static_cast<std::size_t>(h.s[c]);
    a.shear[s] = Vec3(h.sx[c], h.sy[c], h.sz[c]);
    if constexpr (Model::rolling_history) a.roll[s] = Vec3(h.qx[c], h.qy[c], h.qz[c]);
    scatter(h, c, f, t);
  }
}


// The distance test of one listed pair (rows i < j, list slot s, `was` its touch flag of the last
// evaluation): the pair goes into the next chunk entry and stays there only if it touches (no branch
// on the outcome, which is a coin toss in a dense bed); a full chunk runs.
template <class Model, class Chunk>
CHUTELAB_INLINE void test_slot(const PairArrays<typename Model::Coeffs>& a, std::size_t i, std::size_t j, std::size_t s, std::uint8_t was,
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
void screen_slots_avx512(const PairArrays<typename Model::Coeffs>& a, std::size_t s0, std::size_t s1, Chunk& h, Vec3* __restrict f,
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
      _mm512_storeu_si512(cj + m, _mm512_maskz_compress_epi32(maybe, _mm512_maskz_loadu_epi32(lanes, a.neighbor + s)));
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
void pair_rows(const PairArrays<typename Model::Coeffs>& a, std::size_t i0, std::size_t i1, Vec3* __restrict f, Vec3* __restrict t) {
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
    test_slot<Model>(a, static_cast<std::size_t>(a.slot_row[s]), static_cast<std::size_t>(a.neighbor[s]), s, a.touch[s], h, n, f, t);
  if (n > 0) run_chunk<Model>(h, n, a, f, t);
#endif
}

#if !CHUTELAB_DEM_GATHER_IN_LAW
using GatherChunk = ContactChunk;  // never chosen: gather_in_law() is false without AVX2
#endif

// Whether this CPU's vector gathers beat the scalar copy (see above). Decided once per process from
// the vendor; either way the numbers are the same, only the speed differs. CHUTELAB_DEM_GATHER=0/1
// overrides it, for measuring both on one machine.
inline bool gather_in_law() {
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

// The pair contacts of rows [i0, i1), scattered row by row into f/t (a force block's buffers).
template <class Model>
void block_pairs(const PairArrays<typename Model::Coeffs>& a, std::size_t i0, std::size_t i1, Vec3* f, Vec3* t) {
  if (a.gather)
    pair_rows<Model, GatherChunk>(a, i0, i1, f, t);
  else
    pair_rows<Model, ContactChunk>(a, i0, i1, f, t);
}

}  // namespace chutelab::dem::pair_loop
