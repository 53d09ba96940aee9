// The neighbour list's search (dem/neighbor_list.h): a cell grid over the particles' bounding box
// (cell >= largest cut-off), particles sorted by cell for memory locality, and the rows of the half
// list found from the forward half of each particle's 27-cell stencil.
#include "dem/neighbor_list.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <omp.h>
#if defined(__AVX512F__)
#include <immintrin.h>
#endif

#include "dem/storage.h"
#include "dem/team.h"

namespace chutelab::dem {
namespace {

// The candidates j in [k0, k1) of one stencil range that are within cut-off of particle i (centre
// xi, radius plus skin ri), written to out (which has room for k1 - k0 entries), in ascending j;
// returns how many. Spheres of i's own clump (body_i >= 0) are never listed. The AVX-512 path makes
// the same comparisons on the same numbers (no fused operations), so both paths give the same list.
CHUTELAB_INLINE std::size_t near_in_range(const Vec3* __restrict px, const double* __restrict pr, const std::int32_t* __restrict pc,
                          std::size_t k0, std::size_t k1, const Vec3& xi, double ri, std::int32_t body_i,
                          std::int32_t* __restrict out) {
  std::size_t m = 0, j = k0;
#if defined(__AVX512F__) && defined(__AVX512VL__)
  // Eight candidates at a time: their 24 coordinates in three loads, split into x, y and z by two
  // permutes each; the listed indices are compressed into place.
  const __m512i ix0 = _mm512_setr_epi64(0, 3, 6, 9, 12, 15, 0, 0), ix1 = _mm512_setr_epi64(0, 1, 2, 3, 4, 5, 10, 13);
  const __m512i iy0 = _mm512_setr_epi64(1, 4, 7, 10, 13, 0, 0, 0), iy1 = _mm512_setr_epi64(0, 1, 2, 3, 4, 8, 11, 14);
  const __m512i iz0 = _mm512_setr_epi64(2, 5, 8, 11, 14, 0, 0, 0), iz1 = _mm512_setr_epi64(0, 1, 2, 3, 4, 9, 12, 15);
  const __m512d cx = _mm512_set1_pd(xi.x()), cy = _mm512_set1_pd(xi.y()), cz = _mm512_set1_pd(xi.z());
  const __m512d cr = _mm512_set1_pd(ri);
  const __m256i lane = _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7);
  const __m256i body = _mm256_set1_epi32(body_i);
  const double* base = px->data();
  for (; j + 8 <= k1; j += 8) {
    const double* b = base + 3 * j;
    const __m512d a0 = _mm512_loadu_pd(b), a1 = _mm512_loadu_pd(b + 8), a2 = _mm512_loadu_pd(b + 16);
    const __m512d x = _mm512_permutex2var_pd(_mm512_permutex2var_pd(a0, ix0, a1), ix1, a2);
    const __m512d y = _mm512_permutex2var_pd(_mm512_permutex2var_pd(a0, iy0, a1), iy1, a2);
    const __m512d z = _mm512_permutex2var_pd(_mm512_permutex2var_pd(a0, iz0, a1), iz1, a2);
    const __m512d dx = _mm512_sub_pd(x, cx), dy = _mm512_sub_pd(y, cy), dz = _mm512_sub_pd(z, cz);
    const __m512d d2 = _mm512_add_pd(_mm512_add_pd(_mm512_mul_pd(dx, dx), _mm512_mul_pd(dy, dy)), _mm512_mul_pd(dz, dz));
    const __m512d cut = _mm512_add_pd(cr, _mm512_loadu_pd(pr + j));
    __mmask8 near = _mm512_cmp_pd_mask(d2, _mm512_mul_pd(cut, cut), _CMP_LT_OQ);
    if (body_i >= 0)
      near &= _mm256_cmpneq_epi32_mask(_mm256_loadu_si256(reinterpret_cast<const __m256i*>(pc + j)), body);
    const __m256i idx = _mm256_add_epi32(_mm256_set1_epi32(static_cast<std::int32_t>(j)), lane);
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(out + m), _mm256_maskz_compress_epi32(near, idx));
    m += static_cast<std::size_t>(__builtin_popcount(near));
  }
  // The last 1-7 candidates the same way, through masked loads (which read nothing past the mask)
  // and a masked store (`out` has room only for them). Ranges are short (a row of three cells), so
  // a scalar tail was a quarter of the search.
  if (j < k1) {
    const auto rem = static_cast<unsigned>(k1 - j);
    const auto lanes = static_cast<__mmask8>((1u << rem) - 1u);
    const std::uint32_t words = (1u << (3u * rem)) - 1u;  // rem x, y, z triples: up to 21 doubles
    const double* b = base + 3 * j;
    const __m512d a0 = _mm512_maskz_loadu_pd(static_cast<__mmask8>(words), b);
    const __m512d a1 = _mm512_maskz_loadu_pd(static_cast<__mmask8>(words >> 8), b + 8);
    const __m512d a2 = _mm512_maskz_loadu_pd(static_cast<__mmask8>(words >> 16), b + 16);
    const __m512d x = _mm512_permutex2var_pd(_mm512_permutex2var_pd(a0, ix0, a1), ix1, a2);
    const __m512d y = _mm512_permutex2var_pd(_mm512_permutex2var_pd(a0, iy0, a1), iy1, a2);
    const __m512d z = _mm512_permutex2var_pd(_mm512_permutex2var_pd(a0, iz0, a1), iz1, a2);
    const __m512d dx = _mm512_sub_pd(x, cx), dy = _mm512_sub_pd(y, cy), dz = _mm512_sub_pd(z, cz);
    const __m512d d2 = _mm512_add_pd(_mm512_add_pd(_mm512_mul_pd(dx, dx), _mm512_mul_pd(dy, dy)), _mm512_mul_pd(dz, dz));
    const __m512d cut = _mm512_add_pd(cr, _mm512_maskz_loadu_pd(lanes, pr + j));
    __mmask8 near = _mm512_mask_cmp_pd_mask(lanes, d2, _mm512_mul_pd(cut, cut), _CMP_LT_OQ);
    if (body_i >= 0) near &= _mm256_cmpneq_epi32_mask(_mm256_maskz_loadu_epi32(lanes, pc + j), body);
    const __m256i idx = _mm256_add_epi32(_mm256_set1_epi32(static_cast<std::int32_t>(j)), lane);
    const auto count = static_cast<unsigned>(__builtin_popcount(near));
    _mm256_mask_storeu_epi32(out + m, static_cast<__mmask8>((1u << count) - 1u), _mm256_maskz_compress_epi32(near, idx));
    m += count;
    j = k1;
  }
#endif
  for (; j < k1; ++j) {
    const double cut = ri + pr[j];
    const bool near = (px[j] - xi).squaredNorm() < cut * cut;
    const bool same_body = body_i >= 0 && pc[j] == body_i;  // spheres of one clump never touch
    out[m] = static_cast<std::int32_t>(j);
    m += near & !same_body;
  }
  return m;
}

