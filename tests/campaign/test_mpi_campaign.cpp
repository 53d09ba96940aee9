// Campaigns under `mpirun -n 2 --oversubscribe`, as a user runs them, on a tiny two-condition rig
// whose [dem] table keeps each DEM run to 0.4 s simulated: validate with dem, diagnose with a DEM
// baseline and a sensitivity subset give the same bytes as one process (and as --jobs 2). Without
// MPI (CMake found none) the whole executable reports itself skipped (exit 77), never passed.
#define BOOST_TEST_MODULE mpi_campaign
#include <boost/test/unit_test.hpp>

#include <cstdlib>
#include <sys/wait.h>

#include "../cli/cli_runner.h"

using namespace chutelab::test;
namespace fs = std::filesystem;

namespace {

struct SkipWithoutMpi {
  SkipWithoutMpi() {
    if (std::string(CHUTELAB_MPIEXEC).empty()) {
      std::fprintf(stderr, "MPI not found by CMake: mpi_campaign skipped\n");
      std::_Exit(77);
    }
    // The CI runs as root; OpenMPI's launcher refuses root without these.
    ::setenv("OMPI_ALLOW_RUN_AS_ROOT", "1", 1);
    ::setenv("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1", 1);
  }
};
BOOST_GLOBAL_FIXTURE(SkipWithoutMpi);

fs::path tiny_dataset() {
  static const fs::path d = tiny_station_dataset("tiny-dataset", true);
  return d;
}

// chutelab under mpirun with its own empty DEM cache (so every run really runs on its rank).
RunResult run(const std::string& prefix, const std::string& args, const std::string& tag) {
  const fs::path d = fresh_dir("mpi-" + tag);
  const std::string cmd = "CHUTELAB_DEM_CACHE='" + (d / "cache").string() + "' " + prefix + " '" + CHUTELAB_BINARY +
                          "' " + args + " >'" + (d / "out").string() + "' 2>'" + (d / "err").string() + "' </dev/null";
  const int status = std::system(cmd.c_str());
  RunResult r;
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.out = read_file(d / "out");
  r.err = read_file(d / "err");
  return r;
}

const std::string kMpi = std::string("'") + CHUTELAB_MPIEXEC + "' -n 2 --oversubscribe";

void same_files(const fs::path& a, const fs::path& b, std::initializer_list<const char*> files) {
  for (const char* f : files) {
    BOOST_TEST_INFO(f);
    BOOST_REQUIRE(fs::exists(a / f));
    BOOST_TEST(read_file(a / f) == read_file(b / f));
  }
}

}  // namespace

BOOST_AUTO_TEST_CASE(validate_with_dem_is_byte_identical_under_mpirun) {
  const std::string ds = tiny_dataset().string();
  const fs::path one = fresh_dir("v-one"), two = fresh_dir("v-two"), jobs = fresh_dir("v-jobs");
  const auto a = run("", "validate --dataset " + ds + " --models korzen,dem --out " + one.string(), "v1");
  const auto b = run(kMpi, "validate --dataset " + ds + " --models korzen,dem --out " + two.string(), "v2");
  const auto c = run("", "validate --dataset " + ds + " --models korzen,dem --jobs 2 --out " + jobs.string(), "v3");
  BOOST_TEST_MESSAGE(b.out << b.err);
  BOOST_REQUIRE(a.exit_code == 0);
  BOOST_REQUIRE(b.exit_code == 0);
  BOOST_REQUIRE(c.exit_code == 0);
  // report.md/html name each run's wall time and cache file, which differ between any two runs.
  same_files(one, two, {"predictions.csv", "errors.csv", "summary.csv", "dem/T3/timeseries.csv", "dem/T4/sensors.csv",
                        "dem/T4/steady.csv", "dem/T3/trajectory.csv", "dem/T4/side_view.csv"});
  same_files(one, jobs, {"predictions.csv", "errors.csv", "summary.csv", "dem/T4/timeseries.csv"});
  // Rank 0 alone prints: one summary line, and the campaign's balance line.
  BOOST_TEST(count_lines(b.out) == count_lines(a.out));
  // Two conditions, each with its ladder for u_num's discretisation part (2 dt, and two coarser
  // particle sizes: quick coarse-grains the dataset's particles): eight runs spread over the ranks.
  BOOST_TEST(b.err.find("8 jobs on 2 MPI ranks") != std::string::npos);
  // Rank 0 alone staged and committed --out; no rank left a staging folder beside it or in it.
  for (const auto& dir : {two.parent_path(), two})
    for (const auto& e : fs::directory_iterator(dir))
      BOOST_TEST(e.path().filename().string().find(".partial") == std::string::npos, e.path());
}

