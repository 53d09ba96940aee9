// Pressure and wear maps of the plate (dem/station/plate_map.h, dem/wear/): the wear models against
// closed forms on one sphere, and the maps of the tiny station against its load cell and the
// analytical impact zone.
#define BOOST_TEST_MODULE dem_plate_map
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>

#include "analytical/impact_zone.h"
#include "core/input_error.h"
#include "dem/station/cache.h"
#include "dem/station/plate_map.h"
#include "dem/station/run.h"
#include "dem/world.h"
#include "tiny_station.h"

using namespace chutelab;
using namespace chutelab::dem;
using namespace chutelab::dem::station;
namespace tt = boost::test_tools;

namespace {

constexpr double kPi = 3.14159265358979323846;

// A horizontal square plate of two triangles (z = 0, normal +z), as the station's plate is built.
Wall flat_plate(int material) {
  const double h = 0.1;
  return Wall::mesh("plate", TriangleMesh::from_soup({{Vec3(-h, -h, 0), Vec3(h, -h, 0), Vec3(h, h, 0)},
                                                      {Vec3(-h, -h, 0), Vec3(h, h, 0), Vec3(-h, h, 0)}}),
                    material);
}

struct OneSphere {
  std::unique_ptr<World> w;
  int plate = -1;
  double mass = 0.0;
};

OneSphere one_sphere(const Vec3& gravity, double friction, const Vec3& x0, const Vec3& v0) {
  Settings s;
  s.gravity = gravity;
  s.domain = Box{Vec3::Constant(-1.0), Vec3::Constant(1.0)};
  s.on_warning = [](const std::string&) {};
  s.threads = 1;
  s.rolling = RollingModel::none;
  if (friction == 0.0) s.tangential = TangentialModel::frictionless;
  OneSphere o;
  o.w = std::make_unique<World>(s);
  const int ball = o.w->materials().add({"ball", 1e7, 0.3, 1000.0});
  const int wall = o.w->materials().add({"wall", 1e7, 0.3, 7800.0});
  Interaction in;
  in.friction = friction;
  in.restitution = 0.2;
  o.w->materials().set_interaction(ball, wall, in);
  o.plate = o.w->add_wall(flat_plate(wall));
  const double r = 0.005;
  o.w->add_particle({x0, v0, Vec3::Zero(), r, ball});
  o.mass = 1000.0 * 4.0 / 3.0 * kPi * r * r * r;
  return o;
}

// Observes the plate into `rec` and steps `samples` samples of 10 ms, ending one after each; returns
// the sample's length (a whole number of steps).
double record_samples(OneSphere& o, PlateMapRecorder& rec, int samples) {
  o.w->observe_wall(o.plate, [&rec](const WallContact& c) { rec.observe(c); });
  const auto per = static_cast<std::int64_t>(std::llround(0.01 / o.w->dt()));
  for (int k = 1; k <= samples; ++k) {
    o.w->step(per);
    rec.end_sample(o.w->time());
  }
  return static_cast<double>(per) * o.w->dt();
}

}  // namespace

// A sphere resting under gravity on a frictionless plate whose surface slides at U under it: the
// normal load is m g and the sliding distance U T, so Archard's volume is k_A m g U T / H. The plate
// is made to slide (not the sphere) so that nothing slows the slip down. Tolerance 1e-6: the sphere
// settles (restitution 0.2) before the window, then only round-off remains.
BOOST_AUTO_TEST_CASE(archard_volume_of_a_sliding_sphere) {
  const double g = 9.81, U = 0.7;
  OneSphere o = one_sphere(Vec3(0, 0, -g), 0.0, Vec3(0, 0, 0.0049), Vec3::Zero());
  o.w->wall(o.plate).surface.linear = Vec3(U, 0, 0);
  o.w->initialise();
  PlateMapRecorder rec(o.w->walls()[static_cast<std::size_t>(o.plate)], wear::FinnieParams{}, 1000);
  const double sample = record_samples(o, rec, 60);
  const double t1 = o.w->time(), t0 = t1 - 29.5 * sample;  // the last 30 samples
  const PlateMap m = rec.reduce(t0, t1);
  BOOST_TEST(m.duration == 30 * sample, tt::tolerance(1e-9));
  double load_slip = 0.0;
  Vec3 f = Vec3::Zero();
  for (const auto& c : m.cells) load_slip += c.load_slip, f += c.force;
  const double weight = o.mass * g;
  BOOST_TEST(f.z() == -weight, tt::tolerance(1e-6));
  BOOST_TEST(load_slip == weight * U, tt::tolerance(1e-6));
  WearInputs wi;
  wi.archard.coefficient = 3e-5;
  wi.archard.hardness = 2e9;
  double volume = 0.0;
  for (const auto& c : m.cells) volume += c.archard_rate(wi) * c.area * m.duration;
  BOOST_TEST(volume == 3e-5 * weight * U * m.duration / 2e9, tt::tolerance(1e-6));
  // No impact in the window: the sphere stayed in contact.
  double impacts = 0.0;
  for (const auto& c : m.cells) impacts += c.impacts;
  BOOST_TEST(impacts == 0.0);
}

