// Neighbour search: a cell grid over the particles' bounding box (cell >= largest cut-off), particles
// sorted by cell for memory locality, and a Verlet half list with cut-off R_i + R_j + skin that is kept
// until some particle has moved more than skin/2 (or a wall more than skin minus that). Contact history
// is carried over to the new list by particle index maps.
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include <omp.h>
#if defined(__AVX512F__)
#include <immintrin.h>
#endif

#include "dem/storage.h"
#include "dem/walls/closest_point.h"
#include "dem/world.h"

namespace chutelab::dem {
namespace {

constexpr double kInfinity() { return std::numeric_limits<double>::infinity(); }

// Distance from a sphere centre to a wall element (for candidate lists), or +inf if out of reach.
double element_distance(const Wall& w, std::size_t element, const Vec3& x) {
  if (const auto* p = std::get_if<Plane>(&w.current)) {
    const Vec3 r = x - p->point;
    const double s = r.dot(p->normal);
    if (std::abs(r.dot(p->axis_u)) > p->half_u + 1e-300 || std::abs(r.dot(p->axis_v)) > p->half_v + 1e-300) {
      // Outside the strip: distance to the rectangle.
      const double du = std::max(std::abs(r.dot(p->axis_u)) - p->half_u, 0.0);
      const double dv = std::max(std::abs(r.dot(p->axis_v)) - p->half_v, 0.0);
      return std::sqrt(s * s + du * du + dv * dv);
    }
    return s;  // signed: behind the plane counts as touching
  }
  if (const auto* c = std::get_if<Cylinder>(&w.current)) {
    const Vec3 r = x - c->point;
    const double a = r.dot(c->axis);
    const double rho = (r - a * c->axis).norm();
    const double radial = c->inside ? c->radius - rho : rho - c->radius;
    const double axial = std::max({c->axial_min - a, a - c->axial_max, 0.0});
    return std::hypot(std::max(radial, 0.0), axial) + std::min(radial, 0.0);
  }
  const auto& m = std::get<TriangleMesh>(w.current);
  const auto& t = m.triangles[element];
  const TriClosest cp = closest_point_on_triangle(x, m.vertices[static_cast<std::size_t>(t[0])],
                                                  m.vertices[static_cast<std::size_t>(t[1])],
                                                  m.vertices[static_cast<std::size_t>(t[2])]);
  return (cp.point - x).norm();
}

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

}  // namespace

void NeighborList::index_slots(int threads) {
  resize_for_overwrite(slot_row, neighbor.size());
  const std::size_t rows = row_begin.empty() ? 0 : row_begin.size() - 1;
#pragma omp parallel for num_threads(threads) schedule(static)
  for (std::size_t i = 0; i < rows; ++i)
    std::fill(slot_row.begin() + row_begin[i], slot_row.begin() + row_begin[i + 1], static_cast<std::int32_t>(i));
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
#pragma omp parallel for num_threads(threads) schedule(static)
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
#else
  (void)n;
  gap.clear();
  gap_eps = 0.0;
#endif
}

namespace {

// The touching entries of a list in CSR form (row `begin`, per-entry `touch`), compacted into
// `out_begin` by the same rows: count per row, prefix sum, then `size(total)` and `copy(from, to)`
// for each touching entry, every row its own range (rows in parallel, entry order kept).
template <class Size, class Copy>
void compact_touching(const std::vector<std::int32_t>& begin, const std::vector<std::uint8_t>& touch, int nt,
                      std::vector<std::int32_t>& out_begin, Size size, Copy copy) {
  const std::size_t rows = begin.empty() ? 0 : begin.size() - 1;
  resize_for_overwrite(out_begin, rows + 1);
  out_begin[0] = 0;
  {
    const std::int32_t* __restrict rb = begin.data();
    const std::uint8_t* __restrict to = touch.data();
    std::int32_t* __restrict ob = out_begin.data();
#pragma omp parallel for num_threads(nt) schedule(static)
    for (std::size_t r = 0; r < rows; ++r) {
      std::int32_t c = 0;
      for (auto e = rb[r]; e < rb[r + 1]; ++e) c += to[static_cast<std::size_t>(e)];
      ob[r + 1] = c;
    }
  }
  for (std::size_t r = 0; r < rows; ++r) out_begin[r + 1] += out_begin[r];
  size(static_cast<std::size_t>(out_begin[rows]));
#pragma omp parallel for num_threads(nt) schedule(static)
  for (std::size_t r = 0; r < rows; ++r) {
    auto to = static_cast<std::size_t>(out_begin[r]);
    for (auto e = begin[r]; e < begin[r + 1]; ++e)
      if (touch[static_cast<std::size_t>(e)]) copy(static_cast<std::size_t>(e), to++);
  }
}

}  // namespace

void World::save_touching_history(int nt) {
  TouchingHistory& h = history_;
  compact_touching(
      pair_list_.row_begin, pair_list_.touch, nt, h.pair_begin,
      [&](std::size_t m) {
        resize_for_overwrite(h.pair_other, m);
        resize_for_overwrite(h.pair_shear, m);
        resize_for_overwrite(h.pair_roll, m);
      },
      [&](std::size_t from, std::size_t to) {
        h.pair_other[to] = pair_list_.neighbor[from];
        h.pair_shear[to] = pair_list_.shear[from];
        h.pair_roll[to] = pair_list_.roll[from];
      });
  compact_touching(
      wall_list_.begin, wall_list_.touch, nt, h.wall_begin,
      [&](std::size_t m) {
        resize_for_overwrite(h.wall_wall, m);
        resize_for_overwrite(h.wall_element, m);
        resize_for_overwrite(h.wall_shear, m);
        resize_for_overwrite(h.wall_roll, m);
      },
      [&](std::size_t from, std::size_t to) {
        h.wall_wall[to] = wall_list_.wall[from];
        h.wall_element[to] = wall_list_.element[from];
        h.wall_shear[to] = wall_list_.shear[from];
        h.wall_roll[to] = wall_list_.roll[from];
      });
}

void World::rebuild() {
  const std::size_t n = p_.size();
  const int nt = thread_count();
  // Only the touching contacts' history outlives a rebuild: it is copied out compactly, and the lists
  // are rebuilt in their own storage. (Fresh list arrays at every rebuild cost a page fault per 4 kB
  // of new slots, most of them in the 48 B of history per slot: a fifth of a station run's time.
  // Keeping the old lists whole beside the new ones raised the bench bed's peak memory from 0.97 to
  // 1.15 kB per particle.)
  save_touching_history(nt);
  std::vector<std::int32_t> map = std::move(index_map_);  // old list index -> current index

  // --- cell grid ---
  double rmax = 0.0;
  double lx = kInfinity(), ly = kInfinity(), lz = kInfinity();
  double hx = -kInfinity(), hy = -kInfinity(), hz = -kInfinity();
  {
    const Vec3* __restrict px = p_.x.data();
    const double* __restrict pr = p_.radius.data();
    // min and max are exact, so the box does not depend on the thread count.
#pragma omp parallel for num_threads(nt) schedule(static) reduction(max : rmax, hx, hy, hz) reduction(min : lx, ly, lz)
    for (std::size_t i = 0; i < n; ++i) {
      rmax = std::max(rmax, pr[i]);
      lx = std::min(lx, px[i].x()), ly = std::min(ly, px[i].y()), lz = std::min(lz, px[i].z());
      hx = std::max(hx, px[i].x()), hy = std::max(hy, px[i].y()), hz = std::max(hz, px[i].z());
    }
  }
  const Vec3 lo(lx, ly, lz), hi(hx, hy, hz);
  double h = 2.0 * rmax + skin_;
  std::array<std::int64_t, 3> dim{1, 1, 1};
  if (n > 0) {
    // Cap the number of cells (sparse scenes, long trajectories) at a few per particle.
    const double cap = std::max(8.0 * static_cast<double>(n), 4096.0);
    for (;;) {
      double total = 1.0;
      for (int d = 0; d < 3; ++d) total *= std::floor((hi[d] - lo[d]) / h) + 1.0;
      if (total <= cap) break;
      h *= 1.25;
    }
    for (int d = 0; d < 3; ++d) dim[static_cast<std::size_t>(d)] = static_cast<std::int64_t>(std::floor((hi[d] - lo[d]) / h)) + 1;
  }
  const std::int64_t ncell = dim[0] * dim[1] * dim[2];
  auto cell_coord = [&](const Vec3& x, int d) {
    auto c = static_cast<std::int64_t>(std::floor((x[d] - lo[d]) / h));
    return std::clamp<std::int64_t>(c, 0, dim[static_cast<std::size_t>(d)] - 1);
  };
  auto cell_of = [&](const Vec3& x) {
    return (cell_coord(x, 2) * dim[1] + cell_coord(x, 1)) * dim[0] + cell_coord(x, 0);
  };
  // int32: the grid is capped at a few cells per particle (above), and the array is part of the
  // rebuild's memory peak.
  std::vector<std::int32_t> cell(n);
  std::vector<std::int32_t> cell_start(static_cast<std::size_t>(ncell) + 1, 0);
#pragma omp parallel for num_threads(nt) schedule(static)
  for (std::size_t i = 0; i < n; ++i) cell[i] = static_cast<std::int32_t>(cell_of(p_.x[i]));
  for (std::size_t i = 0; i < n; ++i) ++cell_start[static_cast<std::size_t>(cell[i]) + 1];
  for (std::int64_t c = 0; c < ncell; ++c) cell_start[static_cast<std::size_t>(c) + 1] += cell_start[static_cast<std::size_t>(c)];
  std::vector<std::int32_t> order(n);
  {
    std::vector<std::int32_t> fill(cell_start.begin(), cell_start.end() - 1);
    for (std::size_t i = 0; i < n; ++i) order[static_cast<std::size_t>(fill[static_cast<std::size_t>(cell[i])]++)] = static_cast<std::int32_t>(i);
  }
  std::vector<std::int32_t> cell_members;  // particle indices by cell
  if (settings_.sort_particles) {
    p_.permute(order, nt);
    if (!held_.empty()) index_held();
    std::vector<std::int32_t> inv(n);
    for (std::size_t k = 0; k < n; ++k) inv[static_cast<std::size_t>(order[k])] = static_cast<std::int32_t>(k);
    for (auto& m : map)
      if (m >= 0) m = inv[static_cast<std::size_t>(m)];
    std::vector<std::int32_t> sorted_cell(n);
    for (std::size_t k = 0; k < n; ++k) sorted_cell[k] = cell[static_cast<std::size_t>(order[k])];
    cell = std::move(sorted_cell);
    cell_members.resize(n);
    for (std::size_t k = 0; k < n; ++k) cell_members[k] = static_cast<std::int32_t>(k);
  } else {
    cell_members = order;
  }

  // --- pair half list: one pass, each thread fills a contiguous block of rows into its own buffer ---
  // With particles sorted by cell, cells of lower linear index hold only lower indices, so the half
  // list (j > i) needs just the own cell and the 13 "forward" neighbours of the 27-cell stencil.
  const bool sorted = settings_.sort_particles;
  pair_list_.row_begin.assign(n + 1, 0);
  std::vector<std::int32_t> local_start(n);
  auto visit_row = [&](std::size_t i, std::vector<std::int32_t>& out) {
    const Vec3 xi = p_.x[i];
    const double ri = p_.radius[i] + skin_;
    const std::int32_t body_i = p_.clump[i];  // spheres of one clump never contact each other
    const std::int64_t cx = cell_coord(xi, 0), cy = cell_coord(xi, 1), cz = cell_coord(xi, 2);
    const std::int64_t own = (cz * dim[1] + cy) * dim[0] + cx;
    for (std::int64_t z = std::max<std::int64_t>(cz - 1, 0); z <= std::min(cz + 1, dim[2] - 1); ++z)
      for (std::int64_t y = std::max<std::int64_t>(cy - 1, 0); y <= std::min(cy + 1, dim[1] - 1); ++y)
        for (std::int64_t x = std::max<std::int64_t>(cx - 1, 0); x <= std::min(cx + 1, dim[0] - 1); ++x) {
          const std::int64_t cl = (z * dim[1] + y) * dim[0] + x;
          if (sorted && cl < own) continue;
          const std::size_t c = static_cast<std::size_t>(cl);
          for (std::int32_t k = cell_start[c]; k < cell_start[c + 1]; ++k) {
            const std::int32_t j = cell_members[static_cast<std::size_t>(k)];
            if (j <= static_cast<std::int32_t>(i)) continue;
            if (body_i >= 0 && p_.clump[static_cast<std::size_t>(j)] == body_i) continue;
            const double cut = ri + p_.radius[static_cast<std::size_t>(j)];
            if ((p_.x[static_cast<std::size_t>(j)] - xi).squaredNorm() < cut * cut) out.push_back(j);
          }
        }
    if (!sorted) std::sort(out.begin() + local_start[i], out.end());
  };
  // The same rows when particles are sorted by cell, found faster: a row of three cells along x is
  // one contiguous index range, and the forward half of the stencil is five such ranges (the own
  // row from i + 1, the next row up, and three in the next layer), visited in increasing cell
  // order, so j still ascends. Each range is scanned without branching on the outcome. The ranges
  // are the same for every particle of a cell (only the own row's start, i + 1, moves), so they are
  // found once per cell: per particle, the cell coordinates and eight lookups were two fifths of
  // the search.
  struct CellRanges {
    std::int64_t cell = -1;
    std::size_t lo_k[5], hi_k[5];   // [0]: the own row, from i + 1 (set per particle); empty: lo = hi
    std::size_t others = 0;         // the total length of [1..4]
  };
  auto cell_ranges = [&](std::int64_t c, CellRanges& cr) {
    cr.cell = c;
    const std::int64_t cx = c % dim[0], cy = (c / dim[0]) % dim[1], cz = c / (dim[0] * dim[1]);
    const std::int64_t x0 = std::max<std::int64_t>(cx - 1, 0), x1 = std::min(cx + 1, dim[0] - 1);
    cr.hi_k[0] = static_cast<std::size_t>(cell_start[static_cast<std::size_t>((cz * dim[1] + cy) * dim[0] + x1 + 1)]);
    cr.others = 0;
    auto range = [&](int r, std::int64_t y, std::int64_t z) {
      cr.lo_k[r] = cr.hi_k[r] = 0;
      if (y < 0 || y >= dim[1] || z >= dim[2]) return;
      const std::int64_t base = (z * dim[1] + y) * dim[0];
      const auto k0 = static_cast<std::size_t>(cell_start[static_cast<std::size_t>(base + x0)]);
      const auto k1 = static_cast<std::size_t>(cell_start[static_cast<std::size_t>(base + x1 + 1)]);
      if (k1 <= k0) return;
      cr.lo_k[r] = k0, cr.hi_k[r] = k1;
      cr.others += k1 - k0;
    };
    range(1, cy + 1, cz);
    range(2, cy - 1, cz + 1);
    range(3, cy, cz + 1);
    range(4, cy + 1, cz + 1);
  };
  auto visit_row_sorted = [&](std::size_t i, CellRanges& cr, std::vector<std::int32_t>& out) {
    const Vec3 xi = p_.x[i];
    const double ri = p_.radius[i] + skin_;
    const std::int32_t body_i = p_.clump[i];
    const Vec3* __restrict px = p_.x.data();
    const double* __restrict pr = p_.radius.data();
    const std::int32_t* __restrict pc = p_.clump.data();
    // The own row holds i itself (its cell lies between the row's first and last), so it starts at i + 1.
    cr.lo_k[0] = std::min(i + 1, cr.hi_k[0]);
    std::size_t m = out.size();
    out.resize(m + (cr.hi_k[0] - cr.lo_k[0]) + cr.others);  // `out` grows once per row (not once per range)
    for (int r = 0; r < 5; ++r)
      if (cr.hi_k[r] > cr.lo_k[r]) m += near_in_range(px, pr, pc, cr.lo_k[r], cr.hi_k[r], xi, ri, body_i, out.data() + m);
    out.resize(m);
  };
  // Each thread's rows go to its own buffer, kept between rebuilds as the lists are.
  std::vector<std::vector<std::int32_t>>& buf = search_buf_;
  if (buf.size() < static_cast<std::size_t>(nt)) buf.resize(static_cast<std::size_t>(nt));
  std::vector<std::size_t> block(static_cast<std::size_t>(nt) + 1, 0);
#pragma omp parallel num_threads(nt)
  {
    const auto t = static_cast<std::size_t>(omp_get_thread_num());
    const auto nth = static_cast<std::size_t>(omp_get_num_threads());
    const std::size_t lo = n * t / nth, hi = n * (t + 1) / nth;
    // The buffer is moved to this thread's stack while it grows: the vector objects of all threads
    // share a cache line, and each row's resize wrote it, so it went back and forth between the
    // cores at every row (bench bed, 2 threads: the search took as long as on one).
    std::vector<std::int32_t> out = std::move(buf[t]);
    out.clear();
    out.reserve((hi - lo) * 8);
    CellRanges cr;
    for (std::size_t i = lo; i < hi; ++i) {
      local_start[i] = static_cast<std::int32_t>(out.size());
      if (sorted) {
        if (cell[i] != cr.cell) cell_ranges(cell[i], cr);
        visit_row_sorted(i, cr, out);
      } else {
        visit_row(i, out);
      }
    }
    block[t + 1] = out.size();
#pragma omp barrier
#pragma omp single
    {
      for (std::size_t k = 0; k < nth; ++k) block[k + 1] += block[k];
      resize_for_overwrite(pair_list_.neighbor, block[nth]);
    }
    for (std::size_t i = lo; i < hi; ++i) pair_list_.row_begin[i] = static_cast<std::int32_t>(block[t]) + local_start[i];
    std::copy(out.begin(), out.end(), pair_list_.neighbor.begin() + static_cast<std::ptrdiff_t>(block[t]));
    buf[t] = std::move(out);
  }
  pair_list_.row_begin[n] = static_cast<std::int32_t>(pair_list_.neighbor.size());
  const std::size_t nslots = pair_list_.neighbor.size();
  resize_for_overwrite(pair_list_.shear, nslots);
  resize_for_overwrite(pair_list_.roll, nslots);
  resize_for_overwrite(pair_list_.touch, nslots);
  {
    Vec3* __restrict sh = pair_list_.shear.data();
    Vec3* __restrict ro = pair_list_.roll.data();
    std::uint8_t* __restrict to = pair_list_.touch.data();
#pragma omp parallel for num_threads(nt) schedule(static)
    for (std::size_t k = 0; k < nslots; ++k) {
      sh[k].setZero();
      ro[k].setZero();
      to[k] = 0;
    }
  }

  // --- wall candidates: (particle, wall, element) within R + skin, CSR by particle ---
  // Each thread takes a contiguous range (of particles for a primitive, of triangles for a mesh) of
  // every wall into its own buffer; the buffers are then placed by a counting sort (below).
  struct Cand {
    std::int32_t p, wall, element;
  };
  std::vector<std::vector<Cand>> cand_buf(static_cast<std::size_t>(nt));
#pragma omp parallel num_threads(nt)
  {
    const auto t = static_cast<std::size_t>(omp_get_thread_num());
    const auto nth = static_cast<std::size_t>(omp_get_num_threads());
    std::vector<Cand> local;  // on this thread's stack while it grows (see the pair search)
    for (std::size_t wi = 0; wi < walls_.size(); ++wi) {
      const Wall& w = walls_[wi];
      const auto wall_id = static_cast<std::int32_t>(wi);
      // Until the next rebuild no particle moves more than skin/2 (needs_rebuild), so an element of a
      // wall that does not move, farther than R + skin/2 now, cannot be touched before then: listing
      // it only cost its pre-test at every step (three in four of a station's entries were such).
      // The relative margin is far above the rounding of the distances. A moving wall keeps the
      // whole skin, which its own test in needs_rebuild shares with the particles.
      const double wall_skin = w.motion.moving() ? skin_ : 0.5 * skin_ * (1.0 + 1e-6);
      const double reach = rmax + wall_skin;
      if (const auto* m = std::get_if<TriangleMesh>(&w.current)) {
        const std::size_t nt_all = m->triangles.size();
        for (std::size_t tr = nt_all * t / nth; tr < nt_all * (t + 1) / nth; ++tr) {
          Vec3 tlo = m->vertices[static_cast<std::size_t>(m->triangles[tr][0])], thi = tlo;
          for (int k = 1; k < 3; ++k) {
            tlo = tlo.cwiseMin(m->vertices[static_cast<std::size_t>(m->triangles[tr][static_cast<std::size_t>(k)])]);
            thi = thi.cwiseMax(m->vertices[static_cast<std::size_t>(m->triangles[tr][static_cast<std::size_t>(k)])]);
          }
          tlo.array() -= reach;
          thi.array() += reach;
          if (n == 0 || (tlo.array() > hi.array()).any() || (thi.array() < lo.array()).any()) continue;
          const std::int64_t x0 = cell_coord(tlo, 0), x1 = cell_coord(thi, 0);
          const std::int64_t y0 = cell_coord(tlo, 1), y1 = cell_coord(thi, 1);
          const std::int64_t z0 = cell_coord(tlo, 2), z1 = cell_coord(thi, 2);
          for (std::int64_t z = z0; z <= z1; ++z)
            for (std::int64_t y = y0; y <= y1; ++y)
              for (std::int64_t x = x0; x <= x1; ++x) {
                const std::size_t c = static_cast<std::size_t>((z * dim[1] + y) * dim[0] + x);
                for (std::int32_t k = cell_start[c]; k < cell_start[c + 1]; ++k) {
                  const std::int32_t pi = cell_members[static_cast<std::size_t>(k)];
                  const auto ps = static_cast<std::size_t>(pi);
                  if (element_distance(w, tr, p_.x[ps]) < p_.radius[ps] + wall_skin)
                    local.push_back({pi, wall_id, static_cast<std::int32_t>(tr)});
                }
              }
        }
      } else {
        for (std::size_t i = n * t / nth; i < n * (t + 1) / nth; ++i)
          if (element_distance(w, 0, p_.x[i]) < p_.radius[i] + wall_skin)
            local.push_back({static_cast<std::int32_t>(i), wall_id, 0});
      }
    }
    cand_buf[t] = std::move(local);
  }
  // The thread buffers hold, per thread, all walls in order; joined wall by wall they give the
  // serial order. Per particle the (wall, element) pairs must ascend: within one wall a particle's
  // entries come from ascending triangle ranges, so a stable counting sort by particle over the
  // walls in order (and, within a wall, the threads in order) keeps them ascending.
  wall_list_.begin.assign(n + 1, 0);
  for (const auto& b : cand_buf)
    for (const auto& c : b) ++wall_list_.begin[static_cast<std::size_t>(c.p) + 1];
  for (std::size_t i = 0; i < n; ++i) wall_list_.begin[i + 1] += wall_list_.begin[i];
  const auto ncand = static_cast<std::size_t>(wall_list_.begin[n]);
  resize_for_overwrite(wall_list_.wall, ncand);
  resize_for_overwrite(wall_list_.element, ncand);
  {
    std::vector<std::int32_t> next(wall_list_.begin.begin(), wall_list_.begin.end() - 1);
    std::vector<std::size_t> pos(cand_buf.size(), 0);  // per thread buffer: first entry of the current wall
    for (std::size_t wi = 0; wi < walls_.size(); ++wi)
      for (std::size_t t = 0; t < cand_buf.size(); ++t) {
        const auto& b = cand_buf[t];
        std::size_t k = pos[t];
        for (; k < b.size() && static_cast<std::size_t>(b[k].wall) == wi; ++k) {
          const auto at = static_cast<std::size_t>(next[static_cast<std::size_t>(b[k].p)]++);
          wall_list_.wall[at] = b[k].wall;
          wall_list_.element[at] = b[k].element;
        }
        pos[t] = k;
      }
  }
  resize_for_overwrite(wall_list_.shear, ncand);
  resize_for_overwrite(wall_list_.roll, ncand);
  resize_for_overwrite(wall_list_.touch, ncand);
  std::fill(wall_list_.shear.begin(), wall_list_.shear.end(), Vec3::Zero());
  std::fill(wall_list_.roll.begin(), wall_list_.roll.end(), Vec3::Zero());
  std::fill(wall_list_.touch.begin(), wall_list_.touch.end(), std::uint8_t{0});
  resize_for_overwrite(wall_list_.force, ncand);
  resize_for_overwrite(wall_list_.torque, ncand);
  resize_for_overwrite(wall_list_.point, ncand);
  resize_for_overwrite(wall_list_.wall_torque, ncand);
  wall_list_.index_owners();
  pair_list_.index_slots(nt);
  blocks_.layout(n, kForceBlocks, nt, pair_list_.row_begin, pair_list_.neighbor, wall_list_.begin);

  // --- carry contact history over ---
  // Each old contact lands in its own new slot, so the rows can be carried over in parallel.
  const TouchingHistory& hist = history_;
  const std::size_t old_rows = hist.pair_begin.empty() ? 0 : hist.pair_begin.size() - 1;
#pragma omp parallel for num_threads(nt) schedule(dynamic, 512)
  for (std::size_t io = 0; io < old_rows; ++io) {
    const std::int32_t a0 = io < map.size() ? map[io] : -1;
    if (a0 < 0) continue;
    for (auto s = hist.pair_begin[io]; s < hist.pair_begin[io + 1]; ++s) {
      const auto so = static_cast<std::size_t>(s);
      const auto jo = static_cast<std::size_t>(hist.pair_other[so]);
      const std::int32_t b0 = jo < map.size() ? map[jo] : -1;
      if (b0 < 0) continue;
      const std::int32_t a = std::min(a0, b0), b = std::max(a0, b0);
      const double sign = a0 < b0 ? 1.0 : -1.0;  // history is i's view; swapping i and j negates it
      const auto first = pair_list_.neighbor.begin() + pair_list_.row_begin[static_cast<std::size_t>(a)];
      const auto last = pair_list_.neighbor.begin() + pair_list_.row_begin[static_cast<std::size_t>(a) + 1];
      const auto it = std::lower_bound(first, last, b);
      if (it == last || *it != b) continue;
      const auto sn = static_cast<std::size_t>(it - pair_list_.neighbor.begin());
      pair_list_.shear[sn] = sign * hist.pair_shear[so];
      pair_list_.roll[sn] = sign * hist.pair_roll[so];
      pair_list_.touch[sn] = 1;
    }
  }
  // Likewise each old particle's wall entries go to its own new particle's entries.
  const std::size_t old_owners = hist.wall_begin.empty() ? 0 : hist.wall_begin.size() - 1;
#pragma omp parallel for num_threads(nt) schedule(dynamic, 512)
  for (std::size_t io = 0; io < old_owners; ++io) {
    const std::int32_t a = io < map.size() ? map[io] : -1;
    if (a < 0) continue;
    for (auto e = hist.wall_begin[io]; e < hist.wall_begin[io + 1]; ++e) {
      const auto eo = static_cast<std::size_t>(e);
      for (auto k = wall_list_.begin[static_cast<std::size_t>(a)]; k < wall_list_.begin[static_cast<std::size_t>(a) + 1]; ++k) {
        const auto kn = static_cast<std::size_t>(k);
        if (wall_list_.wall[kn] == hist.wall_wall[eo] && wall_list_.element[kn] == hist.wall_element[eo]) {
          wall_list_.shear[kn] = hist.wall_shear[eo];
          wall_list_.roll[kn] = hist.wall_roll[eo];
          wall_list_.touch[kn] = 1;
          break;
        }
      }
    }
  }

  index_map_.resize(n);
  x_ref_.resize(n);
  {
    const Vec3* __restrict px = p_.x.data();
    Vec3* __restrict xr = x_ref_.data();
    std::int32_t* __restrict im = index_map_.data();
#pragma omp parallel for num_threads(nt) schedule(static)
    for (std::size_t i = 0; i < n; ++i) {
      im[i] = static_cast<std::int32_t>(i);
      xr[i] = px[i];
    }
  }
  pair_list_.measure_gaps(x_ref_.data(), p_.radius.data(), n, nt);
  // How far every particle is from each sink now: until one has moved that far, none can be behind
  // it, and insert_and_delete skips its scan (a particle moves at most max_disp_ from x_ref_). The
  // particles within one skin of a sink are listed: until max_disp_ reaches the skin no other can
  // be behind it, so the scan, when it cannot be skipped, looks at them only.
  sink_clearance_.resize(sinks_.size());
  sink_near_.resize(sinks_.size());
  sink_reach_.resize(sinks_.size());
  for (std::size_t k = 0; k < sinks_.size(); ++k) {
    // A local minimum: stored through the member each time, it was a store-to-load chain per
    // particle (aliasing), about a fifth of a station rebuild's serial time.
    const Vec3 point = sinks_[k].point, normal = sinks_[k].normal;
    const double reach = skin_ * normal.norm();
    double c = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < n; ++i) c = std::min(c, (p_.x[i] - point).dot(normal));
    sink_clearance_[k] = c;
    sink_reach_[k] = reach;
    std::vector<std::int32_t>& near = sink_near_[k];
    near.clear();
    if (c <= reach)  // only a sink some particle is near needs the list
      for (std::size_t i = 0; i < n; ++i)
        if ((p_.x[i] - point).dot(normal) <= reach) near.push_back(static_cast<std::int32_t>(i));
  }
  for (std::size_t k = 0; k < walls_.size(); ++k) {
    wall_time_ref_[k] = time_;
    wall_listed_moving_[k] = walls_[k].motion.moving() ? 1 : 0;
  }
  max_disp_ = 0.0;
  list_dirty_ = false;
  ++rebuilds_;
}

}  // namespace chutelab::dem
