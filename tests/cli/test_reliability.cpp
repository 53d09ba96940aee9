// Reliability: one test per defect class, each through the real binary as a
// user runs it. Every refusal is checked for its exit code and its one-line message; every run for
// its inputs byte-identical afterwards and for nothing written outside --out (a snapshot of the whole
// sandbox, --out left out, before and after); no staging folder left behind.
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <fmt/format.h>
#include <map>
#include <set>
#include <vector>
#include <string>
#include <sys/wait.h>
#include <unistd.h>

#include "cli_runner.h"
#include "tree_snapshot.h"
#include "core/file_name.h"

using namespace chutelab::test;
namespace fs = std::filesystem;

namespace {

const fs::path kSrc = CHUTELAB_SOURCE_DIR;
const fs::path kRig = kSrc / "datasets" / "liggghts-rig";

std::string repeat(const std::string& s, int n) {
  std::string o;
  o.reserve(s.size() * static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) o += s;
  return o;
}

// A copy of the bundled LIGGGHTS rig in a sandbox, and an --out beside it.
struct Sandbox {
  fs::path root, data, out;
  explicit Sandbox(const std::string& name) {
    root = fresh_dir("rel-" + name);
    data = root / "data";
    out = root / "out";
    fs::create_directories(data);
    for (const auto& f : fs::directory_iterator(kRig)) fs::copy_file(f.path(), data / f.path().filename());
  }
  std::string q(const fs::path& p) const { return fmt::format("'{}'", p.string()); }
  std::string args(const std::string& cmd) const { return cmd + " --dataset " + q(data) + " --out " + q(out); }
  void replace_in(const std::string& file, const std::string& from, const std::string& to) const {
    std::string s = read_file(data / file);
    for (std::size_t at = 0; (at = s.find(from, at)) != std::string::npos; at += to.size()) s.replace(at, from.size(), to);
    write_file(data / file, s);
  }
};

// The promise for bad input: the exit code, one line naming what is given, nothing changed anywhere
// in the sandbox (--out included), nothing staged left behind.
RunResult refused(const Sandbox& s, const std::string& args, int code, const std::string& says) {
  const auto before = snapshot(s.root);
  const auto r = run_chutelab(args);
  BOOST_TEST_INFO("chutelab " << args.substr(0, 300) << "\nstderr: " << r.err.substr(0, 2000));
  BOOST_TEST(r.exit_code == code);
  BOOST_TEST(count_lines(r.err) == 1);
  BOOST_TEST(r.err.find(says) != std::string::npos);
  BOOST_TEST((snapshot(s.root) == before));
  BOOST_TEST(!staging_left(s.root));
  return r;
}

// A run that succeeds (or fails acceptance): its exit code, nothing written outside --out, the
// inputs unchanged.
RunResult accepted(const Sandbox& s, const std::string& args, int code = 0) {
  const auto outside = snapshot(s.root, s.out);
  const auto r = run_chutelab(args);
  BOOST_TEST_INFO("chutelab " << args.substr(0, 300) << "\nstderr: " << r.err.substr(0, 2000));
  BOOST_TEST(r.exit_code == code);
  BOOST_TEST((snapshot(s.root, s.out) == outside));
  BOOST_TEST(!staging_left(s.root));
  return r;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(reliability)

// Class 1: no TOML file reaches toml++ unbounded. Each reader (setup.toml, tolerances, the
// import mapping; the [dem] table is setup.toml read again) refuses deep and oversized files with
// exit 2 and a line naming file and line, where toml++ would overflow its stack (exit 139).
BOOST_AUTO_TEST_CASE(class1_toml_is_bounded_before_the_parser) {
  Sandbox s("toml");
  const std::string setup = read_file(s.data / "setup.toml");
  const std::string deep_key = "a" + repeat(".a", 49999) + " = 1\n";
  const std::string deep_header = "[" + std::string("a") + repeat(".a", 49999) + "]\nx = 1\n";
  const std::string deep_array = "x = " + repeat("[", 100000) + repeat("]", 100000) + "\n";
  const std::string deep_inline = "x = " + repeat("{a=", 20000) + "1" + repeat("}", 20000) + "\n";
  const std::string deep_mixed = "[b.c]\nx = [{ " + repeat("a.", 40) + "z = 1 }]\n";
  // setup.toml (read by every command, the [dem] table's reader after it)
  for (const auto& [text, line] : {std::pair{deep_key, 1}, {deep_header, 1}, {deep_array, 1}, {deep_inline, 1}}) {
    write_file(s.data / "setup.toml", text + setup);
    refused(s, s.args("validate"), 2, "setup.toml:" + std::to_string(line) + ": nested ");
  }
  write_file(s.data / "setup.toml", setup + "\n" + deep_mixed);
  refused(s, s.args("validate"), 2, "levels deep");
  // Too big, whatever it holds: refused before it is read whole.
  write_file(s.data / "setup.toml", setup + repeat("# padding padding padding padding padding padding padding\n", 20000));
  refused(s, s.args("validate"), 2, "setup.toml: is larger than 1 MiB");
  write_file(s.data / "setup.toml", setup);
  // Wide but shallow and small: read (an unknown key, said and ignored), no crash.
  write_file(s.data / "setup.toml", "wide = [" + repeat("1,", 100000) + "1]\n" + setup);
  const auto wide = accepted(s, s.args("validate"));
  BOOST_TEST(wide.err.find("unknown key 'wide' ignored") != std::string::npos);
  write_file(s.data / "setup.toml", setup);
  // tolerances.toml
  const fs::path tol = s.root / "tol.toml";
  for (const auto& text : {deep_key, deep_header, deep_array, deep_inline}) {
    write_file(tol, text);
    refused(s, s.args("validate") + " --tolerances " + s.q(tol), 2, "tol.toml:1: nested ");
  }
  // The import mapping.
  const fs::path ex = kSrc / "datasets" / "digitised-example";
  for (const auto& text : {deep_key, deep_header, deep_array, deep_inline}) {
    write_file(s.root / "mapping.toml", text);
    refused(s,
            "import-digitised --dataset " + s.q(s.data) + " --mapping " + s.q(s.root / "mapping.toml") + " --input " +
                s.q(ex / "fig-a-stream-limits.csv") + " --out " + s.q(s.out),
            2, "mapping.toml:1: nested ");
  }
  // A TOML file in UTF-16 (Windows Notepad's "Unicode") is named as such.
  std::string utf16 = "\xFF\xFE";
  for (char c : setup) utf16 += std::string{c, '\0'};
  write_file(s.data / "setup.toml", utf16);
  refused(s, s.args("validate"), 2, "setup.toml: is UTF-16 text");
}

// Class 2: a name from the data never becomes a path unmapped. Taken as a path, a condition named
// ../../../ds would make `validate --models dem` write its per-condition files into the dataset
// folder (overwriting trajectory.csv); each name is one plain folder under OUT/dem/. The DEM runs come from the
// recorded runs of tests/peer/dem-cache (--dem-cache-only: no run here).
BOOST_AUTO_TEST_CASE(class2_names_are_not_paths) {
  Sandbox s("names");
  const std::string evil = "../../../ds";
  for (const char* f : {"conditions.csv", "measurements.csv", "trajectory.csv"}) s.replace_in(f, "\nV3-41,", "\n" + evil + ",");
  fs::create_directories(s.out);
  const auto r = accepted(s, s.args("validate") + " --models korzen,dem --dem-quality standard --dem-ladder off "
                                                  "--dem-cache-only --dem-cache " + s.q(kSrc / "tests" / "peer" / "dem-cache"));
  BOOST_TEST(fs::is_regular_file(s.out / "dem" / chutelab::file_name_for(evil) / "timeseries.csv"));
  BOOST_TEST(chutelab::file_name_for(evil) == "%2E.%2F..%2F..%2Fds");
  for (const auto& e : fs::directory_iterator(s.out / "dem")) BOOST_TEST(e.path().filename().string().find('/') == std::string::npos);
  // The map is one-to-one and never leaves its folder.
  for (const char* n : {".", "..", "/", "", "a/b", "a\\b", "~", "%", "%25", "\n", "NUL\x01"})
    BOOST_TEST((chutelab::file_name_for(n).find_first_of("/\n") == std::string::npos &&
                chutelab::file_name_for(n) != "." && chutelab::file_name_for(n) != ".." &&
                chutelab::file_name_for(n).front() != '.'));
  BOOST_TEST(chutelab::file_name_for("%") != chutelab::file_name_for("%25"));
  BOOST_TEST(chutelab::file_name_for("a/b") != chutelab::file_name_for("a%2Fb"));
  const std::string long_a(5000, 'a'), long_b = std::string(4999, 'a') + "b";
  BOOST_TEST(chutelab::file_name_for(long_a).size() <= 120u);
  BOOST_TEST(chutelab::file_name_for(long_a) != chutelab::file_name_for(long_b));
}

// Class 3 (the library's side is in tests/python): what the command line refuses, every entry point
// refuses, because the library enforces it; here the command line keeps refusing it, by the same code.
BOOST_AUTO_TEST_CASE(class3_input_protection_is_the_librarys) {
  Sandbox s("protect");
  refused(s, "synthesize --dataset " + s.q(s.data) + " --out " + s.q(s.data), 2, "is the input folder");
  refused(s, "synthesize --dataset " + s.q(s.data) + " --out " + s.q(s.data / "."), 2, "is the input folder");
  // Every command through the same writer: the designer's page and estimate's drawing too.
  refused(s, "design --dataset " + s.q(s.data) + " --out " + s.q(s.data), 2, "is the input folder");
  refused(s, "estimate --dataset " + s.q(s.data) + " --condition V3-41 --svg " + s.q(s.data / "conditions.csv"), 2,
          "--svg: is an input of this run");
}

// Class 4: every catchable signal that ends the process removes the staging folder and exits
// 128 + its number; the staging folder of a process killed by SIGKILL is swept by the next run
// into the same --out, a live process's is left alone.
BOOST_AUTO_TEST_CASE(class4_every_signal_cleans_up) {
  Sandbox s("signals");
  const auto data_before = snapshot(s.data);
  // validate with the DEM stages OUT/dem while its runs go on (one thread: seconds per condition).
  const std::string cmd = s.args("validate") + " --models korzen,dem --dem-quality quick --no-dem-cache --dem-threads 1";
  for (const auto& [sig, name] : {std::pair{SIGHUP, "HUP"}, {SIGQUIT, "QUIT"}, {SIGALRM, "ALRM"}, {SIGXCPU, "XCPU"},
                                  {SIGPIPE, "PIPE"}, {SIGUSR1, "USR1"}, {SIGKILL, "KILL"}}) {
    BOOST_TEST_CONTEXT("SIG" << name) {
      const fs::path rc = s.root / "rc", script = s.root / "signal.sh";
      // --default-signal: a background job of a script starts with some signals ignored.
      write_file(script, "env --default-signal '" + std::string(CHUTELAB_BINARY) + "' " + cmd + " >/dev/null 2>'" +
                             (s.root / "err").string() + "' &\np=$!\n"
                             "i=0; while [ $i -lt 600 ] && ! ls -a '" + s.root.string() + "' | grep -q partial; do sleep 0.05; i=$((i+1)); done\n"
                             "sleep 0.5\nkill -" + name + " $p\nwait $p\necho $? >'" + rc.string() + "'\n");
      BOOST_REQUIRE(std::system(("sh '" + script.string() + "' 2>/dev/null").c_str()) == 0);
      BOOST_TEST(std::stoi(read_file(rc)) == 128 + sig);
      BOOST_TEST((snapshot(s.data) == data_before));
      BOOST_TEST(!fs::exists(s.out));
      if (sig == SIGKILL) {
        // Left by the killed process: the next command into the same --out sweeps it.
        BOOST_TEST(staging_left(s.root));
        const auto r = run_chutelab("estimate --dataset " + s.q(s.data) + " --condition V3-41 --svg " + s.q(s.root / "x.svg"));
        BOOST_TEST(staging_left(s.root));  // another --out: not its business
        const auto v = run_chutelab(s.args("validate"));
        BOOST_TEST(v.exit_code == 0, v.err);
        fs::remove_all(s.out);
      } else {
        const bool said = read_file(s.root / "err").find("nothing was written") != std::string::npos;
        BOOST_TEST((said || sig == SIGPIPE));
      }
      BOOST_TEST(!staging_left(s.root));
    }
  }
  // A staging folder whose process lives (this test's parent shell, say) is not swept; one whose
  // process id is gone is.
  const pid_t dead = fork();
  if (dead == 0) _exit(0);
  waitpid(dead, nullptr, 0);
  const fs::path gone = s.root / fmt::format(".out.partial-{}", dead), alive = s.root / fmt::format(".out.partial-{}", getppid());
  write_file(gone / "report.md", "half\n");
  write_file(alive / "report.md", "in progress\n");
  const auto v = run_chutelab(s.args("validate"));
  BOOST_TEST(v.exit_code == 0, v.err);
  BOOST_TEST(!fs::exists(gone));
  BOOST_TEST(fs::exists(alive / "report.md"));
}

// Class 5: a command owns its output set. validate after validate --diagnose removes the earlier
// diagnosis (it described another run) and says so; files that are not chutelab's stay
// (tests/cli/test_outputs.cpp has the rest: only what chutelab wrote is chutelab's).
BOOST_AUTO_TEST_CASE(class5_earlier_outputs_do_not_survive_as_current) {
  Sandbox s("stale");
  BOOST_REQUIRE(accepted(s, s.args("validate") + " --diagnose").exit_code == 0);
  BOOST_TEST(fs::exists(s.out / "diagnosis.csv"));
  write_file(s.out / "notes.txt", "mine\n");
  const auto r = accepted(s, s.args("validate"));
  BOOST_TEST(!fs::exists(s.out / "diagnosis.csv"));
  BOOST_TEST(!fs::exists(s.out / "diagnosis.md"));
  BOOST_TEST(r.err.find("removed from") != std::string::npos);
  BOOST_TEST(r.err.find("diagnosis.csv, diagnosis.md") != std::string::npos);
  BOOST_TEST(read_file(s.out / "notes.txt") == "mine\n");
  // A synthetic dataset into a folder holding another dataset: no file of the old one is left to be
  // read as part of the new (plate_map.csv, tolerances.toml); as chutelab did not write them, they
  // are not removed either: refused, and left as they are (issue 50, class 2).
  const fs::path synth = s.root / "synth";
  write_file(synth / "plate_map.csv", "stale\n");
  write_file(synth / "tolerances.toml", "[korzen]\n");
  const auto refused_synth = run_chutelab("synthesize --dataset " + s.q(s.data) + " --out " + s.q(synth));
  BOOST_TEST(refused_synth.exit_code == 2);
  BOOST_TEST(refused_synth.err.find("plate_map.csv: --out: chutelab did not write it, and it would be read as part") !=
             std::string::npos, refused_synth.err);
  BOOST_TEST(read_file(synth / "plate_map.csv") == "stale\n");
  BOOST_TEST(read_file(synth / "tolerances.toml") == "[korzen]\n");
  BOOST_TEST(!fs::exists(synth / "measurements.csv"));
}

// Class 6: a check that cannot be computed does not pass. A measured 0 against a relative limit has
// no relative error: the limit fails (exit 1), it is not "within"; a measured 1e-320 does not blank
// the summary's maximum (it is taken over the finite values).
BOOST_AUTO_TEST_CASE(class6_undefined_metrics_do_not_pass) {
  Sandbox s("metrics");
  s.replace_in("measurements.csv", "V3-41,normal_force_N,", "V3-41,normal_force_N,0#");
  {  // the value cell becomes 0 (the old value is cut off at '#')
    std::string m = read_file(s.data / "measurements.csv");
    const auto at = m.find("0#");
    m.replace(at, m.find(',', at) - at, "0");
    write_file(s.data / "measurements.csv", m);
  }
  const fs::path tol = s.root / "tol.toml";
  write_file(tol, "[korzen]\nnormal_force_N = { relative = 0.5 }\n");
  const auto r = accepted(s, s.args("validate") + " --models korzen --tolerances " + s.q(tol), 1);
  BOOST_TEST(r.out.find("ACCEPTANCE FAILED") != std::string::npos);
  const std::string errors = read_file(s.out / "errors.csv");
  BOOST_TEST(errors.find("fail: relative error undefined: the measured value is 0") != std::string::npos);
  // 1e-320: the relative error is infinite; the summary's maximum is over the other conditions.
  s.replace_in("measurements.csv", "V3-41,normal_force_N,0,", "V3-41,normal_force_N,1e-320,");
  accepted(s, s.args("validate") + " --models korzen");
  const std::string summary = read_file(s.out / "summary.csv");
  const auto row = summary.find("korzen,normal_force_N,");
  BOOST_REQUIRE(row != std::string::npos);
  const std::string line = summary.substr(row, summary.find('\n', row) - row);
  BOOST_TEST_INFO(line);
  BOOST_TEST(line.find(",,") == std::string::npos);  // no blank cell
}

// Class 7: work is bounded before it starts. A joint fit of many effects, a calibration of thousands
// of slump tests and too many sensitivity sizes are refused at once, saying why.
BOOST_AUTO_TEST_CASE(class7_unbounded_work_is_refused_before_it_starts) {
  Sandbox s("bounds");
  std::string fits;
  for (const char* e : {"air_drag", "belt_slip", "belt_adhesion", "plate_rebound", "plate_friction", "load_cell_gain"})
    fits += fmt::format(" --effect {}=fit", e);
  refused(s, s.args("validate") + fits, 2, "--effect: 6 effects to fit at once");
  std::string many = "0";
  for (int i = 1; i < 2000; ++i) many += fmt::format(",{}", i * 1e-4);
  refused(s, s.args("calibrate") + " --rolling " + many, 2, "slump tests; at most 100 run in one command");
  refused(s, s.args("sensitivity") + " --sizes 4,5,6,7,8,9,10", 2, "--sizes: 7 values");
  // Big data is drawn summarised: 40 000 stream points make a report of the usual size, not one of
  // a marker each (a million rows made 386 MB; bench/log/SCALE.md has the timings).
  std::string traj = "condition,boundary,x_mm,y_mm,uncertainty_mm\n";
  for (const char* cond : {"V2-26", "V3-41"})
    for (const char* b : {"upper", "lower"})
      for (int k = 0; k < 10000; ++k)
        traj += fmt::format("{},{},{},{},1.0\n", cond, b, 100 + 0.015 * k, 150 - 30 * (b[0] == 'l') - 0.0004 * k);
  write_file(s.data / "trajectory.csv", traj);
  accepted(s, s.args("validate"));
  const std::string html = read_file(s.out / "report.html");
  BOOST_TEST(html.size() < 2'000'000u);
  BOOST_TEST(html.find("measured points drawn; all in trajectory.csv") != std::string::npos);
  BOOST_TEST(html.find("values here, 40 drawn; all in errors.csv") != std::string::npos);
  BOOST_TEST(count_lines(read_file(s.out / "errors.csv")) > 2 * 40000);  // every value in the CSV
}

// Class 8: one validator for every option, before any work: non-finite numbers, out-of-range values,
// duplicates, empty values and wrong types are refused, naming the flag as typed.
BOOST_AUTO_TEST_CASE(class8_every_option_is_checked) {
  Sandbox s("options");
  refused(s, s.args("calibrate") + " --target-pile-height inf", 2, "--target-pile-height: must be a finite number");
  refused(s, s.args("sensitivity") + " --limit nan", 2, "--limit: must be a finite number in [0, 100] %, got 'nan'");
  refused(s, s.args("calibrate") + " --rolling 0.1,0.2,0.1", 2, "--rolling: '0.1' is given twice");
  refused(s, s.args("calibrate") + " --rolling 0.1,,0.2", 2, "--rolling: '0.1,,0.2' has an empty item");
  refused(s, s.args("sensitivity") + " --only ''", 2, "--only: is empty");
  refused(s, s.args("validate") + " --dem-threads 1.5", 2, "--dem-threads: must be a whole number in [0, 256], got '1.5'");
  refused(s, s.args("validate") + " --dem-threads 999", 2, "--dem-threads: must be a whole number in [0, 256]");
  refused(s, s.args("synthesize") + " --seed -1", 2, "--seed: must be a whole number");
  refused(s, s.args("synthesize") + " --noise-scale nan", 2, "--noise-scale: must be a finite number in [0, 100]");
  refused(s, s.args("simulate") + " --condition V3-41 --max-time 1e999", 2, "--max-time: must be a finite number");
  refused(s, "estimate --belt-speed inf --mass-flow 35 --plate-distance 450", 2, "--belt-speed: must be a finite number");
  refused(s, s.args("diagnose") + " --alpha 0", 2, "--alpha: must be a finite number in [1e-06, 0.5], got '0'");
  refused(s, s.args("validate") + " --models korzen,,booth-cema", 2, "--models: model 2 of the list is empty");
  refused(s, s.args("validate") + " --effect air_drag=nan", 2, "--effect: 'air_drag=nan': 'nan' is not a number");
  // A whole number typed as 2.0 is 2.
  BOOST_TEST(run_chutelab(s.args("synthesize") + " --seed 2.0").exit_code == 0);
  fs::remove_all(s.out);
  // setup.toml: a name must be a text.
  s.replace_in("setup.toml", "name = \"liggghts-rig\"", "name = 42");
  refused(s, s.args("validate"), 2, "setup.toml:1: name: must be a text in quotes");
}

// Class 9: every CSV goes through one writer: a name with a comma is quoted (and reads back), a name
// a spreadsheet would run as a formula gets an apostrophe that chutelab's reader removes again.
BOOST_AUTO_TEST_CASE(class9_csv_has_one_writer_and_a_formula_policy) {
  Sandbox s("csv");
  const std::string formula = "=HYPERLINK(\"x\";\"y\")", comma = "V3,41";
  for (const char* f : {"conditions.csv", "measurements.csv", "trajectory.csv"}) {
    s.replace_in(f, "\nV3-41,", "\n\"" + std::string("=HYPERLINK(\"\"x\"\";\"\"y\"\")") + "\",");
    s.replace_in(f, "\nV2-26,", "\n\"V3,41\",");
  }
  accepted(s, s.args("validate"));
  for (const char* f : {"predictions.csv", "errors.csv"}) {
    const std::string t = read_file(s.out / f);
    BOOST_TEST_INFO(f);
    BOOST_TEST(t.find("\n\"'=HYPERLINK(\"\"x\"\";\"\"y\"\")\",") != std::string::npos);
    BOOST_TEST(t.find("\n=") == std::string::npos);
    BOOST_TEST(t.find("\n\"V3,41\",") != std::string::npos);
  }
  // The names read back unchanged: a dataset synthesized from it and validated again.
  const fs::path synth = s.root / "synth";
  BOOST_TEST(run_chutelab("synthesize --dataset " + s.q(s.data) + " --out " + s.q(synth)).exit_code == 0);
  const auto e = run_chutelab("estimate --dataset " + s.q(synth) + " --condition '" + formula + "' --format csv");
  BOOST_TEST(e.exit_code == 0, e.err);
  BOOST_TEST(e.out.find("\n\"'=HYPERLINK(") != std::string::npos);
  const auto v = run_chutelab("validate --dataset " + s.q(synth) + " --out " + s.q(s.root / "v2"));
  BOOST_TEST(v.exit_code == 0, v.err);
  (void)comma;
}

// Class 10: numbers that are read again are written at round-trip precision, and errors are said
// against the user's file. Two digitised points 4.02 in and 4.020001 in apart are two rows (at 6
// digits they would collide and be refused naming a staging file that does not exist); a sweep in
// steps of 1e-13 shows distinct values.
BOOST_AUTO_TEST_CASE(class10_round_trip_precision) {
  Sandbox s("precision");
  const fs::path ex = kSrc / "datasets" / "digitised-example";
  std::string fig = read_file(ex / "fig-a-stream-limits.csv");
  fig += "4.020001,6.0199,,\n";
  write_file(s.root / "fig-a.csv", fig);
  const std::string import = "import-digitised --dataset " + s.q(s.data) + " --mapping " + s.q(ex / "mapping.toml") +
                             " --input " + s.q(s.root / "fig-a.csv") + " --input " + s.q(ex / "fig-b-forces.json") +
                             " --out " + s.q(s.out);
  // The source dataset has these rows already: import into a copy without trajectory and measurements.
  fs::remove(s.data / "trajectory.csv");
  fs::remove(s.data / "measurements.csv");
  accepted(s, import);
  // Both points are rows of their own, at x values that read back as two numbers.
  std::vector<double> xs;
  const std::string traj = read_file(s.out / "trajectory.csv");
  for (std::size_t at = 0; (at = traj.find("\nV3-41,upper,", at)) != std::string::npos; ++at) {
    const double x = std::stod(traj.substr(at + 13));
    if (std::abs(x - 102.108) < 1e-3) xs.push_back(x);
  }
  BOOST_TEST(xs.size() == 2u);
  if (xs.size() == 2) BOOST_TEST(xs[0] != xs[1]);
  // A point the dataset reader refuses after the import (past the plate face) is said against the
  // digitised file and its line, not against a file of the staging folder.
  fs::remove_all(s.out);
  write_file(s.root / "fig-a.csv", read_file(ex / "fig-a-stream-limits.csv") + "30,1,,\n");
  const long line = count_lines(read_file(s.root / "fig-a.csv"));
  refused(s, import, 2, (s.root / "fig-a.csv").string() + ":" + std::to_string(line) + ":");
  // A sweep in steps of 1e-13: 11 distinct values, and a STEP below a double's resolution is refused.
  const auto sw = run_chutelab("estimate --belt-speed 4 --mass-flow 35 --sweep plate_distance=300:300.000000000001:1e-13 "
                               "--format csv");
  BOOST_TEST(sw.exit_code == 0, sw.err);
  std::set<std::string> swept;
  for (std::size_t at = sw.out.find('\n'); at != std::string::npos && at + 1 < sw.out.size(); at = sw.out.find('\n', at + 1))
    swept.insert(sw.out.substr(at + 1, sw.out.find(',', at + 1) - at - 1));
  BOOST_TEST(swept.size() == 11u);
  refused(s, "estimate --belt-speed 4 --mass-flow 35 --sweep plate_distance=300:300.0000000000002:1e-14", 2,
          "is below the resolution of a number near 300");
}

// Class 11: one formatter for values in messages: a 10 MB value is cut and its size said, a NUL and
// UTF-16 are named, a byte-order mark in mid-file is blamed on its own file, and the flag named is the
// one typed.
BOOST_AUTO_TEST_CASE(class11_messages) {
  Sandbox s("messages");
  const std::string big(10 * 1024 * 1024, 'x');
  s.replace_in("measurements.csv", "V3-41,normal_force_N,", "V3-41,normal_force_N," + big + "#");
  {
    std::string m = read_file(s.data / "measurements.csv");
    const auto at = m.find("#");
    m.erase(at, m.find(',', at) - at);
    write_file(s.data / "measurements.csv", m);
  }
  const auto r = refused(s, s.args("validate"), 2, "'xxxx");
  BOOST_TEST(r.err.size() < 1200u);
  BOOST_TEST(r.err.find("(10 MiB)") != std::string::npos);
  for (const auto& f : fs::directory_iterator(kRig)) fs::copy_file(f.path(), s.data / f.path().filename(), fs::copy_options::overwrite_existing);
  // A NUL in conditions.csv.
  s.replace_in("conditions.csv", "V3-41,", std::string("V3-41\0,", 7));
  refused(s, s.args("validate"), 2, "holds a NUL byte");
  fs::copy_file(kRig / "conditions.csv", s.data / "conditions.csv", fs::copy_options::overwrite_existing);
  // conditions.csv saved as UTF-16.
  std::string u16 = "\xFF\xFE";
  for (char c : read_file(kRig / "conditions.csv")) u16 += std::string{c, '\0'};
  write_file(s.data / "conditions.csv", u16);
  refused(s, s.args("validate"), 2, "conditions.csv: is UTF-16 text");
  fs::copy_file(kRig / "conditions.csv", s.data / "conditions.csv", fs::copy_options::overwrite_existing);
  // A byte-order mark before a row of conditions.csv (two files joined): conditions.csv is named,
  // not measurements.csv, whose V3-41 would no longer match.
  s.replace_in("conditions.csv", "\nV3-41,", "\n\xEF\xBB\xBFV3-41,");
  refused(s, s.args("validate"), 2, "conditions.csv:5: holds a byte-order mark");
  fs::copy_file(kRig / "conditions.csv", s.data / "conditions.csv", fs::copy_options::overwrite_existing);
  // A device named as a data file ends at once (the NUL of /dev/zero), not in an out-of-memory.
  fs::remove(s.data / "conditions.csv");
  fs::create_symlink("/dev/zero", s.data / "conditions.csv");
  refused(s, s.args("validate"), 2, "conditions.csv:1: holds a NUL byte");
  fs::remove(s.data / "conditions.csv");
  fs::copy_file(kRig / "conditions.csv", s.data / "conditions.csv");
  // A dataset folder whose name holds a terminal escape is printed escaped (the summary names the
  // folder the user gave, not setup.toml's name).
  const fs::path odd = s.root / "rig\x1b[2J";
  fs::rename(s.data, odd);
  const auto named = run_chutelab("validate --dataset " + s.q(odd) + " --out " + s.q(s.out));
  BOOST_TEST(named.exit_code == 0, named.err);
  BOOST_TEST(named.out.find("rig\\x1b[2J: 8 conditions") != std::string::npos, named.out);
  BOOST_TEST(named.out.find('\x1b') == std::string::npos);
  fs::rename(odd, s.data);
  // Invisible characters in a value are shown, not passed to the terminal.
  const auto esc = refused(s, s.args("validate") + " --models 'korzen\x1b[31m'", 2, "\\x1b[31m");
  BOOST_TEST(esc.err.find('\x1b') == std::string::npos);
}

BOOST_AUTO_TEST_SUITE_END()

// Issue 50 (round four) -----------------------------------------------------------------------------

BOOST_AUTO_TEST_SUITE(round_four)

// Class 13: condition names that print the same are one name to a reader. A quoted trailing space,
// a no-break space, a zero-width space, or an accent spelt precomposed and decomposed (NFC, NFD) made
// two conditions that every table, chart and terminal shows alike.
BOOST_AUTO_TEST_CASE(class13_names_that_print_the_same_are_refused) {
  const std::string row = ",3.0,41.0,400.0,250.0,34.0\n";
  const std::vector<std::pair<std::string, std::string>> twins = {
      {"V3-41", "\"V3-41 \""},                // a quoted trailing space
      {"K 1", "K\xC2\xA0" "1"},                // a no-break space
      {"V3-41", "V3-4\xE2\x80\x8B" "1"},        // a zero-width space
      {"K\xC3\xB6ln", "Ko\xCC\x88ln"},          // o-umlaut precomposed (NFC) and decomposed (NFD)
  };
  for (const auto& [first, second] : twins) {
    Sandbox s("printed");
    std::string conditions = read_file(s.data / "conditions.csv");
    if (first != "V3-41") conditions += first + row;
    conditions += second + row;
    write_file(s.data / "conditions.csv", conditions);
    refused(s, s.args("validate"), 2, "prints the same as");
  }
  // Names that only look related stay apart, and a name of invisible characters alone is none.
  Sandbox s("printed-apart");
  write_file(s.data / "conditions.csv", read_file(s.data / "conditions.csv") + "V3-41b" + row + "V3 41" + row);
  accepted(s, s.args("validate"));
  write_file(s.data / "conditions.csv", read_file(kRig / "conditions.csv") + "\xE2\x80\x8B" + row);
  refused(s, s.args("validate"), 2, "prints as nothing");
}

// Class 9 (the parts outside the diagnosis): --quiet leaves out the diagnosis's progress lines
// (printed for 500 conditions or more), and a self-check says what it may cost before it starts.
BOOST_AUTO_TEST_CASE(class9_quiet_diagnosis_and_a_self_check_estimated) {
  Sandbox s("quiet");
  std::string conditions = "condition,belt_speed_mps,mass_flow_tph,plate_distance_mm,plate_top_mm\n";
  for (int k = 0; k < 500; ++k)
    conditions += fmt::format("C{},{},{},{},250\n", k, 2.0 + 0.006 * k, 26.0 + 0.03 * k, 300 + (k % 5) * 50);
  write_file(s.data / "conditions.csv", conditions);
  fs::remove(s.data / "measurements.csv");
  fs::remove(s.data / "trajectory.csv");
  accepted(s, s.args("synthesize") + " --effect air_drag=0.5");
  const std::string diagnose = "diagnose --no-pairs --dataset " + s.q(s.out) + " --out " + s.q(s.root / "d");
  const auto loud = run_chutelab(diagnose);
  BOOST_TEST(loud.err.find("diagnose: fitting") != std::string::npos, loud.err.substr(0, 2000));
  const auto quiet = run_chutelab(diagnose + " --quiet");
  BOOST_TEST(quiet.exit_code == loud.exit_code);
  BOOST_TEST(quiet.err.find("diagnose:") == std::string::npos, quiet.err.substr(0, 2000));
  // The self-check's cost, said before it starts (the rig's own 8 conditions: a second or two).
  Sandbox r("self-check");
  const auto checked = run_chutelab(r.args("diagnose") + " --no-pairs --self-check 2");
  // Two replicas of each kind (effect-free, the explanation, each rival): at least 2, as many as it runs.
  BOOST_TEST(checked.err.find("self-check of up to ") != std::string::npos, checked.err.substr(0, 2000));
  BOOST_TEST(checked.err.find(" replica diagnoses; this diagnosis took") != std::string::npos, checked.err.substr(0, 2000));
  // ... and the replicas as they finish, the last one included.
  BOOST_TEST(checked.err.find("replicas done") != std::string::npos, checked.err.substr(0, 2000));
  const auto silent = run_chutelab(r.args("diagnose") + " --no-pairs --self-check 2 --quiet");
  BOOST_TEST(silent.err.find("self-check") == std::string::npos, silent.err.substr(0, 2000));
}

// Class 13: a study's numbers are checked as a dataset's: 1e300 particles in calibration.csv was cast
// and printed as -9223372036854775808, and a step count or a steady flag of any value was taken.
BOOST_AUTO_TEST_CASE(class13_study_numbers_are_checked) {
  Sandbox s("studies");
  const fs::path cal = s.root / "cal", sens = s.root / "sens";
  fs::create_directories(cal);
  fs::create_directories(sens);
  std::string c = read_file(kSrc / "bench" / "calibration" / "calibration.csv");
  c.replace(c.find(",803,1,3.32424,"), 15, ",1e300,1,3.32424,");
  write_file(cal / "calibration.csv", c);
  refused(s, s.args("validate") + " --studies " + s.q(cal), 2, "calibration.csv:2: particles: must be a whole number");
  std::string t = read_file(kSrc / "bench" / "sensitivity" / "sensitivity.csv");
  t.replace(t.find(",29869,5086,1,V3-41,"), 20, ",29869,5086,7,V3-41,");
  write_file(sens / "sensitivity.csv", t);
  refused(s, s.args("validate") + " --studies " + s.q(sens), 2, "sensitivity.csv:2: steady: must be 0 or 1");
}

// Class 13: a direction override in a condition name reached the console raw, reordering the line it
// was printed in; the console now shows it escaped, as messages do.
BOOST_AUTO_TEST_CASE(class13_bidi_overrides_are_escaped_on_the_console) {
  Sandbox s("bidi");
  for (const char* f : {"conditions.csv", "measurements.csv", "trajectory.csv"})
    s.replace_in(f, "\nV2-26,", "\nV2-26\xE2\x80\xAE,");
  const auto r = accepted(s, s.args("diagnose"));
  BOOST_TEST(r.out.find("V2-26\\u202e") != std::string::npos, r.out.substr(0, 3000));
  BOOST_TEST(r.out.find("\xE2\x80\xAE") == std::string::npos);
}

// Class 13: the setup's name went into diagnosis.md's title as raw HTML, which a Markdown viewer
// renders (a script, a link); it is now escaped like the report's text.
BOOST_AUTO_TEST_CASE(class13_the_diagnosis_title_escapes_html) {
  Sandbox s("title");
  s.replace_in("setup.toml", "name = \"liggghts-rig\"", "name = \"rig <img src=x onerror=alert(1)> & co\"");
  accepted(s, s.args("diagnose") + " --no-pairs --quiet");
  const std::string md = read_file(s.out / "diagnosis.md");
  BOOST_TEST(md.rfind("# chutelab diagnosis: rig &lt;img src=x onerror=alert(1)&gt; &amp; co\n", 0) == 0, md.substr(0, 200));
  BOOST_TEST(md.find("<img") == std::string::npos);
}

BOOST_AUTO_TEST_SUITE_END()
