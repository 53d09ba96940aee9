// Another code's results as a model (--models external:NAME=DIR): the bundled example validates,
// reports and diagnoses under its own name; malformed folders are bad input (exit 2, one line
// naming file, line and field) and nothing is written.
#include <boost/test/unit_test.hpp>
#include <fmt/format.h>

#include <filesystem>

#include "../cli/cli_runner.h"

using namespace chutelab::test;
namespace fs = std::filesystem;

namespace {

const fs::path kSource(CHUTELAB_SOURCE_DIR);
const std::string kRig = (kSource / "datasets" / "liggghts-rig").string();
const fs::path kExample = kSource / "datasets" / "liggghts-rig-external-quick";

// A copy of the example with one file's line replaced (1-based; 0 = the file as it is).
fs::path broken(const std::string& tag, const std::string& file, int line, const std::string& text) {
  const fs::path dir = fresh_dir("ext-" + tag);
  for (const char* f : {"predictions.csv", "trajectory.csv", "README.md"}) fs::copy_file(kExample / f, dir / f);
  if (line > 0) {
    std::string all = read_file(dir / file), out;
    int n = 0;
    std::size_t at = 0;
    while (at < all.size()) {
      const std::size_t nl = all.find('\n', at);
      const std::string l = all.substr(at, nl - at);
      out += (++n == line ? text : l) + "\n";
      at = nl == std::string::npos ? all.size() : nl + 1;
    }
    write_file(dir / file, out);
  }
  return dir;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(external_results)

BOOST_AUTO_TEST_CASE(example_validates_reports_and_diagnoses_under_its_name) {
  const fs::path out = fresh_dir("ext-validate");
  const auto v = run_chutelab("validate --dataset " + kRig + " --models korzen,external:dem-quick=" + kExample.string() +
                              " --out " + out.string());
  BOOST_TEST_MESSAGE(v.out << v.err);
  BOOST_REQUIRE(v.exit_code == 0);
  BOOST_TEST(v.out.find("RMS E/u_val korzen ") != std::string::npos, v.out);
  BOOST_TEST(v.out.find(", dem-quick ") != std::string::npos, v.out);
  // Its numbers come through unchanged: the first row of its predictions.csv.
  BOOST_TEST(read_file(out / "predictions.csv").find("V2-26,dem-quick,normal_force_N,14.9246,0.375768,") != std::string::npos);
  BOOST_TEST(read_file(out / "summary.csv").find("dem-quick,trajectory_upper_y_mm,") != std::string::npos);
  BOOST_TEST(read_file(out / "errors.csv").find(",dem-quick,impact_point_y_mm,") != std::string::npos);
  const std::string html = read_file(out / "report.html");
  BOOST_TEST(html.find("dem-quick") != std::string::npos);

  const fs::path dg = fresh_dir("ext-diagnose");
  const auto d = run_chutelab("diagnose --dataset " + kRig + " --models external:dem-quick=" + kExample.string() +
                              " --out " + dg.string());
  BOOST_REQUIRE(d.exit_code == 0);
  const std::string md = read_file(dg / "diagnosis.md");
  // An expensive baseline whose signatures come from the analytical models, and said so.
  BOOST_TEST(md.find("dem-quick is another code's exported results") != std::string::npos);
  BOOST_TEST(md.find("Confirmed by running") == std::string::npos);
}

BOOST_AUTO_TEST_CASE(malformed_folders_are_bad_input_and_write_nothing) {
  struct Case {
    std::string tag, file;
    int line;
    std::string text, expect_file, expect_field;
    int expect_line;
  };
  const std::vector<Case> cases = {
      {"quantity", "predictions.csv", 3, "V2-26,shear_force_kN,2.4,0.1", "predictions.csv", "quantity", 3},
      {"value", "predictions.csv", 4, "V2-26,resultant_force_N,lots,0.1", "predictions.csv", "value", 4},
      {"negative-u", "predictions.csv", 2, "V2-26,normal_force_N,14.9,-1", "predictions.csv", "uncertainty", 2},
      {"duplicate", "predictions.csv", 3, "V2-26,normal_force_N,14.9,0.3", "predictions.csv", "quantity", 3},
      {"condition", "predictions.csv", 5, "V9-99,impact_velocity_mps,1.8,0.05", "predictions.csv", "condition", 5},
      {"boundary", "trajectory.csv", 2, "V2-26,middle,10.0,160.27,0.40", "trajectory.csv", "boundary", 2},
      {"x", "trajectory.csv", 3, "V2-26,upper,,160.14,0.35", "trajectory.csv", "x_mm", 3},
      {"header", "predictions.csv", 1, "condition,quantity,amount,uncertainty", "predictions.csv", "value", 0},
  };
  for (const auto& c : cases) {
    BOOST_TEST_CONTEXT(c.tag) {
      const fs::path dir = broken(c.tag, c.file, c.line, c.text);
      const fs::path out = fresh_dir("ext-out-" + c.tag) / "out";
      const auto r = run_chutelab("validate --dataset " + kRig + " --models korzen,external:x=" + dir.string() +
                                  " --out " + out.string());
      BOOST_TEST(r.exit_code == 2);
      BOOST_TEST(count_lines(r.err) == 1, r.err);
      BOOST_TEST(r.err.find((dir / c.expect_file).string()) != std::string::npos, r.err);
      if (c.expect_line > 0) BOOST_TEST(r.err.find(fmt::format(":{}", c.expect_line)) != std::string::npos, r.err);
      BOOST_TEST(r.err.find(c.expect_field) != std::string::npos, r.err);
      BOOST_TEST(!fs::exists(out));
    }
  }
  // No README (no provenance), no predictions, a bad name or spec, a built-in's name.
  const fs::path no_readme = broken("no-readme", "", 0, "");
  fs::remove(no_readme / "README.md");
  const fs::path no_pred = broken("no-pred", "", 0, "");
  fs::remove(no_pred / "predictions.csv");
  for (const std::string& spec : {"external:x=" + no_readme.string(), "external:x=" + no_pred.string(),
                                  std::string("external:x=/nonexistent/folder"), "external:a,b=" + kExample.string(),
                                  "external:dem=" + kExample.string(), "external:" + kExample.string()}) {
    const fs::path out = fresh_dir("ext-out-spec") / "out";
    const auto r = run_chutelab("validate --dataset " + kRig + " --models " + spec + " --out " + out.string());
    BOOST_TEST(r.exit_code == 2, spec);
    BOOST_TEST(count_lines(r.err) == 1, spec << ": " << r.err);
    BOOST_TEST(!fs::exists(out), spec);
  }
}

BOOST_AUTO_TEST_SUITE_END()
