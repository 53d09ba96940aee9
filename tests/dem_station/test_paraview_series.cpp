#define BOOST_TEST_MODULE paraview_series
// `simulate --out` writes the particles as a time series ParaView opens as one (vtk/particles.pvd
// and one .vtp per frame, dem/io/vtk_series.h). VTK's own XML reader (Debian's python3-vtk9, as
// ParaView reads it) reads every frame back, and each frame's particle count equals the count the
// run recorded at that instant (sensors.csv). Our own main: without python3-vtk9 ctest shows the
// test skipped, not passed.
#define BOOST_TEST_NO_MAIN
#include <boost/test/unit_test.hpp>
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <map>
#include <sstream>

#include "../cli/cli_runner.h"

using namespace chutelab::test;
namespace fs = std::filesystem;

namespace {
// "name=lo:hi" in a reader's line, as two numbers.
std::pair<double, double> range(const std::string& line, const std::string& name) {
  const auto at = line.find(name);
  BOOST_REQUIRE_MESSAGE(at != std::string::npos, name << " in " << line);
  const auto colon = line.find(':', at);
  return {std::stod(line.substr(at + name.size(), colon - at - name.size())), std::stod(line.substr(colon + 1))};
}

const fs::path kPython = "/usr/bin/python3";  // Debian's, where python3-vtk9 installs
const std::string kReader = std::string(CHUTELAB_SOURCE_DIR) + "/tests/dem_station/read_series.py";
constexpr int kSkip = 77;
}  // namespace

