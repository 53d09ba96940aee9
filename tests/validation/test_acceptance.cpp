#include <boost/test/unit_test.hpp>
#include <filesystem>

#include "../cli/cli_runner.h"

using namespace chutelab::test;
namespace fs = std::filesystem;

BOOST_AUTO_TEST_SUITE(acceptance)

const std::string kReference = std::string(CHUTELAB_SOURCE_DIR) + "/datasets/liggghts-rig";

BOOST_AUTO_TEST_CASE(validate_writes_the_five_files_deterministically) {
  const fs::path a = fresh_dir("val-a"), b = fresh_dir("val-b");
  const auto ra = run_chutelab("validate --dataset '" + kReference + "' --out '" + a.string() + "'");
  const auto rb = run_chutelab("validate --dataset '" + kReference + "' --out '" + b.string() + "'");
  BOOST_TEST(ra.exit_code == 0);
  BOOST_TEST(ra.out.find("report: ") != std::string::npos);
  for (const char* f : {"predictions.csv", "errors.csv", "summary.csv", "report.md", "report.html"}) {
    BOOST_TEST_CONTEXT(f) {
      BOOST_TEST(fs::file_size(a / f) > 100u);
      BOOST_TEST(read_file(a / f) == read_file(b / f));  // same inputs, same bytes
    }
  }
  const std::string errors = read_file(a / "errors.csv");
  BOOST_TEST(errors.rfind("condition,model,quantity,measured,uncertainty,predicted,error,relative_error,"
                          "normalised_error", 0) == 0);
  // Korzen's R_n at V2-26: 7.222 kg/s x 2.0 m/s (vertical plate, V_pn = V_d) = 14.444 N vs 14.910.
  BOOST_TEST(errors.find("V2-26,korzen,normal_force_N,14.91,0.068,14.4444,-0.465556") != std::string::npos);
  BOOST_TEST(read_file(a / "summary.csv").rfind(
                 "model,quantity,n,rms_error,rms_normalised_error,max_abs_relative_error,within_tolerance", 0) == 0);
}

BOOST_AUTO_TEST_CASE(tolerances_pass_and_fail_as_written) {
  // Korzen's R_n is within 4 % of the LIGGGHTS rig at every condition (measured: 3.2 % worst);
  // its R_s (Eq 6/7 gives mu_pw R_n) is 3-4 times the DEM's, so a 15 % limit must fail.
  const fs::path dir = fresh_dir("tol");
  write_file(dir / "pass.toml", "[korzen]\nnormal_force_N = { relative = 0.05 }\n");
  write_file(dir / "fail.toml",
             "[korzen]\nnormal_force_N = { relative = 0.05 }\nshear_force_N = { relative = 0.15 }\n");
  const auto pass = run_chutelab("validate --dataset '" + kReference + "' --tolerances '" +
                                 (dir / "pass.toml").string() + "' --out '" + (dir / "p").string() + "'");
  const auto fail = run_chutelab("validate --dataset '" + kReference + "' --tolerances '" +
                                 (dir / "fail.toml").string() + "' --out '" + (dir / "f").string() + "'");
  BOOST_TEST(pass.exit_code == 0);
  BOOST_TEST(pass.out.find("acceptance passed") != std::string::npos);
  BOOST_TEST(fail.exit_code == 1);
  BOOST_TEST(fail.out.find("ACCEPTANCE FAILED") != std::string::npos);
  const std::string errors = read_file(dir / "f" / "errors.csv");
  BOOST_TEST(errors.find("V2-26,korzen,shear_force_N") != std::string::npos);
  BOOST_TEST(errors.find(",fail: |rel|") != std::string::npos);
  BOOST_TEST(read_file(dir / "f" / "summary.csv").find("korzen,shear_force_N,8,") != std::string::npos);
  BOOST_TEST(read_file(dir / "f" / "summary.csv").find(",no\n") != std::string::npos);
  BOOST_TEST(read_file(dir / "p" / "summary.csv").find("korzen,normal_force_N,8,") != std::string::npos);
  // A malformed tolerance file is bad input.
  write_file(dir / "bad.toml", "[korzen]\nnormal_force_N = { relativ = 0.05 }\n");
  const auto bad = run_chutelab("validate --dataset '" + kReference + "' --tolerances '" +
                                (dir / "bad.toml").string() + "' --out '" + (dir / "b").string() + "'");
  BOOST_TEST(bad.exit_code == 2);
  BOOST_TEST(bad.err.find("bad.toml:2: korzen.normal_force_N.relativ") != std::string::npos, bad.err);
}

BOOST_AUTO_TEST_SUITE_END()
