#pragma once
// Pressure and wear maps of a wall (the impact plate, [dem.stl] walls): per triangle of its mesh,
// the steady-window means of the contact force, the impact and sliding energy fluxes and the two
// wear models' rates (dem/wear/archard.h, dem/wear/finnie.h).
//
// The recorder watches the wall's contacts every step (World::observe_wall) and sums, per triangle
// and per block of force samples: the impulse of the contact forces; the normal kinetic energy
// 1/2 m v_n^2 of every impact (a particle whose previous step had no contact with the wall); the
// frictional work |F_t . v_t| dt; Archard's F_n |v_t| dt; Finnie's M v^2 f(alpha) per impact. The
// steady window is known only at the end of the run, so the blocks are kept (only the cells each
// block touched: a stream loads a band of the plate) and the ones inside the window summed then. A
// block is one force sample until the store would pass ~32 MB; then neighbouring blocks merge, and
// a window edge falling inside a merged block drops it (the map then averages over a few ms less
// than the load cell).
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <unordered_map>
#include <vector>

#include "dem/station/settings.h"
#include "dem/walls/wall.h"
#include "dem/walls/wall_contact.h"
#include "dem/wear/archard.h"
#include "dem/wear/finnie.h"

namespace chutelab::dem::station {

// One triangle: geometry and steady means (SI).
struct MapCell {
  std::array<Vec3, 3> corners{};
  Vec3 normal = Vec3::UnitX();   // unit, the way the particles push the wall (into it)
  double area = 0.0;             // m^2
  Vec3 force = Vec3::Zero();     // mean contact force on the triangle, N
  double impact_power = 0.0;     // W: normal kinetic energy of the impacts per second
  double sliding_power = 0.0;    // W: frictional work per second
  double load_slip = 0.0;        // N m/s: Archard's F_n |v_t| summed per second
  double finnie_measure = 0.0;   // kg m^2/s^3: Finnie's M v^n f(alpha) summed per second
  double impacts = 0.0;          // impacts per second
  // The same means over each `block` of the window (counted back from its end), for the standard
  // errors (batch means, as the load cell's, steady_state.h): normal force N, N m/s, kg m^2/s^3.
  std::vector<double> block_normal, block_load_slip, block_finnie;
  Vec3 centroid() const { return (corners[0] + corners[1] + corners[2]) / 3.0; }
  double pressure() const { return area > 0.0 ? force.dot(normal) / area : 0.0; }  // Pa
  double shear_stress() const {                                                      // Pa
    return area > 0.0 ? (force - force.dot(normal) * normal).norm() / area : 0.0;
  }
  double archard_rate(const WearInputs& w) const;  // m/s of depth
  double finnie_rate(const WearInputs& w) const;   // m/s of depth
  // Standard errors of pressure() and of the total wear rate from the block means (NaN with fewer
  // than two blocks).
  double pressure_se() const;
  double wear_rate_se(const WearInputs& w) const;
};

// A grid of square-ish cells laid on a flat rectangular face (the generated plate) for the maps,
// independent of the wall's triangles: a contact counts in the cell its contact point lies in. The
// World never sees it (the wall stays two triangles), so the physics and its round-off are those of
// the coarse plate; only the map is resolved. Each cell is reported as two triangles carrying half
// of its sums each (the maps' data are triangles), so both halves show the cell's value.
struct MapGrid {
  Vec3 origin = Vec3::Zero();  // the face's top edge at z = -width/2
  Vec3 down = -Vec3::UnitY();  // unit, along the face downward
  Vec3 across = Vec3::UnitZ(); // unit, across the face
  double height = 0.0, width = 0.0;  // m
  int rows = 1, cols = 1;
  // Cells of about `cell` m (at most 400 rows or columns), on the face of a PlateFrame.
  static MapGrid on_face(const Vec3& top_edge, const Vec3& down, double height, double width, double cell);
  // The map's triangles, two a cell (2 b and 2 b + 1 for cell b = row * cols + column).
  std::vector<std::array<Vec3, 3>> triangles() const;
};

struct PlateMap {
  std::string wall;              // "plate" or the STL file
  double duration = 0.0;         // s of the steady window the means cover
  std::vector<MapCell> cells;
  std::optional<MapGrid> grid;   // the cells are this grid's triangles (the cache stores it compactly)
  Vec3 total_force() const;
};

class PlateMapRecorder {
 public:
  // With `grid`, the wall's contacts are binned on it (MapGrid); without, per triangle of the wall.
  PlateMapRecorder(const Wall& wall, const wear::FinnieParams& finnie, std::size_t max_samples,
                   const MapGrid* grid = nullptr);
  void observe(const WallContact& c);
  // Closes the force sample ending at t (the recorder's block boundaries follow the samples).
  void end_sample(double t);
  // Means over the samples with t in (start, end], and per `block` s counted back from end
  // (0: no blocks).
  PlateMap reduce(double start, double end, double block = 0.0) const;