// Block means when the window's end falls a hair (under the window's 1e-9 s tolerance) before the
// last sample's end: that sample is in the window, so it is in the block ending there, one sample a
// block, every block the sphere's weight. Counting blocks back with a tolerance in block units put
// it at block -1: converted to an index (undefined behaviour, UBSan's report), then dropped.
BOOST_AUTO_TEST_CASE(block_means_count_a_sample_ending_within_tolerance_after_the_window) {
  const double g = 9.81;
  OneSphere o = one_sphere(Vec3(0, 0, -g), 0.0, Vec3(0, 0, 0.0049), Vec3::Zero());
  o.w->initialise();
  PlateMapRecorder rec(o.w->walls()[static_cast<std::size_t>(o.plate)], wear::FinnieParams{}, 1000);
  const double sample = record_samples(o, rec, 40);
  const double end = o.w->time() - 5e-10, start = end - 3.0 * sample;
  const PlateMap m = rec.reduce(start, end, sample);
  BOOST_TEST(m.duration == 3.0 * sample, tt::tolerance(1e-9));
  BOOST_REQUIRE(!m.cells.empty());
  std::vector<double> normal(3, 0.0);
  for (const auto& c : m.cells) {
    BOOST_TEST_REQUIRE(c.block_normal.size() == 3u);
    for (std::size_t j = 0; j < 3; ++j) normal[j] += c.block_normal[j];
  }
  for (std::size_t j = 0; j < 3; ++j) BOOST_TEST(normal[j] == o.mass * g, tt::tolerance(1e-6));
}

// One sphere striking the plate at speed v and angle alpha to it (no gravity): one impact, with
// Finnie's volume c m v^2 f(alpha) / (p psi K) and normal energy 1/2 m (v sin alpha)^2. The first
// contact step sees the velocity before the impact exactly (no force has acted yet).
BOOST_AUTO_TEST_CASE(finnie_volume_of_one_impact) {
  for (double alpha_deg : {10.0, 30.0, 60.0}) {
    const double v = 2.0, a = alpha_deg * kPi / 180.0;
    OneSphere o = one_sphere(Vec3::Zero(), 0.3, Vec3(0, 0, 0.0051), Vec3(v * std::cos(a), 0, -v * std::sin(a)));
    o.w->initialise();
    wear::FinnieParams fp;
    fp.flow_pressure = 1e9;
    PlateMapRecorder rec(o.w->walls()[static_cast<std::size_t>(o.plate)], fp, 100);
    o.w->observe_wall(o.plate, [&](const WallContact& c) { rec.observe(c); });
    o.w->step(std::llround(0.01 / o.w->dt()));
    rec.end_sample(o.w->time());
    const PlateMap m = rec.reduce(0.0, o.w->time());
    double impacts = 0.0, measure = 0.0, energy = 0.0;
    for (const auto& c : m.cells) {
      impacts += c.impacts * m.duration;
      measure += c.finnie_measure * m.duration;
      energy += c.impact_power * m.duration;
    }
    BOOST_TEST_CONTEXT("alpha " << alpha_deg << " deg") {
      BOOST_TEST(impacts == 1.0, tt::tolerance(1e-9));
      const double f = wear::finnie_angle_function(a, 2.0);
      BOOST_TEST(measure == o.mass * v * v * f, tt::tolerance(1e-9));
      BOOST_TEST(wear::finnie_volume(fp, measure) == 0.5 * o.mass * v * v * f / (1e9 * 2.0 * 2.0), tt::tolerance(1e-9));
      BOOST_TEST(energy == 0.5 * o.mass * std::pow(v * std::sin(a), 2), tt::tolerance(1e-9));
    }
  }
}

