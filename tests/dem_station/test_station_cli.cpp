// `chutelab simulate` and `validate --models dem` as a user runs them, on a tiny dataset whose
// [dem] table keeps the runs short (0.4 s simulated). The DEM cache goes to a fresh folder, so the
// tests never depend on a warm cache.
#define BOOST_TEST_MODULE dem_station_cli
#include <boost/test/unit_test.hpp>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdlib>
#include <sstream>
#include <string>
#include <thread>

#include "../cli/cli_runner.h"
#include "dem/station/settings.h"

using namespace chutelab::test;
namespace fs = std::filesystem;

namespace {

fs::path tiny_dataset() {
  static const fs::path d = tiny_station_dataset("tiny-dataset");
  return d;
}

struct FreshCache {
  FreshCache() { ::setenv("CHUTELAB_DEM_CACHE", fresh_dir("dem-cache").c_str(), 1); }
};

}  // namespace

BOOST_GLOBAL_FIXTURE(FreshCache);

BOOST_AUTO_TEST_CASE(simulate_help_lists_the_scaling_options) {
  const auto r = run_chutelab("simulate --help");
  BOOST_TEST(r.exit_code == 0);
  for (const char* flag : {"--quality", "--diameter-mm", "--shear-modulus-scale", "--dt-fraction", "--contact",
                           "--threads", "--seed", "--out", "--vtk-every", "--dataset", "--condition"})
    BOOST_TEST(r.out.find(flag) != std::string::npos, flag);
  // Every [dem] setting with an option is a flag, named by the option (dem/station/settings.h).
  for (const auto& f : chutelab::dem::station::dem_fields()) {
    if (f.option.empty()) continue;
    std::string flag = "--" + std::string(f.option);
    std::replace(flag.begin(), flag.end(), '_', '-');
    BOOST_TEST(r.out.find(flag + " ") != std::string::npos, flag);
  }
}

BOOST_AUTO_TEST_CASE(bad_input_is_one_line_and_exit_2) {
  const std::string ds = tiny_dataset().string();
  for (const std::string& args : {"simulate --dataset " + ds + " --condition nope",
                                  "simulate --dataset " + ds + " --condition T3 --quality fast",
                                  "simulate --dataset " + ds + " --condition T3 --contact rubber",
                                  "simulate --dataset " + ds + " --condition T3 --dt-fraction 3",
                                  "simulate --dataset " + ds + " --condition T3 --diameter-mm 60",
                                  "simulate --dataset " + ds + " --condition T3 --plate-cells 999",
                                  "simulate --dataset " + ds + " --condition T3 --archard-coefficient -1",
                                  "simulate --dataset " + ds + " --condition T3 --finnie-cutting-fraction 2"}) {
    const auto r = run_chutelab(args);
    BOOST_TEST(r.exit_code == 2, args);
    BOOST_TEST(count_lines(r.err) == 1, args << ": " << r.err);
  }
}

// A run writes the series, the steady means, the side view and VTK, and prints the means.
BOOST_AUTO_TEST_CASE(simulate_writes_series_means_and_vtk) {
  const fs::path out = fresh_dir("sim-out");
  const auto r = run_chutelab("simulate --dataset " + tiny_dataset().string() + " --condition T3 --no-cache --vtk-every 0.2 --plate-cells 8 "
                              "--archard-coefficient 2e-6 --out " + out.string());
  BOOST_TEST_MESSAGE(r.out);
  BOOST_REQUIRE(r.exit_code == 0);
  BOOST_TEST(r.out.find("plate normal force R_n") != std::string::npos);
  for (const char* f : {"timeseries.csv", "sensors.csv", "steady.csv", "trajectory.csv", "side_view.csv", "run.txt",
                        "side_view.vtk", "vtk/walls.vtk", "vtk/particles.pvd", "vtk/particles_00000.vtp", "vtk/particles_00001.vtp"})
    BOOST_TEST(fs::exists(out / f), f);
  BOOST_TEST(read_file(out / "steady.csv").find("normal_force_N,") != std::string::npos);
  BOOST_TEST(count_lines(read_file(out / "timeseries.csv")) > 100);
  // The plate map: one row per triangle, units in the column names, and its VTK.
  BOOST_TEST(r.out.find("plate map (") != std::string::npos);
  // In the units a plate's loads are read in: kPa and µm/h.
  BOOST_TEST(r.out.find(" kPa at y = ") != std::string::npos, r.out);
  BOOST_TEST(r.out.find(" µm/h, mean ") != std::string::npos, r.out);
  BOOST_TEST(r.out.find("um/h") == std::string::npos);
  BOOST_TEST(fs::exists(out / "plate_map.vtk"));
  const std::string map = read_file(out / "plate_map.csv");
  BOOST_TEST(map.rfind("condition,wall,triangle,x_mm,y_mm,z_mm,area_mm2,pressure_Pa,shear_stress_Pa,", 0) == 0);
  BOOST_TEST(map.find("archard_wear_rate_um_per_h") != std::string::npos);
  BOOST_TEST(count_lines(map) > 2 * 8 + 1);
}