// The row of particle i when the particles are not in cell order: the 27 cells of its stencil, then
// sorted. Appended to out, which holds the row from row_start.
void search_row(std::size_t i, const CellGrid& grid, const Particles& p, double skin, std::size_t row_start,
                std::vector<std::int32_t>& out) {
  const Vec3 xi = p.x[i];
  const double ri = p.radius[i] + skin;
  const std::int32_t body_i = p.clump[i];  // spheres of one clump never contact each other
  const auto& dim = grid.dim;
  const std::int64_t cx = grid.coord(xi, 0), cy = grid.coord(xi, 1), cz = grid.coord(xi, 2);
  for (std::int64_t z = std::max<std::int64_t>(cz - 1, 0); z <= std::min(cz + 1, dim[2] - 1); ++z)
    for (std::int64_t y = std::max<std::int64_t>(cy - 1, 0); y <= std::min(cy + 1, dim[1] - 1); ++y)
      for (std::int64_t x = std::max<std::int64_t>(cx - 1, 0); x <= std::min(cx + 1, dim[0] - 1); ++x) {
        const auto c = static_cast<std::size_t>(grid.index(x, y, z));
        for (std::int32_t k = grid.cell_start[c]; k < grid.cell_start[c + 1]; ++k) {
          const std::int32_t j = grid.members[static_cast<std::size_t>(k)];
          if (j <= static_cast<std::int32_t>(i)) continue;
          if (body_i >= 0 && p.clump[static_cast<std::size_t>(j)] == body_i) continue;
          const double cut = ri + p.radius[static_cast<std::size_t>(j)];
          if ((p.x[static_cast<std::size_t>(j)] - xi).squaredNorm() < cut * cut) out.push_back(j);
        }
      }
  std::sort(out.begin() + static_cast<std::ptrdiff_t>(row_start), out.end());
}