BOOST_AUTO_TEST_CASE(series_reads_back_with_the_runs_particle_counts) {
  ::setenv("CHUTELAB_DEM_CACHE", fresh_dir("series-cache").c_str(), 1);
  const fs::path out = fresh_dir("series-out");
  const fs::path dataset = tiny_station_dataset("series-dataset");
  // 0.04 s frames: a multiple of the tiny run's snapshot interval, so frames and snapshots meet.
  const auto r = run_chutelab("simulate --dataset " + dataset.string() + " --condition T3 --no-cache --vtk-every 0.04 --out " +
                              out.string());
  BOOST_REQUIRE_MESSAGE(r.exit_code == 0, r.err);
  const std::string listing = (out / "listing.txt").string();
  std::string legacy;
  for (const char* f : {"side_view.vtk", "plate_map.vtk", "vtk/walls.vtk"})
    if (fs::exists(out / f)) legacy += " '" + (out / f).string() + "'";
  const int rc = std::system(("'" + kPython.string() + "' '" + kReader + "' '" + (out / "vtk" / "particles.pvd").string() + "'" +
                              legacy + " >'" + listing + "' 2>'" + (out / "reader.err").string() + "'")
                                 .c_str());
  BOOST_REQUIRE_MESSAGE(WIFEXITED(rc) && WEXITSTATUS(rc) == 0, "reader: " << read_file(out / "reader.err"));
  // The run's own count at each snapshot: sensors.csv (t_s, particles, ...).
  std::map<long, long> recorded;  // t in 10 us -> particles
  {
    std::istringstream in(read_file(out / "sensors.csv"));
    std::string line;
    std::getline(in, line);
    BOOST_REQUIRE(line.rfind("t_s,particles", 0) == 0);
    while (std::getline(in, line)) {
      const auto c = line.find(',');
      recorded[std::lround(std::stod(line.substr(0, c)) * 1e5)] = std::stol(line.substr(c + 1));
    }
  }
  std::istringstream in(read_file(listing));
  std::string line;
  int frames = 0, matched = 0;
  double last_t = -1.0;
  long max_points = 0;
  const std::string run = read_file(out / "run.txt");
  const auto d_at = run.find("particle_diameter_mm = ");
  BOOST_REQUIRE(d_at != std::string::npos);
  const double diameter_mm = std::stod(run.substr(d_at + 23));
  BOOST_TEST(diameter_mm > 5.0);
  std::map<std::string, std::string> legacy_lines;  // file name -> its line
  double largest_x = 0.0;
  while (std::getline(in, line)) {
    if (line.rfind("legacy ", 0) == 0) {
      legacy_lines[line.substr(7, line.find(' ', 7) - 7)] = line;
      continue;
    }
    std::istringstream ls(line);
    double t = 0;
    long points = 0, verts = 0;
    ls >> t >> points >> verts;
    // Lengths in mm, as every other file of the run: the radius is half run.txt's diameter in mm,
    // and the stream reaches the plate 350 mm from the pulley (in metres both would be below 1).
    if (points > 0) {
      const auto r = range(line, "radius_mm=");
      BOOST_TEST(r.first == 0.5 * diameter_mm, boost::test_tools::tolerance(1e-9));
      BOOST_TEST(r.second == 0.5 * diameter_mm, boost::test_tools::tolerance(1e-9));
      largest_x = std::max(largest_x, range(line, "x=").second);
    }
    ++frames;
    BOOST_TEST(t > last_t);
    last_t = t;
    BOOST_TEST(verts == points);
    max_points = std::max(max_points, points);
    if (auto it = recorded.find(std::lround(t * 1e5)); it != recorded.end()) {
      BOOST_TEST(points == it->second, "t = " << t << " s: series " << points << ", run " << it->second);
      ++matched;
    }
  }
  BOOST_TEST_MESSAGE(frames << " frames read by VTK, " << matched << " at a snapshot of the run, up to " << max_points
                            << " particles; last frame at " << last_t << " s");
  BOOST_TEST(frames >= 5);
  BOOST_TEST(matched >= 3);
  BOOST_TEST(max_points > 100);
  BOOST_TEST(largest_x > 250.0);
  BOOST_TEST(largest_x < 400.0);
  // The legacy files: in mm and saying so. The side view's points are side_view.csv's (mm).
  for (const auto& [file, l] : legacy_lines) BOOST_TEST(l.find("lengths in mm") != std::string::npos, l);
  BOOST_TEST_REQUIRE(legacy_lines.count("side_view.vtk"));
  BOOST_TEST_REQUIRE(legacy_lines.count("walls.vtk"));
  {
    double lo = 1e9, hi = -1e9;
    std::istringstream csv(read_file(out / "side_view.csv"));
    std::string row;
    std::getline(csv, row);
    BOOST_REQUIRE(row.rfind("x_mm,y_mm,z_mm", 0) == 0);
    while (std::getline(csv, row)) {
      const double x = std::stod(row.substr(0, row.find(',')));
      lo = std::min(lo, x), hi = std::max(hi, x);
    }
    const auto side = range(legacy_lines["side_view.vtk"], "x=");
    BOOST_TEST(side.first == lo, boost::test_tools::tolerance(1e-6));
    BOOST_TEST(side.second == hi, boost::test_tools::tolerance(1e-6));
  }
  // The plate's face: the walls reach it at x = 350 mm; its map (when written) lies on it.
  BOOST_TEST(range(legacy_lines["walls.vtk"], "x=").second >= 350.0);
  if (legacy_lines.count("plate_map.vtk")) {
    const auto x = range(legacy_lines["plate_map.vtk"], "x=");
    BOOST_TEST(x.first == 350.0, boost::test_tools::tolerance(0.01));
    BOOST_TEST(x.second == 350.0, boost::test_tools::tolerance(0.01));
    BOOST_TEST(range(legacy_lines["plate_map.vtk"], "z=").second > 100.0);
  }
}

int main(int argc, char* argv[]) {
  if (std::system(("'" + kPython.string() + "' -c 'import vtkmodules.vtkIOXML' 2>/dev/null").c_str()) != 0) {
    std::cerr << "SKIPPED: " << kPython << " has no VTK (Debian's python3-vtk9; scripts/setup.sh installs it): the "
                 "ParaView series was not read back.\n";
    return kSkip;
  }
  return boost::unit_test::unit_test_main(&init_unit_test, argc, argv);
}
