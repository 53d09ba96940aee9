#include "dem/contact_history.h"

#include "dem/neighbor_list.h"
#include "dem/storage.h"
#include "dem/team.h"
#include "dem/walls/wall_contact_list.h"

namespace chutelab::dem {
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
  on_team(nt, [&] {
#pragma omp for schedule(static)
    for (std::size_t r = 0; r < rows; ++r) {
      auto to = static_cast<std::size_t>(out_begin[r]);
      for (auto e = begin[r]; e < begin[r + 1]; ++e)
        if (touch[static_cast<std::size_t>(e)]) copy(static_cast<std::size_t>(e), to++);
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