// The same rows when particles are sorted by cell, found faster: with cells of lower linear index
// holding only lower indices, the half list (j > i) needs just the own cell and the 13 "forward"
// neighbours of the stencil. A row of three cells along x is one contiguous index range, and that
// forward half is five such ranges (the own row from i + 1, the next row up, and three in the next
// layer), visited in increasing cell order, so j still ascends. Each range is scanned without
// branching on the outcome. The ranges are the same for every particle of a cell (only the own
// row's start, i + 1, moves), so they are found once per cell: per particle, the cell coordinates
// and eight lookups were two fifths of the search.
struct CellRanges {
  std::int64_t cell = -1;
  std::size_t lo_k[5], hi_k[5];  // [0]: the own row, from i + 1 (set per particle); empty: lo = hi
  std::size_t others = 0;        // the total length of [1..4]

  void find(const CellGrid& grid, std::int64_t c) {
    const auto& dim = grid.dim;
    const auto& start = grid.cell_start;
    cell = c;
    const std::int64_t cx = c % dim[0], cy = (c / dim[0]) % dim[1], cz = c / (dim[0] * dim[1]);
    const std::int64_t x0 = std::max<std::int64_t>(cx - 1, 0), x1 = std::min(cx + 1, dim[0] - 1);
    hi_k[0] = static_cast<std::size_t>(start[static_cast<std::size_t>((cz * dim[1] + cy) * dim[0] + x1 + 1)]);
    others = 0;
    auto range = [&](int r, std::int64_t y, std::int64_t z) {
      lo_k[r] = hi_k[r] = 0;
      if (y < 0 || y >= dim[1] || z >= dim[2]) return;
      const std::int64_t base = (z * dim[1] + y) * dim[0];
      const auto k0 = static_cast<std::size_t>(start[static_cast<std::size_t>(base + x0)]);
      const auto k1 = static_cast<std::size_t>(start[static_cast<std::size_t>(base + x1 + 1)]);
      if (k1 <= k0) return;
      lo_k[r] = k0, hi_k[r] = k1;
      others += k1 - k0;
    };
    range(1, cy + 1, cz);
    range(2, cy - 1, cz + 1);
    range(3, cy, cz + 1);
    range(4, cy + 1, cz + 1);
  }
};

void search_row_sorted(std::size_t i, CellRanges& cr, const Particles& p, double skin, std::vector<std::int32_t>& out) {
  const Vec3 xi = p.x[i];
  const double ri = p.radius[i] + skin;
  const std::int32_t body_i = p.clump[i];
  const Vec3* __restrict px = p.x.data();
  const double* __restrict pr = p.radius.data();
  const std::int32_t* __restrict pc = p.clump.data();
  // The own row holds i itself (its cell lies between the row's first and last), so it starts at i + 1.
  cr.lo_k[0] = std::min(i + 1, cr.hi_k[0]);
  std::size_t m = out.size();
  out.resize(m + (cr.hi_k[0] - cr.lo_k[0]) + cr.others);  // `out` grows once per row (not once per range)
  for (int r = 0; r < 5; ++r)
    if (cr.hi_k[r] > cr.lo_k[r]) m += near_in_range(px, pr, pc, cr.lo_k[r], cr.hi_k[r], xi, ri, body_i, out.data() + m);
  out.resize(m);
}

}  // namespace

