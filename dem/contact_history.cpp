#include "dem/contact_history.h"

#include <algorithm>

#include "dem/neighbor_list.h"
#include "dem/storage.h"
#include "dem/team.h"
#include "dem/walls/wall_contact_list.h"

namespace chutelab::dem {
namespace {

// The touching entries of a list in CSR form (row `begin`, per-entry `touch`), compacted into
// `out_begin` by the same rows: count per row, prefix sum, then `size(total)` and `copy(from, to)`
// for each touching entry, in entry order (touch is 0 or 1).
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
    on_team(nt, [&] {
#pragma omp for schedule(static)
      for (std::size_t r = 0; r < rows; ++r) {
        std::int32_t c = 0;
        for (auto e = rb[r]; e < rb[r + 1]; ++e) c += to[static_cast<std::size_t>(e)];
        ob[r + 1] = c;
      }
    });
  }
  for (std::size_t r = 0; r < rows; ++r) out_begin[r + 1] += out_begin[r];
  size(static_cast<std::size_t>(out_begin[rows]));
  if (rows == 0) return;
  // Each thread's rows are one range of entries and one range of the output, so the copy runs over
  // entries, not rows. A batch's touching entries are listed first (no branch) and copied after: the
  // copies' loads are scattered over the whole list, and without a mispredicted branch between them
  // they overlap instead of waiting one after the other. In a station run's profile the copy fell
  // from 5 % to under 2 %, though the run gained only 1-2 %: the next pass over the same lines then
  // waits for them (bench/log/RESULTS.md, 2026-12-05).
  on_team(nt, [&] {
    const auto t = static_cast<std::size_t>(omp_get_thread_num());
    const auto team = static_cast<std::size_t>(omp_get_num_threads());
    const auto [r0, r1] = even_share(rows, t, team);
    auto to = static_cast<std::size_t>(out_begin[r0]);
    const auto e1 = static_cast<std::size_t>(begin[r1]);
    const std::uint8_t* __restrict tb = touch.data();
    constexpr std::size_t kBatch = 256;
    std::size_t listed[kBatch];
    for (auto b = static_cast<std::size_t>(begin[r0]); b < e1; b += kBatch) {
      const std::size_t end = std::min(b + kBatch, e1);
      std::size_t m = 0;
      for (std::size_t e = b; e < end; ++e) {
        listed[m] = e;
        m += tb[e];
      }
      for (std::size_t k = 0; k < m; ++k) copy(listed[k], to++);
    }
  });
}

}  // namespace

void TouchingHistory::save(const NeighborList& pairs, const WallContactList& walls, int nt) {
  compact_touching(
      pairs.row_begin, pairs.touch, nt, pair_begin,
      [&](std::size_t m) {
        resize_for_overwrite(pair_other, m);
        resize_for_overwrite(pair_shear, m);
        resize_for_overwrite(pair_roll, m);
      },
      [&](std::size_t from, std::size_t to) {
        pair_other[to] = pairs.neighbor[from];
        pair_shear[to] = pairs.shear[from];
        pair_roll[to] = pairs.roll[from];
      });
  compact_touching(
      walls.begin, walls.touch, nt, wall_begin,
      [&](std::size_t m) {
        resize_for_overwrite(wall_wall, m);
        resize_for_overwrite(wall_element, m);
        resize_for_overwrite(wall_shear, m);
        resize_for_overwrite(wall_roll, m);
      },
      [&](std::size_t from, std::size_t to) {
        wall_wall[to] = walls.wall[from];
        wall_element[to] = walls.element[from];
        wall_shear[to] = walls.shear[from];
        wall_roll[to] = walls.roll[from];
      });
}

}  // namespace chutelab::dem
