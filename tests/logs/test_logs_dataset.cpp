// A dataset of logs end to end: the bundled datasets/hidden-effect-logs through validate and
// import-logs, bad input, and the diagnosis's verdict from logs against the one from the true means.
#include <boost/test/unit_test.hpp>
#include <cmath>
#include <fmt/format.h>
#include <map>

#include "api/diagnose.h"
#include "api/synthesize.h"
#include "../cli/cli_runner.h"
#include "validation/dataset.h"
#include "validation/dataset_output.h"

using namespace chutelab;
namespace fs = std::filesystem;

namespace {
const fs::path kSource = CHUTELAB_SOURCE_DIR;
const fs::path kLogs = kSource / "datasets" / "hidden-effect-logs";
}  // namespace

BOOST_AUTO_TEST_CASE(validate_reads_the_bundled_logs_end_to_end) {
  const auto out = test::fresh_dir("logs-validate");
  const auto r = test::run_chutelab(fmt::format("validate --dataset {} --out {}", kLogs.string(), out.string()));
  BOOST_TEST_MESSAGE(r.err);
  BOOST_REQUIRE(r.exit_code == 0);
  const std::string html = test::read_file(out / "report.html"), md = test::read_file(out / "report.md");
  BOOST_TEST((html.find("The rig&#39;s logs") != std::string::npos || html.find("The rig's logs") != std::string::npos));
  BOOST_TEST(html.find("log-chart") != std::string::npos);
  BOOST_TEST(html.find("log-window") != std::string::npos);
  BOOST_TEST(md.find("V2-26 (logs/V2-26.csv)") != std::string::npos);
}

BOOST_AUTO_TEST_CASE(import_logs_writes_means_with_their_provenance) {
  const auto out = test::fresh_dir("logs-import") / "means";
  const auto r = test::run_chutelab(fmt::format("import-logs --dataset {} --out {}", kLogs.string(), out.string()));
  BOOST_REQUIRE(r.exit_code == 0);
  const std::string meas = test::read_file(out / "measurements.csv");
  BOOST_TEST(meas.rfind("condition,quantity,value,uncertainty,source_file,window_start_s,window_end_s,method\n", 0) == 0);
  BOOST_TEST(meas.find("V2-26,normal_force_N,") != std::string::npos);
  BOOST_TEST(meas.find("logs/V2-26.csv") != std::string::npos);
  BOOST_TEST(meas.find("batch means") != std::string::npos);
  BOOST_TEST(test::read_file(out / "log_provenance.csv").find("tau_s,n_eff") != std::string::npos);
  BOOST_TEST(fs::exists(out / "log_checks.csv"));
  BOOST_TEST(!fs::exists(out / "logs"));
  // The dataset of means is a dataset: it validates, and reads the same values the logs gave.
  const auto v = test::run_chutelab(fmt::format("validate --dataset {} --out {}", out.string(), (out / "v").string()));
  BOOST_TEST(v.exit_code == 0);
}

BOOST_AUTO_TEST_CASE(bad_logs_exit_2_and_write_nothing) {
  const auto dir = test::fresh_dir("logs-badset");
  fs::copy(kLogs, dir / "d", fs::copy_options::recursive);
  std::string layout = test::read_file(dir / "d" / "logs" / "layout.toml");
  layout.replace(layout.find("gain = "), 7, "gian = ");
  test::write_file(dir / "d" / "logs" / "layout.toml", layout);
  const auto r = test::run_chutelab(
      fmt::format("import-logs --dataset {} --out {}", (dir / "d").string(), (dir / "out").string()));
  BOOST_TEST(r.exit_code == 2);
  BOOST_TEST(r.err.find("layout.toml") != std::string::npos);
  BOOST_TEST(r.err.find("channel.gain") != std::string::npos);
  BOOST_TEST(!fs::exists(dir / "out"));
  // A condition without its log.
  fs::copy_file(kLogs / "logs" / "layout.toml", dir / "d" / "logs" / "layout.toml", fs::copy_options::overwrite_existing);
  fs::remove(dir / "d" / "logs" / "V3-41.csv");
  const auto m = test::run_chutelab(fmt::format("validate --dataset {} --out {}", (dir / "d").string(), (dir / "out").string()));
  BOOST_TEST(m.exit_code == 2);
  BOOST_TEST(m.err.find("V3-41") != std::string::npos);
  BOOST_TEST(!fs::exists(dir / "out"));
}

