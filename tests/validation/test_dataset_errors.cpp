#define BOOST_TEST_MODULE validation
#include <boost/test/unit_test.hpp>
#include <filesystem>
#include <fstream>
#include <string>

#include "../cli/cli_runner.h"

using namespace chutelab::test;
namespace fs = std::filesystem;

namespace {

// A copy of the LIGGGHTS reference dataset with one file replaced or edited.
fs::path dataset_with(const std::string& name, const std::string& file, const std::string& text) {
  const fs::path d = fresh_dir(name);
  for (const char* f : {"setup.toml", "conditions.csv", "measurements.csv", "trajectory.csv"})
    fs::copy_file(fs::path(CHUTELAB_SOURCE_DIR) / "datasets/liggghts-rig" / f, d / f);
  if (!file.empty()) write_file(d / file, text);
  return d;
}

std::string replace_line(const std::string& file, int line, const std::string& with) {
  std::ifstream in(fs::path(CHUTELAB_SOURCE_DIR) / "datasets/liggghts-rig" / file);
  std::string out, l;
  for (int n = 1; std::getline(in, l); ++n) out += (n == line ? with : l) + "\n";
  return out;
}

struct BadCase {
  const char* label;
  const char* file;
  std::string text;
  std::string expect_in_message;  // file:line and field
};

}  // namespace

BOOST_AUTO_TEST_SUITE(dataset_errors)

