// Each model asks only for what it reads: the analytical chain for the rig's geometry, the bulk
// density and the wall friction; the DEM for the contact model's material values, every missing one
// in one message before it runs. estimate takes the common geometry and material as flags.
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <filesystem>
#include <string>

#include "cli_runner.h"

using namespace chutelab::test;
namespace fs = std::filesystem;

namespace {

const fs::path kSource(CHUTELAB_SOURCE_DIR);

// The reference study's rig as the analytical models read it, and nothing else.
const std::string kAnalyticalSetup =
    "[belt]\npulley_diameter_mm = 250\nbelt_thickness_mm = 5\nbelt_width_mm = 300\nloaded_width_mm = 200\n"
    "incline_deg = 0\n[plate]\nwidth_mm = 400\nheight_mm = 500\nangle_deg = 0\n"
    "[material]\nbulk_density_kgm3 = 540\nfriction_plate = 0.27\n";

const std::string kPoint = " --belt-speed 4 --mass-flow 35 --plate-distance 450 --format csv";

std::string q(const fs::path& p) { return "'" + p.string() + "'"; }

// The number after "<model>,<key>," in estimate's CSV; NaN when absent.
double model_value(const std::string& csv, const std::string& model, const std::string& key) {
  const std::string tag = "," + model + "," + key + ",";
  const auto at = csv.find(tag);
  return at == std::string::npos ? std::nan("") : std::stod(csv.substr(at + tag.size()));
}

}  // namespace

BOOST_AUTO_TEST_SUITE(model_inputs)

BOOST_AUTO_TEST_CASE(estimate_reads_the_geometry_the_bulk_density_and_the_wall_friction_only) {
  const fs::path d = fresh_dir("inputs-analytical");
  write_file(d / "setup.toml", kAnalyticalSetup);
  const auto lean = run_chutelab("estimate --setup " + q(d / "setup.toml") + kPoint);
  const auto full = run_chutelab("estimate" + kPoint);  // the bundled rig: the same plus the DEM's values
  BOOST_TEST(lean.exit_code == 0, lean.err);
  BOOST_TEST(lean.err == "");
  BOOST_TEST(full.exit_code == 0, full.err);
  for (const auto& [model, key] : {std::pair{"korzen", "normal_force_N"}, {"korzen", "shear_force_N"},
                                   {"booth-cema", "impact_velocity_mps"}, {"booth-cema", "impact_point_y_mm"}}) {
    BOOST_TEST_CONTEXT(model << " " << key) {
      BOOST_TEST(std::isfinite(model_value(lean.out, model, key)));
      BOOST_TEST(model_value(lean.out, model, key) == model_value(full.out, model, key));
    }
  }
  // Air drag acts on one particle: it needs the particles' size and density, and says so.
  const auto drag = run_chutelab("estimate --setup " + q(d / "setup.toml") + kPoint + " --effect air_drag=0.5");
  BOOST_TEST(drag.exit_code == 2);
  BOOST_TEST(count_lines(drag.err) == 1);
  BOOST_TEST(drag.err.find("material.particle_diameter_mm") != std::string::npos, drag.err);
  // The required keys missing are named together.
  write_file(d / "two-missing.toml", "[belt]\nbelt_thickness_mm = 5\nbelt_width_mm = 300\nloaded_width_mm = 200\n"
                                     "incline_deg = 0\n[plate]\nwidth_mm = 400\nheight_mm = 500\nangle_deg = 0\n"
                                     "[material]\nbulk_density_kgm3 = 540\n");
  const auto two = run_chutelab("estimate --setup " + q(d / "two-missing.toml") + kPoint);
  BOOST_TEST(two.exit_code == 2);
  BOOST_TEST(count_lines(two.err) == 1);
  BOOST_TEST(two.err.find("belt.pulley_diameter_mm, material.friction_plate") != std::string::npos, two.err);
}

