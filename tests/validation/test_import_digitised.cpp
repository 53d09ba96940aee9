// `chutelab import-digitised`: WebPlotDigitizer exports become rows the strict reader accepts, and
// every bad mapping or point is one message (file, line, field), exit 2, nothing written.
#include <boost/test/unit_test.hpp>
#include <filesystem>
#include <sstream>

#include "../cli/cli_runner.h"

using namespace chutelab::test;
namespace fs = std::filesystem;

namespace {

const std::string kSource = CHUTELAB_SOURCE_DIR;
const std::string kExample = kSource + "/datasets/digitised-example";
const std::string kGrima = kSource + "/datasets/grima2010";

std::string q(const fs::path& p) { return "'" + p.string() + "'"; }

RunResult import(const std::string& dataset, const fs::path& mapping, const std::vector<fs::path>& inputs,
                 const fs::path& out) {
  std::string args = "import-digitised --dataset '" + dataset + "' --mapping " + q(mapping) + " --out " + q(out);
  for (const auto& i : inputs) args += " --input " + q(i);
  return run_chutelab(args);
}

// The cell of `column` in the row of trajectory/measurements text that starts with `prefix`.
std::string row_starting(const std::string& text, const std::string& prefix) {
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);)
    if (line.rfind(prefix, 0) == 0) return line;
  return "<no row " + prefix + ">";
}

}  // namespace

BOOST_AUTO_TEST_SUITE(import_digitised)

BOOST_AUTO_TEST_CASE(the_bundled_example_becomes_rows_that_validate) {
  const fs::path dir = fresh_dir("wpd-example");
  const fs::path out = dir / "grima2010-digitised";
  const auto r = import(kGrima, kExample + "/mapping.toml",
                        {kExample + "/fig-a-stream-limits.csv", kExample + "/fig-b-forces.json"}, out);
  BOOST_TEST_REQUIRE(r.exit_code == 0, r.err);
  BOOST_TEST(r.out.find("8 measurements, 10 trajectory points imported") != std::string::npos, r.out);

  // Inches to mm (25.4 exactly), the digitising uncertainty 0.02 in = 0.508 mm; the CSV's first
  // point of each limit.
  const std::string traj = read_file(out / "trajectory.csv");
  BOOST_TEST(traj.rfind("condition,boundary,x_mm,y_mm,uncertainty_mm\n", 0) == 0);
  BOOST_TEST(row_starting(traj, "V3-41,upper,102.108,") == "V3-41,upper,102.108,152.908,0.508");
  // Round-trip precision: each number is the double the conversion gave, which reads back as itself
  // (5.03 in x 0.0254 m/in is not the double nearest 0.127762 m).
  BOOST_TEST(row_starting(traj, "V3-41,lower,100.838,") == "V3-41,lower,100.838,127.76200000000001,0.508");
  BOOST_TEST(count_lines(traj) == 1 + 10);
  // Each force point is the high-flow condition at its belt speed. R_n's uncertainty is 2 px
  // through the project's y calibration (70 N over 420 px), R_s's 0.3 N as stated.
  const std::string meas = read_file(out / "measurements.csv");
  BOOST_TEST(row_starting(meas, "V2-41,normal_force_N") == "V2-41,normal_force_N,23.3,0.3333333333333333");
  BOOST_TEST(row_starting(meas, "V5-44,normal_force_N") == "V5-44,normal_force_N,60.5,0.3333333333333333");
  BOOST_TEST(row_starting(meas, "V4-41,shear_force_N") == "V4-41,shear_force_N,3.3,0.3");
  BOOST_TEST(count_lines(meas) == 1 + 8);
  // The rest of the dataset comes along unchanged; the README says where the rows came from.
  BOOST_TEST(read_file(out / "conditions.csv") == read_file(kGrima + "/conditions.csv"));
  BOOST_TEST(read_file(out / "setup.toml") == read_file(kGrima + "/setup.toml"));
  BOOST_TEST(read_file(out / "README.md").find("## Digitised data") != std::string::npos);

  // The rows validate: the strict reader takes them and the models are compared with them.
  const auto v = run_chutelab("validate --dataset " + q(out) + " --out " + q(dir / "val"));
  BOOST_TEST_REQUIRE(v.exit_code == 0, v.err);
  const std::string errors = read_file(dir / "val" / "errors.csv");
  BOOST_TEST(errors.find("V3-41,booth-cema,trajectory_upper_y_mm,152.908,0.508,") != std::string::npos);
  BOOST_TEST(errors.find("V5-44,korzen,normal_force_N,60.5,0.3333333333333333,") != std::string::npos);
}