BOOST_AUTO_TEST_CASE(each_error_class_names_file_line_field_and_writes_nothing) {
  const std::vector<BadCase> cases = {
      {"missing column", "measurements.csv",
       replace_line("measurements.csv", 1, "condition,quantity,uncertainty"), "measurements.csv:1: value"},
      {"unknown quantity", "measurements.csv",
       replace_line("measurements.csv", 3, "V2-26,normal_force_kN,14.9,0.07"), "measurements.csv:3: quantity"},
      {"non-number", "measurements.csv",
       replace_line("measurements.csv", 4, "V2-26,shear_force_N,abc,0.02"), "measurements.csv:4: value"},
      {"NaN", "measurements.csv",
       replace_line("measurements.csv", 5, "V2-26,resultant_force_N,nan,0.07"), "measurements.csv:5: value"},
      {"negative speed", "conditions.csv",
       replace_line("conditions.csv", 3, "V2-41,-2.0,41.0,300.0,250.0,48.6"), "conditions.csv:3: belt_speed_mps"},
      {"negative flow", "conditions.csv",
       replace_line("conditions.csv", 4, "V3-28,3.0,-28.0,400.0,250.0,25.8"), "conditions.csv:4: mass_flow_tph"},
      {"negative measured speed", "measurements.csv",
       replace_line("measurements.csv", 6, "V2-26,impact_velocity_mps,-1.9,0.01"), "measurements.csv:6: value"},
      {"unknown condition", "measurements.csv",
       replace_line("measurements.csv", 7, "V9-99,exit_velocity_mps,1.7,0.003"), "measurements.csv:7: condition"},
      {"duplicate measurement", "measurements.csv",
       replace_line("measurements.csv", 3, "V2-26,normal_force_N,14.910,0.068"), "measurements.csv:3: quantity"},
      {"duplicate condition", "conditions.csv",
       replace_line("conditions.csv", 3, "V2-26,2.0,41.0,300.0,250.0,48.6"), "conditions.csv:3: condition"},
      {"trajectory non-number", "trajectory.csv",
       replace_line("trajectory.csv", 2, "V2-26,upper,100.0,inf,1.0"), "trajectory.csv:2: y_mm"},
      {"unknown boundary", "trajectory.csv",
       replace_line("trajectory.csv", 3, "V2-26,middle,150.0,133.1,1.0"), "trajectory.csv:3: boundary"},
      {"plate map: missing column", "plate_map.csv", "condition,y_mm,quantity,value\nV2-26,50,plate_pressure_Pa,100\n",
       "plate_map.csv:1: z_mm"},
      {"plate map: unknown quantity", "plate_map.csv",
       "condition,y_mm,z_mm,quantity,value,uncertainty\nV2-26,50,0,plate_pressure_Pa,100,5\nV2-26,50,0,pressure_kPa,1,\n",
       "plate_map.csv:3: quantity"},
      {"plate map: non-number", "plate_map.csv",
       "condition,y_mm,z_mm,quantity,value,uncertainty\nV2-26,fifty,0,plate_pressure_Pa,100,5\n", "plate_map.csv:2: y_mm"},
      {"plate map: negative wear", "plate_map.csv",
       "condition,y_mm,z_mm,quantity,value,uncertainty\nV2-26,50,0,wear_depth_um,-3,1\n", "plate_map.csv:2: value"},
      {"plate map: unknown condition", "plate_map.csv",
       "condition,y_mm,z_mm,quantity,value,uncertainty\nV9-99,50,0,plate_pressure_Pa,100,5\n", "plate_map.csv:2: condition"},
      {"plate map: duplicate point", "plate_map.csv",
       "condition,y_mm,z_mm,quantity,value,uncertainty\nV2-26,50,0,plate_pressure_Pa,100,5\nV2-26,50,0,plate_pressure_Pa,90,5\n",
       "plate_map.csv:3: y_mm"},
      // The plate of these rows spans y = -250 ... 250 mm (top 250 mm, 500 mm high) and z = -200 ... 200 mm.
      {"plate map: point above the plate", "plate_map.csv",
       "condition,y_mm,z_mm,quantity,value,uncertainty\nV2-26,250,0,plate_pressure_Pa,100,5\nV2-26,251,0,plate_pressure_Pa,0,5\n",
       "plate_map.csv:3: y_mm"},
      {"plate map: point beside the plate", "plate_map.csv",
       "condition,y_mm,z_mm,quantity,value,uncertainty\nV2-26,50,-200,plate_pressure_Pa,100,5\nV2-26,50,201,plate_pressure_Pa,0,5\n",
       "plate_map.csv:3: z_mm"},
      {"malformed TOML", "setup.toml", "name = \"x\"\n[belt\npulley_diameter_mm = 250\n", "setup.toml:2"},
      {"missing TOML key", "setup.toml",
       "name = \"x\"\n[belt]\npulley_diameter_mm = 250.0\n", "setup.toml: belt.belt_thickness_mm"},
      {"impossible geometry", "setup.toml", replace_line("setup.toml", 7, "loaded_width_mm = 400.0"),
       "setup.toml: loaded_width_mm"},
      {"value outside its physical range", "setup.toml",
       replace_line("setup.toml", 24, "restitution_plate = 1.66"), "setup.toml:24: material.restitution_plate"},
  };
  int n = 0;
  for (const auto& c : cases) {
    BOOST_TEST_CONTEXT(c.label) {
      const fs::path d = dataset_with("bad" + std::to_string(n++), c.file, c.text);
      const fs::path out = d / "out";
      const auto r = run_chutelab("validate --dataset '" + d.string() + "' --out '" + out.string() + "'");
      BOOST_TEST(r.exit_code == 2);
      BOOST_TEST(count_lines(r.err) == 1);
      BOOST_TEST(r.err.find(c.expect_in_message) != std::string::npos, "message: " << r.err);
      BOOST_TEST(!fs::exists(out));  // nothing written, not even the folder
    }
  }
}