BOOST_AUTO_TEST_CASE(the_verdict_from_logs_is_the_verdict_from_the_true_means) {
  // The true means: the models with the hidden effect and no noise (how datasets/hidden-effect and
  // its logs were made, their HOW-MADE.md), at the hidden-effect dataset's stated uncertainties.
  api::SynthesizeOptions so;
  so.dataset = kSource / "datasets" / "grima2010";
  so.effects = {"air_drag=0.7"};
  so.noise_scale = 0.0;
  const api::SynthesizeResult truth = api::synthesize(so);
  const auto dir = test::fresh_dir("logs-truth") / "t";
  validation::write_dataset(dir, truth.files, truth.source.dir, "synthesize");
  validation::Dataset means = validation::read_dataset(kSource / "datasets" / "hidden-effect");
  std::map<std::pair<std::string, Quantity>, double> value;
  for (const auto& m : validation::read_measurements(dir / "measurements.csv", nullptr))
    value[{m.condition, m.quantity}] = m.value;
  for (auto& m : means.measurements) m.value = value.at({m.condition, m.quantity});
  for (auto& p : means.trajectory) (void)p;  // the stream's limits stay as measured in both
  api::DiagnoseOptions o;
  o.dataset = kLogs;
  const api::DiagnoseResult from_logs = api::diagnose(o);
  const api::DiagnoseResult from_truth = api::diagnose(means, o);
  BOOST_REQUIRE(from_truth.diagnosis.best());
  BOOST_REQUIRE(from_logs.diagnosis.best());
  BOOST_TEST(from_truth.diagnosis.best()->label() == "air_drag");
  BOOST_TEST(from_logs.diagnosis.best()->label() == from_truth.diagnosis.best()->label());
  BOOST_TEST(static_cast<int>(from_logs.diagnosis.verdict_code) == static_cast<int>(from_truth.diagnosis.verdict_code));
}

BOOST_AUTO_TEST_CASE(logs_ride_on_the_dems_own_plate_force_series) {
  // A DEM run's series (as simulate --out writes it) for each condition: a rise, then a steady load
  // with its own fluctuation (7 Hz, 1 N). The logs carry that fluctuation on the truth's means; read
  // back, the R_n are the truth's within 3 u (the fluctuation averages out over the window).
  const auto dir = test::fresh_dir("logs-dem");
  const std::vector<std::string> conditions = {"V2-26", "V2-41", "V3-28", "V3-41", "V4-28", "V4-41", "V5-28", "V5-44"};
  std::string truth = "condition,quantity,value\n";
  for (const auto& c : conditions) {
    truth += c + ",normal_force_N,30\n" + c + ",shear_force_N,3\n" + c + ",impact_point_y_mm,60\n";
    std::string s = "t_s,normal_force_N,shear_force_N,moment_Nm,impact_point_y_mm\n";
    for (int k = 1; k <= 300; ++k) {
      const double t = 0.003 * k, rise = 1.0 - std::exp(-t / 0.05);
      const double n = 32.0 * rise + std::sin(2.0 * 3.14159265358979 * 7.0 * t);
      s += fmt::format("{},{},{},{},{}\n", t, n, 3.2 * rise, -0.06 * n, rise > 0.01 ? "61" : "");
    }
    test::write_file(dir / "dem" / c / "timeseries.csv", s);
  }
  test::write_file(dir / "truth.csv", truth);
  const auto made = test::run_chutelab(fmt::format("synthesize-logs --dataset {} --truth {} --dem-series {} --seed 4 --out {}",
                                                   (kSource / "datasets" / "hidden-effect").string(),
                                                   (dir / "truth.csv").string(), (dir / "dem").string(),
                                                   (dir / "logs").string()));
  BOOST_REQUIRE(made.exit_code == 0);
  const auto imp = test::run_chutelab(fmt::format("import-logs --dataset {} --out {}", (dir / "logs").string(),
                                                  (dir / "means").string()));
  BOOST_REQUIRE(imp.exit_code == 0);
  // (At least 7 of 8: a clean log is taken for a creeping one about once in a hundred, bench/LOGS.md,
  // and its correction then moves it by the test's threshold; with this seed V2-26 is such a log.)
  int rows = 0, within = 0;
  for (const auto& m : validation::read_measurements(dir / "means" / "measurements.csv", nullptr)) {
    if (m.quantity != Quantity::normal_force) continue;
    ++rows;
    within += std::abs(m.value - 30.0) < 3.0 * *m.uncertainty;
  }
  BOOST_TEST(rows == 8);
  BOOST_TEST(within >= 7);
  // A condition without its run: bad input naming the folder's key.
  fs::remove_all(dir / "dem" / "V5-44");
  const auto bad = test::run_chutelab(fmt::format("synthesize-logs --dataset {} --truth {} --dem-series {} --out {}",
                                                  (kSource / "datasets" / "hidden-effect").string(),
                                                  (dir / "truth.csv").string(), (dir / "dem").string(),
                                                  (dir / "logs2").string()));
  BOOST_TEST(bad.exit_code == 2);
  BOOST_TEST(bad.err.find("--dem-series") != std::string::npos);
  BOOST_TEST(!fs::exists(dir / "logs2"));
}