// Finnie's two branches meet at tan(alpha) = K/6, the erosion peaks at shallow angles and vanishes
// head-on (ductile cutting).
BOOST_AUTO_TEST_CASE(finnie_angle_function_shape) {
  for (double K : {1.0, 2.0, 4.0}) {
    const double edge = std::atan(K / 6.0);
    const double below = std::sin(2 * edge) - 6.0 / K * std::pow(std::sin(edge), 2);
    BOOST_TEST(below == K / 6.0 * std::pow(std::cos(edge), 2), tt::tolerance(1e-12));
    BOOST_TEST(wear::finnie_angle_function(edge - 1e-9, K) == wear::finnie_angle_function(edge + 1e-9, K),
               tt::tolerance(1e-6));
  }
  BOOST_TEST(std::abs(wear::finnie_angle_function(kPi / 2, 2.0)) < 1e-15);
  BOOST_TEST(wear::finnie_angle_function(17.0 * kPi / 180, 2.0) > wear::finnie_angle_function(45.0 * kPi / 180, 2.0));
}

namespace {

const StationResult& tiny_map_run(double plate_distance) {
  static std::map<double, StationResult> runs;
  auto it = runs.find(plate_distance);
  if (it != runs.end()) return it->second;
  RunOptions o;
  o.settings = test::tiny_settings();
  o.settings.plate_cells = 16;  // 25 mm rows on the 400 mm plate
  Station st = test::tiny_station();
  st.plate_distance = plate_distance;
  return runs.emplace(plate_distance, run_station(st, o)).first->second;
}

}  // namespace

// The map is the load cell resolved in space: over the same window its triangles' forces add up to
// the plate's total force, so its pressure integral is R_n (a stream striking the vertical plate
// normally). Tolerance 1e-9: both sum the same contact forces, in another order.
BOOST_AUTO_TEST_CASE(map_sums_to_the_plate_force_and_R_n) {
  const StationResult& r = tiny_map_run(0.35);
  BOOST_REQUIRE(!r.maps.empty());
  const PlateMap& m = r.maps.front();
  BOOST_TEST(m.cells.size() == 2u * 16u * 24u);
  BOOST_TEST(m.duration == r.window.end - r.window.start, tt::tolerance(0.02));
  double normal = 0.0, shear_down = 0.0;
  for (const auto& c : m.cells) {
    normal += c.pressure() * c.area;
    shear_down -= c.force.y();
  }
  BOOST_TEST_MESSAGE("map: normal " << normal << " N, down " << shear_down << " N; load cell R_n " << r.normal_force.value
                                    << " +- " << r.normal_force.se << ", R_s " << r.shear_force.value);
  BOOST_TEST(normal == r.normal_force.value, tt::tolerance(1e-9));
  BOOST_TEST(m.total_force().x() == r.normal_force.value, tt::tolerance(1e-9));
  // The cells' block means (0.1 s, counted back from the window's end as the load cell's) add up to
  // the load cell's block means, so their standard errors are the same batch means.
  BOOST_REQUIRE_EQUAL(m.cells.front().block_normal.size(), static_cast<std::size_t>(r.window.blocks));
  std::vector<double> blocks(static_cast<std::size_t>(r.window.blocks), 0.0);
  for (const auto& c : m.cells)
    for (std::size_t b = 0; b < blocks.size(); ++b) blocks[b] += c.block_normal[b];
  double mean = 0.0;
  for (double b : blocks) mean += b / static_cast<double>(blocks.size());
  BOOST_TEST(mean == r.normal_force.value, tt::tolerance(0.01));  // blocks of 33 or 34 samples
  BOOST_TEST(shear_down == r.shear_force.value, tt::tolerance(1e-9));
  // Centre of pressure = the load cell's impact point (moment / force), up to the rolling couples the
  // load cell also feels (tolerance 2 mm, under a sixth of a particle).
  BOOST_TEST(std::abs(pressure_centre_y(m) - r.impact_point_y.value) < 2e-3,
             "centre of pressure " << pressure_centre_y(m) << " m, y_R " << r.impact_point_y.value);
  // Something wears where the stream lands; far above it (150 mm) nothing presses.
  WearInputs wi;
  double peak_wear = 0.0, peak_p = 0.0, above = 0.0;
  for (const auto& c : m.cells) {
    peak_wear = std::max(peak_wear, c.archard_rate(wi) + c.finnie_rate(wi));
    peak_p = std::max(peak_p, c.pressure());
    if (c.centroid().y() > r.impact_point_y.value + 0.15) above = std::max(above, c.pressure());
  }
  BOOST_TEST(peak_wear > 0.0);
  BOOST_TEST(above < 0.01 * peak_p);
}