// validate --models dem runs the DEM once; the second validate comes from the cache, at once, with
// the same numbers.
BOOST_AUTO_TEST_CASE(validate_with_dem_is_cached) {
  const std::string ds = tiny_dataset().string();
  const fs::path a = fresh_dir("val-a"), b = fresh_dir("val-b");
  const auto t0 = std::chrono::steady_clock::now();
  const auto first = run_chutelab("validate --dataset " + ds + " --models korzen,booth-cema,dem --out " + a.string());
  const auto t1 = std::chrono::steady_clock::now();
  const auto second = run_chutelab("validate --dataset " + ds + " --models korzen,booth-cema,dem --out " + b.string());
  const auto t2 = std::chrono::steady_clock::now();
  BOOST_TEST_MESSAGE(first.out << first.err);
  BOOST_REQUIRE(first.exit_code == 0);
  BOOST_REQUIRE(second.exit_code == 0);
  const double s1 = std::chrono::duration<double>(t1 - t0).count(), s2 = std::chrono::duration<double>(t2 - t1).count();
  BOOST_TEST_MESSAGE("first validate " << s1 << " s, second " << s2 << " s");
  // The cache is read, not timed against a fixed limit (a sanitized build under load took 2.25 s):
  // the second call says every run came from it, and takes a fraction of the first.
  BOOST_TEST(second.err.find("all from the cache") != std::string::npos, second.err);
  BOOST_TEST(s2 < 0.5 * s1);
  // The plate map comes back from the cache too: both reports have the section.
  BOOST_TEST(read_file(a / "report.md").find("## Plate loading and wear") != std::string::npos);
  BOOST_TEST(read_file(b / "report.md").find("## Plate loading and wear") != std::string::npos);
  const std::string p = read_file(a / "predictions.csv");
  BOOST_TEST(p == read_file(b / "predictions.csv"));
  BOOST_TEST(p.find(",dem,") != std::string::npos);
  BOOST_TEST(fs::exists(a / "dem" / "T3" / "timeseries.csv"));
  BOOST_TEST(fs::exists(b / "dem" / "T3" / "side_view.vtk"));
  // Progress in a log (stderr is a pipe here): one plain line per run that ran, each "[k/N] ...
  // done in", no carriage return; from the cache one line saying so; with --quiet nothing.
  BOOST_TEST(first.err.find('\r') == std::string::npos);
  const auto total_at = first.err.find("validate: ");
  BOOST_REQUIRE(total_at != std::string::npos);
  const int runs = std::stoi(first.err.substr(total_at + 10));
  BOOST_TEST(runs >= 1);
  int done = 0;
  std::istringstream lines(first.err);
  for (std::string l; std::getline(lines, l);)
    if (l.starts_with("validate: [")) {
      ++done;
      BOOST_TEST(l.find("/" + std::to_string(runs) + "] dem T3") != std::string::npos, l);
      BOOST_TEST(l.find(" done in ") != std::string::npos, l);
    }
  BOOST_TEST(done == runs, first.err);
  BOOST_TEST(second.err.find("all from the cache") != std::string::npos, second.err);
  BOOST_TEST(count_lines(second.err) <= 2, second.err);
  const auto quiet = run_chutelab("validate --dataset " + ds + " --models korzen,booth-cema,dem --quiet --out " +
                                  fresh_dir("val-q").string());
  BOOST_TEST(quiet.exit_code == 0);
  BOOST_TEST(quiet.err.empty(), quiet.err);
  // The same results on stdout: --quiet silences progress only.
  BOOST_TEST(quiet.out.substr(0, quiet.out.find("report: ")) == second.out.substr(0, second.out.find("report: ")));
}