// An --out that cannot be placed under mpirun: refused once, before the DEM runs, --out as it was.
BOOST_AUTO_TEST_CASE(unusable_out_under_mpirun_is_one_line_and_leaves_out_alone) {
  const fs::path out = fresh_dir("bad-out");
  fs::create_directories(out / "errors.csv");
  const auto r = run(kMpi, "validate --dataset " + tiny_dataset().string() + " --models korzen,dem --out " + out.string(),
                     "bad-out");
  BOOST_TEST(r.exit_code == 2);
  std::size_t n = 0;
  for (auto at = r.err.find("chutelab: "); at != std::string::npos; at = r.err.find("chutelab: ", at + 1)) ++n;
  BOOST_TEST(n == 1u, r.err);
  BOOST_TEST(r.err.find("errors.csv: --out: is a folder where chutelab writes a file") != std::string::npos, r.err);
  BOOST_TEST(r.err.find("jobs on 2 MPI ranks") == std::string::npos, r.err);  // no DEM campaign started
  std::size_t entries = 0;
  for (const auto& e : fs::directory_iterator(out)) entries += e.path().filename() == "errors.csv" ? 1 : 100;
  BOOST_TEST(entries == 1u);
  for (const auto& e : fs::directory_iterator(out.parent_path()))
    BOOST_TEST(e.path().filename().string().find(".partial") == std::string::npos, e.path());
}

BOOST_AUTO_TEST_CASE(diagnose_with_a_dem_baseline_is_byte_identical_under_mpirun) {
  const std::string ds = tiny_dataset().string();
  const fs::path one = fresh_dir("d-one"), two = fresh_dir("d-two");
  const auto a = run("", "diagnose --dataset " + ds + " --models dem --out " + one.string(), "d1");
  const auto b = run(kMpi, "diagnose --dataset " + ds + " --models dem --out " + two.string(), "d2");
  BOOST_REQUIRE(a.exit_code == 0);
  BOOST_REQUIRE(b.exit_code == 0);
  same_files(one, two, {"diagnosis.csv", "diagnosis.md"});
  BOOST_TEST(a.out.substr(0, a.out.find('\n')) == b.out.substr(0, b.out.find('\n')));  // the verdict
  // Every list of runs goes over the ranks: the baseline with its ladders, and the DEM's own
  // signature runs (one probe per candidate it represents and condition).
  std::size_t campaigns = 0;
  for (auto at = b.err.find("jobs on 2 MPI ranks"); at != std::string::npos; at = b.err.find("jobs on 2 MPI ranks", at + 1))
    ++campaigns;
  BOOST_TEST(campaigns >= 2u, b.err);
}

BOOST_AUTO_TEST_CASE(sensitivity_is_byte_identical_under_mpirun) {
  const std::string args = "sensitivity --dataset " + tiny_dataset().string() + " --condition T3 --only G/10,d=9mm,LSD --out ";
  const fs::path one = fresh_dir("s-one"), two = fresh_dir("s-two");
  const auto a = run("", args + one.string(), "s1");
  const auto b = run(kMpi, args + two.string(), "s2");
  BOOST_TEST_MESSAGE(b.out << b.err);
  BOOST_REQUIRE(a.exit_code == 0);
  BOOST_REQUIRE(b.exit_code == 0);
  same_files(one, two, {"sensitivity.csv", "sensitivity.md", "sensitivity.html"});
  BOOST_TEST(fs::exists(two / "sensitivity-timing.csv"));
}

// Bad input under mpirun: exit 2 and chutelab's one line once (rank 0's; mpirun adds its own
// notice of a non-zero exit), nothing written.
BOOST_AUTO_TEST_CASE(bad_input_under_mpirun_is_one_line) {
  const fs::path out = fresh_dir("bad") / "out";
  const auto r = run(kMpi, "sensitivity --dataset " + tiny_dataset().string() + " --condition nope --out " + out.string(), "bad");
  BOOST_TEST(r.exit_code == 2);
  std::size_t n = 0;
  for (auto at = r.err.find("chutelab: "); at != std::string::npos; at = r.err.find("chutelab: ", at + 1)) ++n;
  BOOST_TEST(n == 1u, r.err);
  BOOST_TEST(r.err.find("no condition named 'nope'") != std::string::npos);
  BOOST_TEST(!fs::exists(out));
}