// The default map: the contacts on the generated plate binned on 10 mm cells while the
// World keeps the plate as two triangles. The grid only reads contacts, so the load cell's numbers
// equal those of a run with the coarse map bit for bit; the map resolves the loaded band over
// several rows, and its centre of pressure lies within one cell of the DEM's impact point y_R (the
// map and the load cell sum the same contact forces; what differs is the rolling couples, ~2 mm
// in the test above, and where in its cell a contact counts, at most one cell).
BOOST_AUTO_TEST_CASE(default_map_is_a_10_mm_grid_that_changes_no_force) {
  RunOptions o;
  o.settings = test::tiny_settings();
  BOOST_REQUIRE(o.settings.plate_cells == 0);
  BOOST_REQUIRE(o.settings.map_cell == 0.010);
  const Station st = test::tiny_station();
  const StationResult fine = run_station(st, o);
  o.settings.map_cell = 0.0;
  const StationResult coarse = run_station(st, o);
  BOOST_TEST(fine.normal_force.value == coarse.normal_force.value);
  BOOST_TEST(fine.shear_force.value == coarse.shear_force.value);
  BOOST_TEST(fine.impact_point_y.value == coarse.impact_point_y.value);
  BOOST_REQUIRE_EQUAL(fine.forces.size(), coarse.forces.size());
  for (std::size_t i = 0; i < fine.forces.size(); ++i) BOOST_TEST(fine.forces[i].normal == coarse.forces[i].normal);
  BOOST_REQUIRE(!coarse.maps.empty() && !fine.maps.empty());
  BOOST_TEST(coarse.maps.front().cells.size() == 2u);
  const PlateMap& m = fine.maps.front();
  const int rows = static_cast<int>(std::lround(st.plate.height / 0.010)), cols = static_cast<int>(std::lround(st.plate.width / 0.010));
  BOOST_TEST(m.cells.size() == static_cast<std::size_t>(2 * rows * cols));
  // Same total as the load cell (tolerance 1e-9: the same forces summed in another order).
  BOOST_TEST(m.total_force().x() == fine.normal_force.value, tt::tolerance(1e-9));
  // A band: rows loaded above a tenth of the peak row's pressure.
  const auto prof = pressure_profile(m);
  double peak = 0.0;
  for (const auto& [y, p] : prof) peak = std::max(peak, p);
  int loaded = 0;
  for (const auto& [y, p] : prof) loaded += p > 0.1 * peak;
  const double cell = st.plate.height / rows, cop = pressure_centre_y(m);
  BOOST_TEST_MESSAGE("default map: " << rows << " x " << cols << " cells of " << cell * 1e3 << " mm; " << loaded
                                     << " rows above 10 % of the peak row (" << peak << " Pa); centre of pressure "
                                     << cop * 1e3 << " mm, y_R " << fine.impact_point_y.value * 1e3 << " mm");
  BOOST_TEST(loaded >= 3);
  BOOST_TEST(loaded < rows / 2);
  BOOST_TEST(std::abs(cop - fine.impact_point_y.value) <= cell);
  // The cache stores the grid once and only the cells with a contact; what it gives back is the
  // map, bit for bit.
  const std::string text = to_text(fine);
  const auto back = from_text(text);
  BOOST_REQUIRE(back.has_value());
  BOOST_REQUIRE_EQUAL(back->maps.front().cells.size(), m.cells.size());
  std::size_t differ = 0;
  for (std::size_t i = 0; i < m.cells.size(); ++i) {
    const MapCell &a = m.cells[i], &b = back->maps.front().cells[i];
    differ += !(a.corners == b.corners && a.normal == b.normal && a.area == b.area && a.force == b.force &&
                a.impact_power == b.impact_power && a.sliding_power == b.sliding_power && a.load_slip == b.load_slip &&
                a.finnie_measure == b.finnie_measure && a.impacts == b.impacts && a.block_normal == b.block_normal &&
                a.block_load_slip == b.block_load_slip && a.block_finnie == b.block_finnie);
  }
  BOOST_TEST(differ == 0u);
  BOOST_TEST(to_text(*back) == text);
  BOOST_TEST_MESSAGE("cache entry with the grid map: " << text.size() << " bytes");
  BOOST_TEST(text.size() < 400000u);
}