BOOST_AUTO_TEST_CASE(csv_exports_with_and_without_headers) {
  const fs::path dir = fresh_dir("wpd-csv");
  // A single dataset's export: bare x,y rows, named after the file; and one with an X,Y label row.
  write_file(dir / "upper.csv", "100,153\n200,137.5\n");
  write_file(dir / "lower.csv", "x,y\n0.1,0.128\n0.2,0.110\n");
  // Two datasets, the name over both columns, the shorter one padded with empty cells.
  write_file(dir / "both.csv", "centre,centre,lower2,lower2\nX,Y,X,Y\n100,140,100,127\n150,133,,\n");
  write_file(dir / "map.toml",
             "[[curve]]\nname = \"upper\"\ncondition = \"V3-41\"\nboundary = \"upper\"\nx_unit = \"mm\"\n"
             "y_unit = \"mm\"\nuncertainty = 1\n"
             "[[curve]]\nname = \"lower\"\ncondition = \"V3-41\"\nboundary = \"lower\"\nx_unit = \"m\"\n"
             "y_unit = \"m\"\nuncertainty = 0\n"
             "[[curve]]\nname = \"centre\"\ncondition = \"V3-41\"\nboundary = \"centre\"\nx_unit = \"mm\"\n"
             "y_unit = \"mm\"\nuncertainty = 1\n");
  const auto r = import(kGrima, dir / "map.toml", {dir / "upper.csv", dir / "lower.csv", dir / "both.csv"}, dir / "out");
  BOOST_TEST_REQUIRE(r.exit_code == 0, r.err);
  const std::string traj = read_file(dir / "out" / "trajectory.csv");
  BOOST_TEST(traj.find("V3-41,upper,200,137.5,1\n") != std::string::npos, traj);
  BOOST_TEST(traj.find("V3-41,lower,100,128,\n") != std::string::npos, traj);  // 0 = unknown: empty
  BOOST_TEST(traj.find("V3-41,centre,150,133,1\n") != std::string::npos, traj);
  BOOST_TEST(count_lines(traj) == 1 + 2 + 2 + 2);
  // The curve in the inputs that the mapping does not use is named, not imported.
  BOOST_TEST(r.err.find("warning: curve 'lower2' is not in the mapping") != std::string::npos, r.err);
  // No measurements were imported, so the new dataset has none (grima2010 has none either).
  BOOST_TEST(!fs::exists(dir / "out" / "measurements.csv"));
}