BOOST_AUTO_TEST_CASE(plate_that_the_stream_misses_is_reported_at_its_condition_line) {
  // A plate 1.5 m away at 2 m/s: the stream falls below it. Found after parsing, still located, and
  // blamed on the distance, with how near the plate must come (the centre line falls ~0.4 m to the
  // plate's foot in ~0.28 s, ~0.57 m at 2 m/s).
  const fs::path d = dataset_with("miss", "conditions.csv",
                                  replace_line("conditions.csv", 2, "V2-26,2.0,26.0,1500.0,250.0,34.2"));
  const auto r = run_chutelab("validate --dataset '" + d.string() + "' --out '" + (d / "out").string() + "'");
  BOOST_TEST(r.exit_code == 2);
  BOOST_TEST(count_lines(r.err) == 1);
  BOOST_TEST(r.err.find("conditions.csv:2: plate_distance_mm") != std::string::npos, r.err);
  BOOST_TEST(r.err.find("misses the plate") != std::string::npos);
  BOOST_TEST(r.err.find("below the plate's foot") != std::string::npos, r.err);
  const auto at = r.err.find("bring it within x = ");
  BOOST_TEST_REQUIRE(at != std::string::npos, r.err);
  const double reach = std::stod(r.err.substr(at + 20));
  BOOST_TEST(reach > 500.0);
  BOOST_TEST(reach < 650.0);
  BOOST_TEST(!fs::exists(d / "out"));

  // The suggested distance is one at which the stream does meet the plate.
  const fs::path ok = dataset_with("miss-fixed", "conditions.csv",
                                   replace_line("conditions.csv", 2,
                                                "V2-26,2.0,26.0," + std::to_string(reach) + ",250.0,34.2"));
  const auto fixed = run_chutelab("validate --dataset '" + ok.string() + "' --out '" + (ok / "out").string() + "'");
  BOOST_TEST(fixed.exit_code == 0, fixed.err);
}

BOOST_AUTO_TEST_CASE(plate_below_or_above_the_stream_is_blamed_on_its_height) {
  // At 300 mm the stream passes y ~ 40 mm: a plate topped at -200 mm is under it, one whose foot is
  // at +1000 mm over it, and no distance helps the second.
  const struct {
    const char* row;
    const char* expect;
  } cases[] = {{"V2-26,2.0,26.0,300.0,-200.0,34.2", "above the plate's top edge"},
               {"V2-26,2.0,26.0,300.0,1500.0,34.2", "no plate distance reaches the stream"}};
  int n = 0;
  for (const auto& c : cases) {
    BOOST_TEST_CONTEXT(c.row) {
      const fs::path d = dataset_with("miss-height" + std::to_string(n++), "conditions.csv",
                                      replace_line("conditions.csv", 2, c.row));
      const auto r = run_chutelab("validate --dataset '" + d.string() + "' --out '" + (d / "out").string() + "'");
      BOOST_TEST(r.exit_code == 2);
      BOOST_TEST(r.err.find("conditions.csv:2: plate_top_mm") != std::string::npos, r.err);
      BOOST_TEST(r.err.find(c.expect) != std::string::npos, r.err);
      BOOST_TEST(!fs::exists(d / "out"));
    }
  }
}

// Measured plate pressures (a pressure film) are compared like every measurement: korzen predicts
// its mean pressure inside the analytical impact zone and none outside; errors.csv carries the point.
BOOST_AUTO_TEST_CASE(plate_map_points_are_compared) {
  const fs::path d = dataset_with("platemap", "plate_map.csv",
                                  "condition,y_mm,z_mm,quantity,value,uncertainty\n"
                                  "V3-41,60,0,plate_pressure_Pa,4000,400\n"
                                  "V3-41,200,0,plate_pressure_Pa,10,5\n"
                                  "V3-41,60,0,wear_depth_um,3,1\n");
  const fs::path out = d / "out";
  const auto r = run_chutelab("validate --dataset '" + d.string() + "' --models korzen --out '" + out.string() + "'");
  BOOST_TEST(r.exit_code == 0, r.err);
  std::ifstream f(out / "errors.csv");
  std::string line, inside, outside;
  bool wear = false;
  while (std::getline(f, line)) {
    if (line.rfind("V3-41,korzen,plate_pressure_Pa,4000", 0) == 0) inside = line;
    if (line.rfind("V3-41,korzen,plate_pressure_Pa,10", 0) == 0) outside = line;
    wear = wear || line.find("wear_depth_um") != std::string::npos;
  }
  // Zone of V3-41 (estimate): y = 76.8 ... 42.8 mm, mean pressure 5024.5 Pa.
  BOOST_TEST(inside.find(",5024.5") != std::string::npos, inside);
  BOOST_TEST(inside.find(",60,0") != std::string::npos, inside);
  BOOST_TEST(outside.find(",10,5,0,") != std::string::npos, outside);
  BOOST_TEST(!wear);  // korzen does not predict wear: no row
}

BOOST_AUTO_TEST_SUITE_END()