BOOST_AUTO_TEST_CASE(the_dem_asks_for_every_missing_key_in_one_message) {
  const fs::path d = fresh_dir("inputs-dem") / "rig";
  fs::create_directories(d);
  write_file(d / "setup.toml", kAnalyticalSetup);
  for (const char* f : {"conditions.csv", "measurements.csv"})
    fs::copy_file(kSource / "datasets/hidden-effect" / f, d / f);
  const char* keys[] = {"material.particle_diameter_mm", "material.solid_density_kgm3", "material.youngs_modulus_Pa",
                        "material.poisson_ratio", "material.friction_particle", "material.friction_belt",
                        "material.rolling_friction_particle", "material.restitution_particle",
                        "material.restitution_plate"};
  const auto sim = run_chutelab("simulate --dataset " + q(d) + " --condition V3-41");
  const auto dem = run_chutelab("validate --dataset " + q(d) + " --models korzen,dem --out " + q(d.parent_path() / "o"));
  for (const auto* r : {&sim, &dem}) {
    BOOST_TEST(r->exit_code == 2);
    BOOST_TEST(count_lines(r->err) == 1, r->err);
    for (const char* k : keys) BOOST_TEST(r->err.find(k) != std::string::npos, k << " in " << r->err);
    BOOST_TEST(r->err.find("setup.toml") != std::string::npos, r->err);
  }
  BOOST_TEST(!fs::exists(d.parent_path() / "o"));
  // The analytical models validate the same dataset.
  const auto ana = run_chutelab("validate --dataset " + q(d) + " --out " + q(d.parent_path() / "a"));
  BOOST_TEST(ana.exit_code == 0, ana.err);
  BOOST_TEST(ana.err == "");
  // A diagnosis cannot try air drag without the particles' size and density, and says so.
  const auto diag = run_chutelab("diagnose --dataset " + q(d) + " --out " + q(d.parent_path() / "g"));
  BOOST_TEST(diag.exit_code == 0, diag.err);
  BOOST_TEST(diag.err.find("air drag cannot be tried on this rig") != std::string::npos, diag.err);
}

BOOST_AUTO_TEST_CASE(estimate_takes_pulley_diameter_belt_width_and_bulk_density_as_flags) {
  const fs::path d = fresh_dir("inputs-flags");
  std::string setup = read_file(kSource / "datasets/grima2010/setup.toml");
  for (const auto& [from, to] : {std::pair<std::string, std::string>{"pulley_diameter_mm = 250.0", "pulley_diameter_mm = 500"},
                                 {"belt_width_mm = 300.0", "belt_width_mm = 600"},
                                 {"bulk_density_kgm3 = 540.0", "bulk_density_kgm3 = 800"}}) {
    const auto at = setup.find(from);
    BOOST_REQUIRE(at != std::string::npos);
    setup.replace(at, from.size(), to);
  }
  write_file(d / "setup.toml", setup);
  const auto flags = run_chutelab("estimate" + kPoint + " --pulley-diameter 500 --belt-width 600 --bulk-density 800");
  const auto file = run_chutelab("estimate --setup " + q(d / "setup.toml") + kPoint);
  const auto plain = run_chutelab("estimate" + kPoint);
  BOOST_TEST(flags.exit_code == 0, flags.err);
  BOOST_TEST(flags.out == file.out);
  BOOST_TEST(flags.out != plain.out);
  const auto bad = run_chutelab("estimate" + kPoint + " --pulley-diameter -5");
  BOOST_TEST(bad.exit_code == 2);
  BOOST_TEST(bad.err.find("--pulley-diameter") != std::string::npos, bad.err);
  const auto narrow = run_chutelab("estimate" + kPoint + " --belt-width 150");
  BOOST_TEST(narrow.exit_code == 2);
  BOOST_TEST(narrow.err.find("--belt-width") != std::string::npos, narrow.err);
  BOOST_TEST(narrow.err.find("loaded width") != std::string::npos, narrow.err);
  const auto swept = run_chutelab("estimate --belt-speed 4 --mass-flow 35 --plate-distance 450 --pulley-diameter 500 "
                                  "--sweep pulley_diameter=300:600:100");
  BOOST_TEST(swept.exit_code == 2);
  BOOST_TEST(swept.err.find("--pulley-diameter") != std::string::npos, swept.err);
}

BOOST_AUTO_TEST_SUITE_END()