BOOST_AUTO_TEST_CASE(pixels_become_y_units_through_the_calibration_also_on_a_log_axis) {
  // y axis: 1 N at py = 400, 100 N at py = 0, logarithmic: 2 decades over 400 px. At y = 10 N one
  // pixel is 10 ln(10) 0.005 N, so 2 px are 0.230259 N; 0.1 N stated adds in quadrature.
  const fs::path dir = fresh_dir("wpd-log");
  write_file(dir / "log.json",
             "{\"axesColl\": [{\"name\": \"XY\", \"type\": \"XYAxes\", \"isLogY\": true, \"calibrationPoints\": [\n"
             "  {\"px\": 0, \"py\": 400, \"dx\": \"1\", \"dy\": \"1\"}, {\"px\": 500, \"py\": 400, \"dx\": \"6\", \"dy\": \"1\"},\n"
             "  {\"px\": 0, \"py\": 400, \"dx\": \"1\", \"dy\": \"1\"}, {\"px\": 0, \"py\": 0, \"dx\": \"1\", \"dy\": \"100\"}]}],\n"
             " \"datasetColl\": [{\"name\": \"R_s\", \"axesName\": \"XY\", \"data\": [{\"value\": [3.0, 10.0]}]},\n"
             "                   {\"name\": \"R_n\", \"axesName\": \"XY\", \"data\": [{\"value\": [3.0, 10.0]}]}]}\n");
  write_file(dir / "map.toml",
             "[defaults]\nuncertainty = 5\nx_unit = \"m/s\"\ny_unit = \"N\"\n"
             "[[curve]]\nname = \"R_s\"\nquantity = \"shear_force_N\"\ncondition = \"V3-41\"\nuncertainty_px = 2\n"
             "[[curve]]\nname = \"R_n\"\nquantity = \"normal_force_N\"\ncondition = \"V3-41\"\nuncertainty_px = 2\n"
             "uncertainty = 0.1\n");
  const auto r = import(kGrima, dir / "map.toml", {dir / "log.json"}, dir / "out");
  BOOST_TEST_REQUIRE(r.exit_code == 0, r.err);
  const std::string meas = read_file(dir / "out" / "measurements.csv");
  // The curve's own uncertainty_px replaces the defaults' 5 N.
  // 10 N x ln(10) x (1/200 decades per px) x 2 px = 0.2302585 N; with 0.1 N in quadrature 0.2510358 N.
  BOOST_TEST(row_starting(meas, "V3-41,shear_force_N") == "V3-41,shear_force_N,10,0.2302585092994046");
  BOOST_TEST(row_starting(meas, "V3-41,normal_force_N") == "V3-41,normal_force_N,10,0.25103581637842837");
}

