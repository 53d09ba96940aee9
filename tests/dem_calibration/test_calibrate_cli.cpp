// `chutelab calibrate` end to end on one slump test, and its bad-input handling (one line, exit 2,
// nothing written).
#define BOOST_TEST_MODULE dem_calibrate_cli
#include <boost/test/unit_test.hpp>

#include <filesystem>

#include "../cli/cli_runner.h"
#include "validation/dataset.h"

using namespace chutelab::test;
namespace fs = std::filesystem;

// One sphere run (quick quality, ~800 grains, ~5-10 s): every file is written, Table 3 has its row,
// and material.toml, spliced into the dataset's setup in place of its [material], reads back with the
// chosen rolling friction and density.
BOOST_AUTO_TEST_CASE(calibrate_writes_table3_and_a_usable_material_block) {
  const fs::path out = fresh_dir("calibrate");
  const RunResult r = run_chutelab("calibrate --shape sphere --rolling 0.15 --density 990 --no-incline --out '" +
                                   out.string() + "'");
  BOOST_TEST_MESSAGE(r.out << r.err);
  BOOST_TEST(r.exit_code == 0);
  for (const char* f : {"calibration.csv", "calibration.md", "calibration.html", "calibration.svg", "material.toml",
                        "incline.csv"})
    BOOST_TEST(fs::exists(out / f), f);
  // The chart is a file of its own beside calibration.md, which links it.
  BOOST_TEST(read_file(out / "calibration.svg").rfind("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<svg xmlns=", 0) == 0);
  BOOST_TEST(read_file(out / "calibration.md").find("](calibration.svg)\n") != std::string::npos);
  BOOST_TEST(read_file(out / "calibration.html").find("calibration.svg") == std::string::npos);
  const std::string csv = read_file(out / "calibration.csv");
  BOOST_TEST(count_lines(csv) == 2);
  BOOST_TEST(csv.find("sphere,sphere d=5.6mm,0.15,990,") != std::string::npos);
  // closest to the dataset's bulk density (the only row), then which dataset and quality
  BOOST_TEST(csv.find(",1,grima2010,quick\n") != std::string::npos);
  BOOST_TEST(read_file(out / "calibration.html").find("<svg") != std::string::npos);
  // The reference study's Table 3 layout: one row per mu_r x rho_s, the shape's bulk density and pile height beside it.
  const std::string md = read_file(out / "calibration.md");
  BOOST_TEST(md.find("| rolling friction mu_r | solid density (kg/m^3) | sphere d=5.6mm: bulk density (kg/m^3) | "
                     "sphere d=5.6mm: pile height (mm) |") != std::string::npos);
  BOOST_TEST(md.find("\n| 0.15 | 990 | **") != std::string::npos);

  const std::string setup = read_file(fs::path(CHUTELAB_SOURCE_DIR) / "datasets/grima2010/setup.toml");
  const std::string head = setup.substr(0, setup.find("[material]"));
  write_file(out / "ds" / "setup.toml", head + read_file(out / "material.toml"));
  const auto s = chutelab::validation::read_setup(out / "ds" / "setup.toml");
  BOOST_TEST(s.material.rolling_friction_particle == 0.15);
  BOOST_TEST(s.material.solid_density == 990.0);
  BOOST_TEST(s.material.friction_particle == 0.3);
}

BOOST_AUTO_TEST_CASE(calibrate_bad_input_is_one_line_and_exit_2) {
  const fs::path out = fresh_dir("calibrate-bad");
  for (const std::string args : {"--rolling 0.1,abc", "--density -5", "--shape cube", "--dataset /nonexistent"}) {
    const RunResult r = run_chutelab("calibrate " + args + " --out '" + (out / "x").string() + "'");
    BOOST_TEST(r.exit_code == 2, args);
    BOOST_TEST(count_lines(r.err) == 1, args << ": " << r.err);
    BOOST_TEST(!fs::exists(out / "x"), args);
  }
}
