#pragma once
// The Verlet neighbour list: the pairs within cut-off R_i + R_j + skin (half list, j > i, ascending
// per row, CSR by row) with each slot's contact history. Built from a cell grid; World keeps it until
// some particle has moved more than skin/2 (or a wall more than the skin minus that,
// World::needs_rebuild), and carries the history of the touching contacts over to the next build.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "dem/cell_grid.h"
#include "dem/contact_history.h"
#include "dem/particles.h"
#include "dem/types.h"

// The pair loop's AVX-512 form screens the slots by their gap at the rebuild (NeighborList::gap);
// other builds test every slot and keep no gaps.
#if defined(__AVX512F__) && defined(__AVX512VL__) && defined(__AVX512BW__)
#define CHUTELAB_DEM_PAIR_GAPS 1
#else
#define CHUTELAB_DEM_PAIR_GAPS 0
#endif

namespace chutelab::dem {

class NeighborList {
 public:
  std::vector<std::int32_t> row_begin;  // size N+1
  std::vector<std::int32_t> neighbor;
  std::vector<Vec3> shear;  // tangential history, i's view
  std::vector<Vec3> roll;   // rolling history, i's view
  std::vector<std::uint8_t> touch;
  std::vector<std::int32_t> slot_row;  // row (particle i) of each slot, so the pair loop is one flat loop
  // Per slot, a lower bound of the gap between the two surfaces at the reference positions (float,
  // rounded down, less gap_eps): while every particle is within d of its reference position, a slot
  // whose gap exceeds 2 d + gap_eps cannot touch (CHUTELAB_DEM_PAIR_GAPS builds only).
  std::vector<float> gap;
  double gap_eps = 0.0;

  // Every pair within cut-off: the own cell and the forward half of the 27-cell stencil. sorted:
  // the particles are in cell order (CellGrid::sort_by), which the search uses. History starts at
  // zero (carry_history fills in the contacts that touched); slot_row is indexed.
  void build(const CellGrid& grid, const Particles& p, double skin, bool sorted, int threads);
  void index_slots(int threads);  // slot_row from row_begin
  // The gaps from the positions the displacements are measured from.
  void measure_gaps(const Vec3* x_ref, const double* radius, std::size_t n, int threads);
  // The touching pairs of the last list into their slots of this one; map: old index -> new (-1 gone).
  void carry_history(const TouchingHistory& saved, const std::vector<std::int32_t>& map, int threads);
  std::size_t rows() const { return row_begin.empty() ? 0 : row_begin.size() - 1; }

 private:
  // Each thread's rows during the search, kept between builds as the lists are.
  std::vector<std::vector<std::int32_t>> row_buffers_;
};

}  // namespace chutelab::dem
