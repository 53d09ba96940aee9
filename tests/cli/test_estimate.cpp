#include <boost/test/unit_test.hpp>
#include <cmath>
#include <string>

#include "cli_runner.h"

using namespace chutelab::test;

BOOST_AUTO_TEST_SUITE(estimate)

BOOST_AUTO_TEST_CASE(table_csv_and_json_for_a_bundled_condition) {
  const auto t = run_chutelab("estimate --condition V2-26");
  BOOST_TEST(t.exit_code == 0);
  BOOST_TEST(t.out.find("stationary (build-up) flow") != std::string::npos);
  BOOST_TEST(t.out.find("Eq 6") != std::string::npos);
  const auto j = run_chutelab("estimate --condition V5-44 --format json");
  BOOST_TEST(j.exit_code == 0);
  BOOST_TEST(j.out.find("\"stationary_flow\": false") != std::string::npos);
  BOOST_TEST(j.out.find("\"korzen\": {\"normal_force_N\"") != std::string::npos);
  BOOST_TEST(j.out.find("\"booth-cema\": {") != std::string::npos);
  BOOST_TEST(j.out.find("\"impact_angle_deg\"") != std::string::npos);
  const auto c = run_chutelab("estimate --belt-speed 3 --mass-flow 30 --plate-distance 400 --format csv");
  BOOST_TEST(c.exit_code == 0);
  BOOST_TEST(c.out.rfind("condition,model,quantity,value\n", 0) == 0);
  BOOST_TEST(c.out.find(",korzen,normal_force_N,") != std::string::npos);
}

BOOST_AUTO_TEST_CASE(flags_override_the_dataset_row) {
  const auto a = run_chutelab("estimate --condition V3-41 --format csv");
  const auto b = run_chutelab("estimate --condition V3-41 --mass-flow 20.5 --format csv");
  BOOST_TEST(a.exit_code == 0);
  BOOST_TEST(b.exit_code == 0);
  BOOST_TEST(a.out != b.out);
  BOOST_TEST(b.out.find("analysis,mass_flow_tph,20.5\n") != std::string::npos);
}

namespace {
// The number after "<key>," in estimate's CSV; NaN when absent.
double csv_value(const std::string& csv, const std::string& key) {
  const auto at = csv.find("," + key + ",");
  return at == std::string::npos ? std::nan("") : std::stod(csv.substr(at + key.size() + 2));
}
}  // namespace

BOOST_AUTO_TEST_CASE(a_new_operating_point_takes_h_b_from_continuity_not_from_the_row) {
  // The LIGGGHTS rig's V3-41 row measured h_b = 34.0 mm at 41 t/h; at 20 t/h that layer is gone.
  const std::string rig = "estimate --dataset '" + std::string(CHUTELAB_SOURCE_DIR) + "/datasets/liggghts-rig' ";
  const auto row = run_chutelab(rig + "--condition V3-41 --format csv");
  const auto flow = run_chutelab(rig + "--condition V3-41 --mass-flow 20 --format csv");
  const auto speed = run_chutelab(rig + "--condition V3-41 --belt-speed 4 --format csv");
  const auto given = run_chutelab(rig + "--condition V3-41 --mass-flow 20 --stream-thickness 30 --format csv");
  const auto no_row = run_chutelab(rig + "--belt-speed 3 --mass-flow 20 --plate-distance 400 --format csv");
  for (const auto* r : {&row, &flow, &speed, &given, &no_row}) BOOST_TEST(r->exit_code == 0, r->err);
  BOOST_TEST(csv_value(row.out, "stream_thickness_mm") == 34.0);
  BOOST_TEST(csv_value(row.out, "stream_thickness_from_continuity") == 0.0);
  const double h20 = csv_value(flow.out, "stream_thickness_mm");
  BOOST_TEST(std::abs(h20 - 34.0) > 1.0, "h_b at 20 t/h: " << h20);
  BOOST_TEST(csv_value(flow.out, "stream_thickness_from_continuity") == 1.0);
  BOOST_TEST(h20 == csv_value(no_row.out, "stream_thickness_mm"));  // the same continuity answer
  BOOST_TEST(std::abs(csv_value(speed.out, "stream_thickness_mm") - 34.0) > 1.0);
  BOOST_TEST(csv_value(speed.out, "stream_thickness_from_continuity") == 1.0);
  BOOST_TEST(csv_value(given.out, "stream_thickness_mm") == 30.0);  // an explicit h_b still wins
  BOOST_TEST(csv_value(given.out, "stream_thickness_from_continuity") == 0.0);
  const auto table = run_chutelab(rig + "--condition V3-41 --mass-flow 20");
  BOOST_TEST(table.out.find("(from continuity)") != std::string::npos, table.out);
}

BOOST_AUTO_TEST_CASE(bad_input_gives_one_line_and_exit_2) {
  const auto dir = fresh_dir("estimate-bad");
  write_file(dir / "bad.toml", "name = \"x\"\n[belt\npulley_diameter_mm = 250\n");
  const char* cases[] = {
      "estimate --condition V2-26 --frobnicate 3",                              // unknown flag
      "estimate --belt-speed -2 --mass-flow 26 --plate-distance 300",            // negative speed
      "estimate --belt-speed 2 --mass-flow 26 --plate-distance 0.001",           // plate behind pulley
      "estimate --belt-speed 2 --mass-flow 26 --plate-distance 3000",            // misses the plate
      "estimate --condition V9-99",                                              // unknown condition
      "estimate --belt-speed 2 --mass-flow 26",                                  // missing input
      "estimate --condition V2-26 --format xml",                                 // bad choice
  };
  for (const char* args : cases) {
    BOOST_TEST_CONTEXT(args) {
      const auto r = run_chutelab(args);
      BOOST_TEST(r.exit_code == 2);
      BOOST_TEST(r.out.empty());
      BOOST_TEST(count_lines(r.err) == 1);
    }
  }
  const auto toml = run_chutelab("estimate --setup '" + (dir / "bad.toml").string() +
                                 "' --belt-speed 2 --mass-flow 26 --plate-distance 300");
  BOOST_TEST(toml.exit_code == 2);
  BOOST_TEST(count_lines(toml.err) == 1);
  BOOST_TEST(toml.err.find("bad.toml:2") != std::string::npos);  // names file and line
  const auto missing = run_chutelab("estimate --condition V2-26 --belt-speed 2 --plate-distance 3000");
  BOOST_TEST(missing.err.find("misses the plate") != std::string::npos);
  BOOST_TEST(missing.err.find("plate_distance_mm:") != std::string::npos, missing.err);
  const auto behind = run_chutelab("estimate --belt-speed 2 --mass-flow 26 --plate-distance 0.001");
  BOOST_TEST(behind.err.find("behind") != std::string::npos);
}

BOOST_AUTO_TEST_SUITE_END()
