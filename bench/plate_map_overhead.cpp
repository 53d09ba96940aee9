// Cost of the plate map recorder (dem/station/plate_map.h): the tiny station of the tests, plate
// meshed in 16 rows, stepped 4000 steps after filling, alternately without and with the recorder
// observing the plate (same scene, same seed, so the same particles), three times each. With the
// argument `grid`: the plate as its two triangles and the recorder binning on the default 10 mm
// map grid (MapGrid), as every run does by default.
#include <cstring>
#include <chrono>
#include <cstdio>
#include "dem/station/plate_map.h"
#include "dem/station/scene.h"
#include "tests/dem_station/tiny_station.h"
using namespace chutelab;
using namespace chutelab::dem::station;
int main(int argc, char** argv) {
  const bool grid = argc > 1 && std::strcmp(argv[1], "grid") == 0;
  const auto st = test::tiny_station();
  auto s = test::tiny_settings();
  s.plate_cells = grid ? 0 : 16;
  double t[2] = {0, 0};
  for (int rep = 0; rep < 3; ++rep)
    for (int mode = 0; mode < 2; ++mode) {
      Scene sc = build_scene(st, s, DemTable{}, ExternalInputs{});
      auto& w = *sc.world;
      w.initialise();
      std::unique_ptr<PlateMapRecorder> rec;
      if (mode == 1) {
        const MapGrid g = MapGrid::on_face(sc.plate.top_edge, sc.plate.down, sc.plate.height, sc.plate.width, s.map_cell);
        rec = std::make_unique<PlateMapRecorder>(w.walls()[sc.plate_wall], s.wear.finnie, 1000, grid ? &g : nullptr);
        w.observe_wall(sc.plate_wall, [p = rec.get()](const dem::WallContact& c) { p->observe(c); });
      }
      w.step(3000);  // fill the rig (untimed)
      const auto a = std::chrono::steady_clock::now();
      for (int k = 0; k < 100; ++k) { w.step(40); if (rec) rec->end_sample(w.time()); sc.discharge(); }
      const double d = std::chrono::duration<double>(std::chrono::steady_clock::now() - a).count();
      t[mode] += d;
      std::printf("rep %d %s: %.3f s, %zu particles, %zu wall contacts\n", rep, mode ? "map" : "no map", d,
                  w.particles().size(), w.wall_contact_count());
    }
  std::printf("ratio map/no map: %.3f\n", t[1] / t[0]);
}
