// The diagnosis predicts the conditions of its analytical fits on --jobs threads; the files it
// writes must not depend on how many (the determinism rule: same inputs, same numbers, any thread
// count). The dataset is large enough (200 conditions) for the threads to be used.
#include <boost/test/unit_test.hpp>
#include <filesystem>
#include <fmt/format.h>

#include "../cli/cli_runner.h"

using namespace chutelab::test;
namespace fs = std::filesystem;

BOOST_AUTO_TEST_SUITE(diagnosis_threads)

BOOST_AUTO_TEST_CASE(same_files_on_one_and_two_threads) {
  const fs::path d = fresh_dir("diagnosis-threads");
  fs::create_directories(d / "rig");
  fs::copy_file(fs::path(CHUTELAB_SOURCE_DIR) / "datasets" / "liggghts-rig" / "setup.toml", d / "rig" / "setup.toml");
  // The LIGGGHTS rig's geometry at 2-5 m/s and 20-45 t/h, the plate farther for faster belts.
  std::string conditions = "condition,belt_speed_mps,mass_flow_tph,plate_distance_mm,plate_top_mm\n";
  for (int i = 0; i < 200; ++i) {
    const double v = 2.0 + 3.0 * ((i * 37) % 200) / 200.0, f = 20.0 + 25.0 * ((i * 53) % 200) / 200.0;
    conditions += fmt::format("C{:03d},{:.3f},{:.2f},{:.0f},250\n", i, v, f, 300.0 + 100.0 * static_cast<int>(v - 2.0));
  }
  write_file(d / "rig" / "conditions.csv", conditions);
  BOOST_REQUIRE(run_chutelab(fmt::format("synthesize --dataset '{}' --effect air_drag=0.7 --effect load_cell_offset=5 "
                                         "--seed 7300 --out '{}'",
                                         (d / "rig").string(), (d / "data").string()))
                    .exit_code == 0);
  for (int jobs : {1, 2})
    BOOST_REQUIRE(run_chutelab(fmt::format("diagnose --dataset '{}' --jobs {} --no-pairs --out '{}'", (d / "data").string(),
                                           jobs, (d / fmt::format("diag{}", jobs)).string()))
                      .exit_code == 0);
  for (const char* file : {"diagnosis.csv", "diagnosis.md"}) {
    BOOST_TEST_CONTEXT(file) {
      const std::string one = read_file(d / "diag1" / file), two = read_file(d / "diag2" / file);
      BOOST_TEST(!one.empty());
      BOOST_TEST((one == two));
    }
  }
}

BOOST_AUTO_TEST_SUITE_END()