void NeighborList::build(const CellGrid& grid, const Particles& p, double skin, bool sorted, int nt) {
  const std::size_t n = p.size();
  row_begin.assign(n + 1, 0);
  std::vector<std::int32_t> local_start(n);
  if (row_buffers_.size() < static_cast<std::size_t>(nt)) row_buffers_.resize(static_cast<std::size_t>(nt));
  std::vector<std::size_t> block(static_cast<std::size_t>(nt) + 1, 0);
  // One pass: each thread fills a contiguous block of rows into its own buffer.
  on_team(nt, [&] {
    const auto t = static_cast<std::size_t>(omp_get_thread_num());
    const auto nth = static_cast<std::size_t>(omp_get_num_threads());
    const auto [lo, hi] = even_share(n, t, nth);
    // The buffer is moved to this thread's stack while it grows: the vector objects of all threads
    // share a cache line, and each row's resize wrote it, so it went back and forth between the
    // cores at every row (bench bed, 2 threads: the search took as long as on one).
    std::vector<std::int32_t> out = std::move(row_buffers_[t]);
    out.clear();
    out.reserve((hi - lo) * 8);
    CellRanges cr;
    for (std::size_t i = lo; i < hi; ++i) {
      local_start[i] = static_cast<std::int32_t>(out.size());
      if (sorted) {
        if (grid.cell[i] != cr.cell) cr.find(grid, grid.cell[i]);
        search_row_sorted(i, cr, p, skin, out);
      } else {
        search_row(i, grid, p, skin, static_cast<std::size_t>(local_start[i]), out);
      }
    }
    block[t + 1] = out.size();
#pragma omp barrier
#pragma omp single
    {
      for (std::size_t k = 0; k < nth; ++k) block[k + 1] += block[k];
      resize_for_overwrite(neighbor, block[nth]);
    }
    for (std::size_t i = lo; i < hi; ++i) row_begin[i] = static_cast<std::int32_t>(block[t]) + local_start[i];
    std::copy(out.begin(), out.end(), neighbor.begin() + static_cast<std::ptrdiff_t>(block[t]));
    row_buffers_[t] = std::move(out);
  });
  row_begin[n] = static_cast<std::int32_t>(neighbor.size());
  const std::size_t nslots = neighbor.size();
  resize_for_overwrite(shear, nslots);
  resize_for_overwrite(roll, nslots);
  resize_for_overwrite(touch, nslots);
  Vec3* __restrict sh = shear.data();
  Vec3* __restrict ro = roll.data();
  std::uint8_t* __restrict to = touch.data();
  on_team(nt, [&] {
#pragma omp for schedule(static)
    for (std::size_t k = 0; k < nslots; ++k) {
      sh[k].setZero();
      ro[k].setZero();
      to[k] = 0;
    }
  });
  index_slots(nt);
}

void NeighborList::index_slots(int threads) {
  resize_for_overwrite(slot_row, neighbor.size());
  const std::size_t rows = row_begin.empty() ? 0 : row_begin.size() - 1;
  on_team(threads, [&] {
#pragma omp for schedule(static)
    for (std::size_t i = 0; i < rows; ++i)
      std::fill(slot_row.begin() + row_begin[i], slot_row.begin() + row_begin[i + 1], static_cast<std::int32_t>(i));
  });
}

