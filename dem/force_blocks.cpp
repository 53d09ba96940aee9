#include "dem/force_blocks.h"

#include <algorithm>

#include <omp.h>

#include "dem/storage.h"
#include "dem/team.h"

namespace chutelab::dem {

void ForceBlocks::layout(std::size_t n, std::size_t count, int threads, const std::vector<std::int32_t>& row_begin,
                         const std::vector<std::int32_t>& neighbor, const std::vector<std::int32_t>& wall_begin) {
  first_row_.assign(count + 1, n);
  reach_end_.assign(count, 0);
  offset_.assign(count + 1, 0);
  // Blocks of equal estimated work, not of equal rows: threads take whole blocks, so with blocks of
  // very different cost no cut between threads is even (bench bed, one thread, per block: the floor
  // layer's 115 ms against 90 and the top layer's 65, so the best cut of 16 blocks left two threads
  // 42 ms apart in 1.47 s). The work of the rows before row i, in units of one pair slot, is
  // kRowCost i + row_begin[i] + kWallCost wall_begin[i], rising with i, so each boundary is a binary
  // search. The weights are that measurement's (per slot 13-15 ns with its share of contact laws,
  // per wall entry 81 ns, per row ~15 ns of finishing and integration); they move work between
  // threads only, never a number, as the boundaries come from the lists alone (the same at any
  // thread count, and after a checkpoint's restore).
  constexpr std::int64_t kRowCost = 1, kWallCost = 6;
  auto work_before = [&](std::size_t i) {
    return kRowCost * static_cast<std::int64_t>(i) + row_begin[i] + kWallCost * wall_begin[i];
  };
  const std::int64_t total = work_before(n);
  if (count > 0) first_row_[0] = 0;
  for (std::size_t b = 1; b < count; ++b) {
    const std::int64_t target = total * static_cast<std::int64_t>(b) / static_cast<std::int64_t>(count);
    std::size_t lo = first_row_[b - 1], hi = n;  // the first row with work_before >= target
    while (lo < hi) {
      const std::size_t mid = lo + (hi - lo) / 2;
      if (work_before(mid) < target) lo = mid + 1;
      else hi = mid;
    }
    first_row_[b] = lo;
  }
  on_team(threads, [&] {
#pragma omp for schedule(static)
    for (std::size_t b = 0; b < count; ++b) {
      const std::size_t r0 = first_row_[b], r1 = first_row_[b + 1];
      std::size_t reach = r1;
      for (auto s = row_begin[r0]; s < row_begin[r1]; ++s)
        reach = std::max(reach, static_cast<std::size_t>(neighbor[static_cast<std::size_t>(s)]) + 1);
      reach_end_[b] = reach;
    }
  });
  for (std::size_t b = 0; b < count; ++b) offset_[b + 1] = offset_[b] + (reach_end_[b] - first_row_[b]);
  first_reaching_.assign(count, 0);
  for (std::size_t b = 0; b < count; ++b) {
    std::size_t first = b;
    for (std::size_t a = 0; a < b; ++a)
      if (reach_end_[a] > first_row_[b]) {
        first = a;
        break;
      }
    first_reaching_[b] = first;
  }
  resize_for_overwrite(force_, offset_[count]);
  resize_for_overwrite(torque_, offset_[count]);
  // Zero between force evaluations (the evaluation that reads an entry clears it), each block by the
  // thread that takes it in the pair pass while the cut between threads is even.
  on_team(threads, [&] {
#pragma omp for schedule(static)
    for (std::size_t b = 0; b < count; ++b) {
      const auto lo = static_cast<std::ptrdiff_t>(offset_[b]), hi = static_cast<std::ptrdiff_t>(offset_[b + 1]);
      std::fill(force_.begin() + lo, force_.begin() + hi, Vec3::Zero());
      std::fill(torque_.begin() + lo, torque_.begin() + hi, Vec3::Zero());
    }
  });
}

void ForceBlocks::reduce(std::size_t ob, Vec3* f, Vec3* t) {
  const std::size_t lo = first_row_[ob], hi = first_row_[ob + 1];
  // The first buffer that reaches a particle is copied, not added to zero: a buffer never holds
  // -0.0 (it starts at +0.0 and, rounding to nearest, a sum or difference is -0.0 only when it
  // already was), and 0.0 + x is x for every other x. Zero beyond its reach.
  bool first = true;
  for (std::size_t b = first_reaching_[ob]; b <= ob; ++b) {
    const std::size_t end = std::min(hi, reach_end_[b]);
    if (end <= lo) continue;
    double* __restrict fs = (force_.data() + offset_[b] + (lo - first_row_[b]))->data();
    double* __restrict ts = (torque_.data() + offset_[b] + (lo - first_row_[b]))->data();
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
}

std::pair<std::size_t, std::size_t> ForceBlocks::thread_blocks() const {
  const auto t = static_cast<std::size_t>(omp_get_thread_num());
  const auto nt = static_cast<std::size_t>(omp_get_num_threads());
  return cut_.blocks(t, nt, count());
}

std::pair<std::size_t, std::size_t> ForceBlocks::thread_rows(std::size_t n) const {
  const auto t = static_cast<std::size_t>(omp_get_thread_num());
  const auto nt = static_cast<std::size_t>(omp_get_num_threads());
  const std::size_t nb = count();
  if (nb == 0) return even_share(n, t, nt);
  const auto [b0, b1] = cut_.blocks(t, nt, nb);
  return {std::min(first_row_[b0], n), b1 == nb ? n : std::min(first_row_[b1], n)};
}

void ThreadCut::fit(std::size_t nt, std::size_t blocks) {
  if (at.size() == nt + 1 && at.back() == blocks) return;
  at.resize(nt + 1);
  for (std::size_t t = 0; t <= nt; ++t) at[t] = blocks * t / nt;
  busy.assign(nt, 0.0);
  steps = 0;
}

std::pair<std::size_t, std::size_t> ThreadCut::blocks(std::size_t t, std::size_t nt, std::size_t nblocks) const {
  if (at.size() == nt + 1 && at.back() == nblocks) return {at[t], at[t + 1]};
  return even_share(nblocks, t, nt);
}

// A block moves to the neighbouring thread only when the busier of the two would stay busier after
// giving it (its time exceeds the other's by more than one of its blocks): so a cut never swings
// back and forth, and an even pair stays as it is.
void ThreadCut::step() {
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

}  // namespace chutelab::dem