 private:
  // Fx Fy Fz (N s), impact J, sliding J, Archard N m, Finnie, impacts, contact normal . face normal (s)
  static constexpr std::size_t kChannels = 9;
  std::size_t bin_of(const WallContact& c) const;
  void merge_blocks();
  std::string name_;
  std::vector<std::array<Vec3, 3>> corners_;  // the map's triangles
  std::vector<Vec3> normals_;  // unit, of the corners' winding
  // What the sums are kept per: a triangle of the wall, or a cell of the grid (its two triangles,
  // 2 b and 2 b + 1, each get half).
  std::size_t bins_ = 0, triangles_per_bin_ = 1;
  std::optional<MapGrid> grid_;
  wear::FinnieParams finnie_;
  std::size_t samples_per_block_ = 1;
  std::size_t in_block_ = 0;
  double block_start_ = 0.0;
  std::vector<double> current_;                 // bins x channels, the block being summed
  std::vector<std::uint32_t> touched_;          // bins of current_ with a contact in this block
  std::vector<std::uint8_t> touched_flag_;      // per bin: in touched_
  // The finished blocks, sparse: entries (bin, channels) of the touched bins, block b's entries in
  // [block_begin_[b], block_begin_[b + 1]).
  std::vector<std::uint32_t> store_bins_;
  std::vector<double> store_;                   // entries x channels
  std::vector<std::size_t> block_begin_;
  std::vector<double> block_t0_, block_t1_;     // (start, end] of each block
  std::int64_t last_step_ = 0;
  std::unordered_map<std::int64_t, std::int64_t> last_touch_;  // particle id -> last step in contact
};

// The pressure along the face, averaged across it: each triangle's load spread over its height into
// bins of `bin` m from the top (bin <= 0: the triangles' median height, one bin a row of cells).
// Rows are (y of the bin's centre, mean pressure Pa), top to bottom.
std::vector<std::pair<double, double>> pressure_profile(const PlateMap& m, double bin = 0.0);
// Height of the peak of that profile, m, refined by a parabola through the peak bin and its
// neighbours (NaN for an unloaded map).
double peak_pressure_y(const PlateMap& m, double bin = 0.0);
// Centre of pressure: the height where the normal load acts (sum p A y / sum p A), m.
double pressure_centre_y(const PlateMap& m);

// A map cell's geometry from its corners as the recorder computes it (area, unit normal of the
// corners' winding, flipped when `flip`), its values zero: for readers that rebuild a grid map.
MapCell empty_cell(const std::array<Vec3, 3>& corners, bool flip, std::size_t blocks);

// OUT/plate_map.csv (every map, one row per triangle, units in the column names) and a VTK of the
// maps for ParaView.
void write_plate_map_csv(const std::string& path, const std::vector<PlateMap>& maps, const WearInputs& w,
                         const std::string& condition);
void write_plate_map_vtk(const std::string& path, const std::vector<PlateMap>& maps, const WearInputs& w);

}  // namespace chutelab::dem::station