BOOST_AUTO_TEST_CASE(bad_mappings_and_points_are_one_message_and_nothing_written) {
  const fs::path dir = fresh_dir("wpd-bad");
  const std::string curve_a = "[[curve]]\nname = \"V3-41 upper\"\nboundary = \"upper\"\n";  // lines 1-3
  write_file(dir / "image-axes.json",
             "{\"axesColl\": [{\"name\": \"Image\", \"type\": \"ImageAxes\"}],\n"
             " \"datasetColl\": [{\"name\": \"R_n\",\n"
             "   \"axesName\": \"Image\", \"data\": [{\"value\": [120, 300]}]}]}\n");
  write_file(dir / "half.csv", "a,,b,\n1,2,3,4\n5,6,7,\n");
  write_file(dir / "speeds.json",
             "{\"axesColl\": [{\"name\": \"XY\", \"type\": \"XYAxes\"}],\n"
             " \"datasetColl\": [{\"name\": \"R_n\", \"axesName\": \"XY\", \"data\": [\n"
             "   {\"value\": [2.0, 23.0]},\n"
             "   {\"value\": [3.0, 35.0]}]}]}\n");
  const std::string rn = "[[curve]]\nname = \"R_n\"\nquantity = \"normal_force_N\"\nx_unit = \"m/s\"\ny_unit = \"N\"\n"
                         "uncertainty = 0.3\ncondition_by = \"belt_speed_mps\"\n";  // lines 1-7
  struct Case {
    const char* label;
    std::string mapping;
    std::vector<fs::path> inputs;
    std::string expect;
    std::string dataset = kGrima;
  };
  const fs::path fig_a = kExample + "/fig-a-stream-limits.csv";
  const std::vector<Case> cases = {
      {"unknown condition", curve_a + "condition = \"V9-99\"\nx_unit = \"in\"\ny_unit = \"in\"\nuncertainty = 0.02\n",
       {fig_a}, "map.toml:4: curve[0].condition: condition 'V9-99' is not in conditions.csv"},
      {"unit of another dimension",
       curve_a + "condition = \"V3-41\"\nx_unit = \"N\"\ny_unit = \"in\"\nuncertainty = 0.02\n", {fig_a},
       "map.toml:5: curve[0].x_unit: 'N' is not a length"},
      {"unknown unit", curve_a + "condition = \"V3-41\"\nx_unit = \"in\"\ny_unit = \"furlong\"\nuncertainty = 0.02\n",
       {fig_a}, "map.toml:6: curve[0].y_unit: unknown unit 'furlong'"},
      {"no digitising uncertainty", curve_a + "condition = \"V3-41\"\nx_unit = \"in\"\ny_unit = \"in\"\n", {fig_a},
       "curve[0].uncertainty: is required"},
      {"pixels without a calibration",
       curve_a + "condition = \"V3-41\"\nx_unit = \"in\"\ny_unit = \"in\"\nuncertainty_px = 2\n", {fig_a},
       "map.toml:7: curve[0].uncertainty_px: curve 'V3-41 upper' has no pixel calibration"},
      {"unknown key", curve_a + "condition = \"V3-41\"\nx_unit = \"in\"\ny_unit = \"in\"\nuncertainty = 0.02\nsmooth = true\n",
       {fig_a}, "map.toml:8: curve[0].smooth: unknown key"},
      {"curve not in the inputs", "[[curve]]\nname = \"V3-41 centre\"\nboundary = \"centre\"\n", {fig_a},
       "map.toml:2: curve[0].name: no curve named 'V3-41 centre' in the inputs"},
      {"uncalibrated axes", rn, {dir / "image-axes.json"},
       "image-axes.json:3: datasetColl[0].axesName: dataset 'R_n' is on ImageAxes axes"},
      {"a point without y", "", {dir / "half.csv"}, "half.csv:3: b.y: a point needs both x and y"},
      {"a speed two conditions share", rn, {dir / "speeds.json"},
       "speeds.json:3: datasetColl[0].data[0].value: x = 2 m/s matches V2-26 and V2-41 by belt_speed_mps"},
      {"a row the dataset already has", rn + "conditions = [\"V2-41\", \"V3-41\"]\n", {dir / "speeds.json"},
       "speeds.json:3: datasetColl[0].data[0].value: normal_force_N of condition 'V2-41' is already in the dataset",
       kSource + "/datasets/liggghts-rig"},
  };
  int k = 0;
  for (const auto& c : cases) {
    BOOST_TEST_CONTEXT(c.label) {
      const fs::path out = dir / ("out" + std::to_string(k++));
      write_file(dir / "map.toml", c.mapping.empty() ? curve_a : c.mapping);
      const auto r = import(c.dataset, dir / "map.toml", c.inputs, out);
      BOOST_TEST(r.exit_code == 2);
      BOOST_TEST(r.err.find(c.expect) != std::string::npos, r.err);
      BOOST_TEST(count_lines(r.err) == 1, r.err);
      BOOST_TEST(!fs::exists(out));
    }
  }
  // Nor inside the source it copies.
  fs::copy(kGrima, dir / "src", fs::copy_options::recursive);
  const auto inside = import((dir / "src").string(), kExample + "/mapping.toml",
                             {fig_a, kExample + "/fig-b-forces.json"}, dir / "src" / "new");
  BOOST_TEST(inside.exit_code == 2);
  BOOST_TEST(inside.err.find("lies inside the source dataset") != std::string::npos, inside.err);
  BOOST_TEST(!fs::exists(dir / "src" / "new"));
  // An existing dataset folder is never written over.
  fs::create_directories(dir / "taken");
  write_file(dir / "taken" / "keep.txt", "mine\n");
  const auto r = import(kGrima, kExample + "/mapping.toml",
                        {fig_a, kExample + "/fig-b-forces.json"}, dir / "taken");
  BOOST_TEST(r.exit_code == 2);
  BOOST_TEST(r.err.find("--out: exists and is not an empty folder") != std::string::npos, r.err);
  BOOST_TEST(read_file(dir / "taken" / "keep.txt") == "mine\n");
  BOOST_TEST(!fs::exists(dir / "taken" / "measurements.csv"));
}

BOOST_AUTO_TEST_SUITE_END()
