// The DEM-baseline diagnosis on data made by another code. datasets/liggghts-flowbias is the LIGGGHTS rig with one hidden effect; its
// HOW-MADE.md gives the truth, mass_flow_bias = -0.12. datasets/liggghts-rig is the same rig without
// any effect. Both are diagnosed exactly as a user would (`diagnose --models dem --dem-quality
// standard --signature-quality quick`) from DEM runs recorded in tests/peer/dem-cache by
// bench/peer_diagnosis.sh: --dem-cache-only makes a missing run an error (exit 2 naming it) instead
// of an hour of computing, so a change of the station model (kStationModelVersion) or of the
// datasets fails here until the runs are recorded again.
#define BOOST_TEST_MODULE peer_diagnosis
#include <boost/test/unit_test.hpp>
#include <cmath>
#include <filesystem>
#include <sstream>

#include "../cli/cli_runner.h"

using namespace chutelab;
namespace fs = std::filesystem;

namespace {

const fs::path kSource = CHUTELAB_SOURCE_DIR;

struct Row {
  int rank = 0;
  std::string effect, significant;
  double estimate = 0, uncertainty = 0, explained = 0;
};

// diagnosis.csv rows of single effects (rank, effect, parameter, estimate, uncertainty, chi2_before,
// chi2_after, delta_bic, explained_fraction, significant, ...).
std::vector<Row> singles(const std::string& csv) {
  std::vector<Row> out;
  std::istringstream in(csv);
  std::string line;
  std::getline(in, line);
  while (std::getline(in, line)) {
    std::vector<std::string> f;
    std::stringstream ss(line);
    for (std::string c; std::getline(ss, c, ',');) f.push_back(c);
    if (f.size() < 10 || f[0] == "pair") continue;
    out.push_back({std::stoi(f[0]), f[1], f[9], std::stod(f[3]), f[4] == "inf" ? INFINITY : std::stod(f[4]),
                   std::stod(f[8])});
  }
  return out;
}

test::RunResult diagnose(const std::string& dataset, const fs::path& out) {
  return test::run_chutelab("diagnose --dataset " + (kSource / "datasets" / dataset).string() +
                            " --models dem --dem-quality standard --signature-quality quick --dem-cache-only "
                            "--dem-cache " + (kSource / "tests" / "peer" / "dem-cache").string() + " --out " +
                            out.string());
}

}  // namespace

BOOST_AUTO_TEST_CASE(flow_bias_found_in_peer_data) {
  const fs::path out = test::fresh_dir("peer-flowbias");
  const auto r = diagnose("liggghts-flowbias", out);
  BOOST_TEST_MESSAGE(r.out << r.err);
  BOOST_REQUIRE_MESSAGE(r.exit_code == 0, r.err);
  // Each set of runs says what it is for before it starts (they take a minute each from empty).
  for (const char* purpose : {"diagnose: the baseline: every condition without candidate effects (11 runs)",
                              "diagnose: the signatures: every condition without candidates and with each of the 12",
                              "diagnose: leading candidate 1, run for real to confirm its rank: every condition with "
                              "mass_flow_bias = ",
                              "diagnose: a point of mass_flow_bias's profile (its chi^2 from real runs): every condition "
                              "with mass_flow_bias = "})
    BOOST_TEST(r.err.find(purpose) != std::string::npos, purpose);
  const auto rows = singles(test::read_file(out / "diagnosis.csv"));
  BOOST_REQUIRE(!rows.empty());
  const Row& top = rows.front();
  BOOST_TEST(top.effect == "mass_flow_bias");
  BOOST_TEST(top.significant == "yes");
  // Within three standard deviations of the truth (HOW-MADE.md: -0.12). This is one case, not a
  // rate: the printed ± 2 sd covers the truth in 18-20 of 20 replicas per class (bench/DIAGNOSIS.md),
  // so a single case held to 2 sd fails one honest run in twenty, to 3 sd one in 370. Here the five
  // profile runs give -0.1236 ± 0.0017 (2.1 sd; bench/log/PEER_DIAGNOSIS.md): the stream's upper limit,
  // which the two codes also put apart on the clean rig, pulls the strength below the forces' own
  // -0.1200 ± 0.0023.
  BOOST_TEST(std::abs(top.estimate - -0.12) <= 3.0 * top.uncertainty, top.estimate << " ± " << top.uncertainty);
  // And >= 80 % of the excess misfit (chi^2 - n) explained, by the real runs at the fitted strength
  // (the leading candidates are re-run before the ranking is final).
  BOOST_TEST(top.explained >= 0.8, top.explained);
  BOOST_TEST_MESSAGE("explained fraction " << top.explained);
}

BOOST_AUTO_TEST_CASE(no_false_alarm_on_the_clean_peer_rig) {
  const fs::path out = test::fresh_dir("peer-clean");
  const auto r = diagnose("liggghts-rig", out);
  BOOST_TEST_MESSAGE(r.out << r.err);
  BOOST_REQUIRE_MESSAGE(r.exit_code == 0, r.err);
  BOOST_TEST(r.out.find("No significant missing effect") != std::string::npos, r.out);
}