// Moving the plate away from the pulley lowers where the stream strikes it: in the DEM (peak of the
// pressure profile and centre of pressure) and in the analytical zone, by amounts that agree. The
// tolerance on the DEM's drop against the analytical one (40 % or 15 mm) allows for the layer that
// builds up on the plate and for the 25 mm rows of the map.
BOOST_AUTO_TEST_CASE(impact_zone_moves_down_as_the_plate_moves_away) {
  const double near = 0.30, far = 0.45;
  const StationResult& a = tiny_map_run(near);
  const StationResult& b = tiny_map_run(far);
  Station sa = test::tiny_station(), sb = sa;
  sa.plate_distance = near;
  sb.plate_distance = far;
  const auto za = analytical::impact_zone(analytical::analyse_transfer(sa));
  const auto zb = analytical::impact_zone(analytical::analyse_transfer(sb));
  const double pa = peak_pressure_y(a.maps.front()), pb = peak_pressure_y(b.maps.front());
  const double ca = pressure_centre_y(a.maps.front()), cb = pressure_centre_y(b.maps.front());
  BOOST_TEST_MESSAGE("peak pressure y " << pa * 1e3 << " -> " << pb * 1e3 << " mm; centre of pressure " << ca * 1e3
                                        << " -> " << cb * 1e3 << " mm; analytical centroid " << za.centroid_y * 1e3
                                        << " -> " << zb.centroid_y * 1e3 << " mm (zone " << za.top_y * 1e3 << ".."
                                        << za.bottom_y * 1e3 << " -> " << zb.top_y * 1e3 << ".." << zb.bottom_y * 1e3
                                        << ")");
  BOOST_TEST(zb.top_y < za.top_y);
  BOOST_TEST(zb.bottom_y < za.bottom_y);
  BOOST_TEST(pb < pa);
  BOOST_TEST(cb < ca);
  const double drop = za.centroid_y - zb.centroid_y;
  BOOST_TEST(std::abs((ca - cb) - drop) < std::max(0.4 * drop, 0.015));
  BOOST_TEST(std::abs((pa - pb) - drop) < std::max(0.4 * drop, 0.015));
}

// [dem.wear] is checked like [dem]: unknown keys and bad values name the file, the line and the key.
BOOST_AUTO_TEST_CASE(wear_table_is_checked) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / "chutelab_test_wear_table";
  fs::create_directories(dir);
  const fs::path file = dir / "setup.toml";
  auto write = [&](const std::string& text) { std::ofstream(file) << text; };
  write("name = \"x\"\n[dem]\nplate_cells = 12\n[dem.wear]\narchard_coefficient = 2e-6\nhardness_Pa = 1.5e9\n"
        "finnie_force_ratio = 3\nexposure_h = 100\n");
  const DemTable t = read_dem_table(file.string());
  RunSettings s = resolve(t, {});
  BOOST_TEST(s.plate_cells == 12);
  BOOST_TEST(s.wear.archard.coefficient == 2e-6);
  BOOST_TEST(s.wear.archard.hardness == 1.5e9);
  BOOST_TEST(s.wear.finnie.force_ratio == 3.0);
  BOOST_TEST(s.wear.exposure_hours == 100.0);
  BOOST_TEST(canonical(s).find("finnie_force_ratio") != std::string::npos);
  BOOST_TEST(canonical(resolve(DemTable{}, {})).find("plate_cells") == std::string::npos);
  // The map grid: the default keys nothing (cached runs keep their key), another size keys apart.
  BOOST_TEST(canonical(resolve(DemTable{}, {})).find("map_cell") == std::string::npos);
  write("name = \"x\"\n[dem]\nmap_cell_mm = 5\n");
  const RunSettings fine = resolve(read_dem_table(file.string()), {});
  BOOST_TEST(fine.map_cell == 0.005);
  BOOST_TEST(canonical(fine).find("map_cell = 0.005") != std::string::npos);
  auto fails = [&](const std::string& text, const std::string& field, long line) {
    write(text);
    try {
      read_dem_table(file.string());
    } catch (const InputError& e) {
      BOOST_TEST(std::string(e.what()).find(field) != std::string::npos, e.what());
      BOOST_TEST(std::string(e.what()).find(file.string()) != std::string::npos, e.what());
      BOOST_TEST(std::string(e.what()).find(":" + std::to_string(line)) != std::string::npos, e.what());
      return;
    }
    BOOST_TEST(false, "no error for " << text);
  };
  fails("[dem.wear]\narchard = 1\n", "dem.wear.archard", 2);
  fails("[dem]\nmap_cell_mm = 0.5\n", "dem.map_cell_mm", 2);
  fails("[dem.wear]\nhardness_Pa = -1\n", "dem.wear.hardness_Pa", 2);
  fails("[dem.wear]\n\nfinnie_cutting_fraction = 2\n", "dem.wear.finnie_cutting_fraction", 3);
  fails("[dem]\nplate_cells = 1.5\n", "dem.plate_cells", 2);
  fs::remove_all(dir);
}