// The gaps need the list's slot_row (index_slots) and the positions max_disp_ is measured from.
// eps covers the rounding of this pass, of the displacements and of the pair loop's own test (all
// within a few units in the last place of the coordinates) a million times over.
void NeighborList::measure_gaps([[maybe_unused]] const Vec3* x_ref, [[maybe_unused]] const double* radius,
                                std::size_t n, [[maybe_unused]] int threads) {
#if CHUTELAB_DEM_PAIR_GAPS
  double scale = 0.0, rmax = 0.0;
#pragma omp parallel for num_threads(threads) schedule(static) reduction(max : scale, rmax)
  for (std::size_t i = 0; i < n; ++i) {
    scale = std::max(scale, x_ref[i].cwiseAbs().maxCoeff());
    rmax = std::max(rmax, radius[i]);
  }
  gap_eps = 1e-9 * (scale + 2.0 * rmax);
  const std::size_t nslots = neighbor.size();
  resize_for_overwrite(gap, nslots);
  const double* __restrict xb = x_ref->data();
  const std::int32_t* __restrict rows = slot_row.data();
  const std::int32_t* __restrict nb = neighbor.data();
  float* __restrict out = gap.data();
  const __m512d eps = _mm512_set1_pd(gap_eps), zero = _mm512_setzero_pd();
  const std::size_t groups = (nslots + 7) / 8;
  on_team(threads, [&] {
#pragma omp for schedule(static)
    for (std::size_t g = 0; g < groups; ++g) {
      const std::size_t s = 8 * g, rem = nslots - s;
      const auto lanes = static_cast<__mmask8>(rem >= 8 ? 0xFFu : (1u << rem) - 1u);
      const auto gather = [&](__m256i idx, const double* base) { return _mm512_mask_i32gather_pd(zero, lanes, idx, base, 8); };
      const __m256i vi = _mm256_maskz_loadu_epi32(lanes, rows + s), vj = _mm256_maskz_loadu_epi32(lanes, nb + s);
      const __m256i i3 = _mm256_add_epi32(vi, _mm256_add_epi32(vi, vi)), j3 = _mm256_add_epi32(vj, _mm256_add_epi32(vj, vj));
      const __m512d dx = _mm512_sub_pd(gather(j3, xb), gather(i3, xb));
      const __m512d dy = _mm512_sub_pd(gather(j3, xb + 1), gather(i3, xb + 1));
      const __m512d dz = _mm512_sub_pd(gather(j3, xb + 2), gather(i3, xb + 2));
      const __m512d d = _mm512_maskz_sqrt_pd(lanes, _mm512_add_pd(_mm512_add_pd(_mm512_mul_pd(dx, dx), _mm512_mul_pd(dy, dy)), _mm512_mul_pd(dz, dz)));
      const __m512d gd = _mm512_sub_pd(_mm512_sub_pd(d, _mm512_add_pd(gather(vi, radius), gather(vj, radius))), eps);
      _mm256_mask_storeu_ps(out + s, lanes, _mm512_maskz_cvt_roundpd_ps(lanes, gd, _MM_FROUND_TO_NEG_INF | _MM_FROUND_NO_EXC));
    }
  });
#else
  (void)n;
  gap.clear();
  gap_eps = 0.0;
#endif
}

void NeighborList::carry_history(const TouchingHistory& saved, const std::vector<std::int32_t>& map, int threads) {
  // Each old contact lands in its own new slot, so the rows can be carried over in parallel.
  const std::size_t old_rows = saved.pair_begin.empty() ? 0 : saved.pair_begin.size() - 1;
  on_team(threads, [&] {
#pragma omp for schedule(dynamic, 512)
    for (std::size_t io = 0; io < old_rows; ++io) {
      const std::int32_t a0 = io < map.size() ? map[io] : -1;
      if (a0 < 0) continue;
      for (auto s = saved.pair_begin[io]; s < saved.pair_begin[io + 1]; ++s) {
        const auto so = static_cast<std::size_t>(s);
        const auto jo = static_cast<std::size_t>(saved.pair_other[so]);
        const std::int32_t b0 = jo < map.size() ? map[jo] : -1;
        if (b0 < 0) continue;
        const std::int32_t a = std::min(a0, b0), b = std::max(a0, b0);
        const double sign = a0 < b0 ? 1.0 : -1.0;  // history is i's view; swapping i and j negates it
        const auto first = neighbor.begin() + row_begin[static_cast<std::size_t>(a)];
        const auto last = neighbor.begin() + row_begin[static_cast<std::size_t>(a) + 1];
        const auto it = std::lower_bound(first, last, b);
        if (it == last || *it != b) continue;
        const auto sn = static_cast<std::size_t>(it - neighbor.begin());
        shear[sn] = sign * saved.pair_shear[so];
        roll[sn] = sign * saved.pair_roll[so];
        touch[sn] = 1;
      }
    }
  });
}

}  // namespace chutelab::dem