// The DEM cache trusts an entry only whole (dem/station/cache.h). An unparsable R_n was read as 0
// N, a FIFO in an entry's place blocked the command for ever, and a run that could not be cached
// was reported "cached as FILE".
BOOST_AUTO_TEST_CASE(a_damaged_cache_entry_is_refused_not_read) {
  const std::string ds = tiny_dataset().string();
  const fs::path cache = fresh_dir("cache-damaged");
  const std::string args = "validate --dataset " + ds + " --models korzen,dem --dem-ladder off --dem-cache " + cache.string();
  const fs::path a = fresh_dir("damaged-a");
  const auto first = run_chutelab(args + " --out " + a.string());
  BOOST_REQUIRE_MESSAGE(first.exit_code == 0, first.err);
  fs::path entry;
  for (const auto& e : fs::directory_iterator(cache))
    if (e.path().extension() == ".txt") entry = e.path();
  BOOST_REQUIRE(!entry.empty());
  const std::string text = read_file(entry);
  BOOST_TEST(read_file(a / "report.md").find("cached as " + entry.string()) != std::string::npos);
  // R_n unreadable: under --dem-cache-only bad input naming the file, its line and what is wrong.
  const std::size_t at = text.find("\nscalar normal_force ") + 21;
  BOOST_REQUIRE(at > 21);
  write_file(entry, text.substr(0, at) + "abc" + text.substr(text.find(' ', at)));
  const auto only = run_chutelab(args + " --dem-cache-only --out " + fresh_dir("damaged-b").string());
  BOOST_TEST(only.exit_code == 2);
  // One error line (a log's progress line says the run failed).
  BOOST_TEST(only.err.find("chutelab: ") == only.err.rfind("chutelab: "), only.err);
  const long line = 1 + static_cast<long>(std::count(text.begin(), text.begin() + static_cast<long>(at), '\n'));
  BOOST_TEST(only.err.find(entry.string() + ":" + std::to_string(line) + ": scalar: normal_force: 'abc' is not a number") !=
                 std::string::npos,
             only.err);
  // Without it the run is made again, said on stderr and in the report, and its entry is whole again.
  const fs::path c = fresh_dir("damaged-c");
  const auto again = run_chutelab(args + " --out " + c.string());
  BOOST_REQUIRE_MESSAGE(again.exit_code == 0, again.err);
  BOOST_TEST(again.err.find("DEM cache entry refused") != std::string::npos, again.err);
  BOOST_TEST(read_file(c / "report.md").find("refused and run again") != std::string::npos);
  BOOST_TEST(read_file(c / "predictions.csv") == read_file(a / "predictions.csv"));
  BOOST_TEST(run_chutelab(args + " --dem-cache-only --out " + fresh_dir("damaged-d").string()).exit_code == 0);
  // A FIFO where the entry belongs: refused at once (a writer opens it after 60 s, should the
  // command wait for one).
  fs::remove(entry);
  BOOST_REQUIRE(::mkfifo(entry.c_str(), 0600) == 0);
  std::atomic<bool> done{false};
  std::thread rescue([&] {
    for (int k = 0; k < 600 && !done; ++k) std::this_thread::sleep_for(std::chrono::milliseconds(100));
    const int fd = ::open(entry.c_str(), O_WRONLY | O_NONBLOCK);
    if (fd >= 0) ::close(fd);
  });
  const auto t0 = std::chrono::steady_clock::now();
  const auto fifo = run_chutelab(args + " --dem-cache-only --out " + fresh_dir("damaged-e").string());
  const double waited = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  done = true;
  rescue.join();
  BOOST_TEST(waited < 30.0);
  BOOST_TEST(fifo.exit_code == 2);
  BOOST_TEST(fifo.err.find("is a FIFO") != std::string::npos, fifo.err);
  fs::remove(entry);
  // A cache that cannot be written (a file stands where its folder would be): the run is said to
  // be not cached, and why.
  const fs::path blocked = fresh_dir("damaged-blocked");
  write_file(blocked / "file", "x");
  const fs::path f = fresh_dir("damaged-f");
  const auto unwritable = run_chutelab("validate --dataset " + ds + " --models korzen,dem --dem-ladder off --dem-cache " +
                                       (blocked / "file" / "cache").string() + " --out " + f.string());
  BOOST_REQUIRE_MESSAGE(unwritable.exit_code == 0, unwritable.err);
  const std::string report = read_file(f / "report.md");
  BOOST_TEST(report.find("cached as") == std::string::npos);
  BOOST_TEST(report.find("not cached (cannot make the cache folder") != std::string::npos);
  BOOST_TEST(unwritable.err.find("not cached") != std::string::npos, unwritable.err);
}
