// Hostile-but-realistic input, one test per defect class. Every bad input must give exit 2
// (or 1 for a failed acceptance) with one line on stderr naming the file, line and field; no abort
// (134) and no internal error (3); the output folder and every input file byte-identical afterwards;
// no staging (.partial) entry left anywhere near --out.
#include <boost/test/unit_test.hpp>

#include <cstdlib>
#include <fmt/format.h>
#include <filesystem>
#include <algorithm>
#include <map>
#include <tuple>
#include <vector>
#include <string>

#include "cli_runner.h"
#include "tree_snapshot.h"

using namespace chutelab::test;
namespace fs = std::filesystem;

namespace {

const fs::path kRig = fs::path(CHUTELAB_SOURCE_DIR) / "datasets" / "liggghts-rig";

// An earlier validate's --out (its files and the record that chutelab wrote them), made once.
const fs::path& earlier_result() {
  static const fs::path dir = [] {
    const fs::path d = fresh_dir("harden-earlier") / "out";
    const auto r = run_chutelab("validate --dataset '" + kRig.string() + "' --out '" + d.string() + "'");
    BOOST_REQUIRE_MESSAGE(r.exit_code == 0, r.err);
    return d;
  }();
  return dir;
}

// A copy of the bundled LIGGGHTS rig to spoil, and an --out holding an earlier result and a file
// of the user's.
struct Case {
  fs::path root, data, out;
  explicit Case(const std::string& name) {
    root = fresh_dir("harden-" + name);
    data = root / "data";
    out = root / "out";
    fs::create_directories(data);
    for (const auto& f : fs::directory_iterator(kRig)) fs::copy_file(f.path(), data / f.path().filename());
    fs::copy(earlier_result(), out, fs::copy_options::recursive);
    write_file(out / "keep.txt", "not ours\n");
  }
  std::string args(const std::string& cmd) const {
    return cmd + " --dataset '" + data.string() + "' --out '" + out.string() + "'";
  }
};

// Runs and checks the promise for bad input: exit code, one line naming what is given, folders
// untouched, nothing staged left behind.
RunResult expect_refused(const Case& c, const std::string& args, int code, const std::string& says) {
  const auto data_before = snapshot(c.data), out_before = snapshot(c.out);
  const auto r = run_chutelab(args);
  BOOST_TEST_INFO("chutelab " << args << "\nstderr: " << r.err);
  BOOST_TEST(r.exit_code == code);
  BOOST_TEST(count_lines(r.err) == 1);
  BOOST_TEST(r.err.find(says) != std::string::npos);
  BOOST_TEST((snapshot(c.data) == data_before));
  BOOST_TEST((snapshot(c.out) == out_before));
  BOOST_TEST(!staging_left(c.root));
  return r;
}

// Sets cell `col` of the first row starting with `prefix` (e.g. "V3-41," or "V3-41,normal_force_N,");
// returns that row's line number.
long set_cell(const fs::path& f, const std::string& prefix, std::size_t col, const std::string& value) {
  std::string s = read_file(f);
  const auto at = s.find("\n" + prefix) + 1;
  BOOST_REQUIRE(at != 0);
  const auto eol = s.find('\n', at);
  std::vector<std::string> cells;
  const std::string row = s.substr(at, eol - at);
  for (std::size_t p = 0, q = 0; p <= row.size(); p = q + 1) {
    q = row.find(',', p);
    if (q == std::string::npos) q = row.size();
    cells.push_back(row.substr(p, q - p));
  }
  BOOST_REQUIRE(col < cells.size());
  cells[col] = value;
  std::string joined;
  for (std::size_t k = 0; k < cells.size(); ++k) joined += (k ? "," : "") + cells[k];
  s.replace(at, eol - at, joined);
  write_file(f, s);
  return 1 + static_cast<long>(std::count(s.begin(), s.begin() + static_cast<long>(at), '\n'));
}

}  // namespace

BOOST_AUTO_TEST_SUITE(hardening)

// Class 1: inputs that could abort (exit 134) give a clean exit 2 and leave --out as it was.
BOOST_AUTO_TEST_CASE(class1_no_abort_and_out_left_as_it_was) {
  Case c("abort");
  // A folder where an output file goes: an abort half-way would leave a mix and .partial files.
  fs::remove(c.out / "errors.csv");
  fs::create_directories(c.out / "errors.csv");
  expect_refused(c, c.args("validate"), 2, "errors.csv: --out: is a folder where chutelab writes a file");
  fs::remove(c.out / "errors.csv");
  // A file where OUT/dem goes: refused before any DEM run, not after minutes of them.
  write_file(c.out / "dem", "a file\n");
  const auto dem = expect_refused(c, c.args("validate") + " --models korzen,dem --no-dem-cache", 2,
                                  "dem: --out: is a file where chutelab writes a folder");
  BOOST_TEST(dem.err.find("validate: dem") == std::string::npos);  // no run started
  fs::remove(c.out / "dem");
  // A symlink loop as the dataset, as --out and as a file of the dataset.
  fs::create_symlink(c.root / "loop", c.root / "loop");
  expect_refused(c, "validate --dataset '" + (c.root / "loop").string() + "' --out '" + c.out.string() + "'", 2,
                 "loop: cannot read the dataset folder");
  expect_refused(c, "validate --dataset '" + c.data.string() + "' --out '" + (c.root / "loop").string() + "'", 2,
                 "loop: --out: ");
  // An extreme measured value (Korzen's Eq 4 iteration can throw on it; the throw must reach a handler).
  const long line = set_cell(c.data / "measurements.csv", "V3-41,normal_force_N,", 2, "5e307");
  expect_refused(c, c.args("diagnose"), 2, "measurements.csv:" + std::to_string(line) + ": value:");
  expect_refused(c, c.args("validate") + " --effect air_drag=fit", 2, "value: normal_force_N = 5e+307 is beyond");
}

// Ctrl-C (and SIGTERM) in the middle of a run: exit 130/143, --out as it was, nothing staged left.
BOOST_AUTO_TEST_CASE(class1_interrupt_leaves_nothing_behind) {
  Case c("interrupt");
  const auto data_before = snapshot(c.data), out_before = snapshot(c.out);
  // Standard quality: a quick run of one condition ends in about the 2 s the signal waits.
  const std::string simulate =
      "simulate --dataset '" + c.data.string() + "' --condition V3-41 --quality standard --no-cache";
  // validate with the DEM stages OUT/dem while its runs go on (one thread: seconds per condition).
  const std::string validate = "validate --dataset '" + c.data.string() +
                               "' --models korzen,dem --dem-quality quick --no-dem-cache --dem-threads 1";
  for (const auto& [sig, code, cmd] : {std::tuple{"INT", 130, simulate}, {"TERM", 143, simulate}, {"INT", 130, validate}}) {
    BOOST_TEST_CONTEXT(sig << " " << cmd) {
    const fs::path rc = c.root / "rc", script = c.root / "interrupt.sh";
    // The signal arrives mid-run. (env --default-signal: a background job of a script starts with
    // SIGINT ignored, as a user's terminal job does not.)
    write_file(script, "env --default-signal=INT,TERM '" + std::string(CHUTELAB_BINARY) + "' " + cmd +
                           " --out '" + c.out.string() + "' >/dev/null 2>'" +
                           (c.root / "err").string() + "' &\np=$!\nsleep 2\nkill -" + sig + " $p\nwait $p\necho $? >'" +
                           rc.string() + "'\n");
    const std::string shell = "sh '" + script.string() + "'";
    BOOST_REQUIRE(std::system(shell.c_str()) == 0);
    BOOST_TEST(std::stoi(read_file(rc)) == code);
    BOOST_TEST(read_file(c.root / "err").find("nothing was written") != std::string::npos);
    BOOST_TEST((snapshot(c.data) == data_before));
    BOOST_TEST((snapshot(c.out) == out_before));
    BOOST_TEST(!staging_left(c.root));
    }
  }
}

// Class 2: no command overwrites a file it reads.
BOOST_AUTO_TEST_CASE(class2_output_never_overwrites_an_input) {
  Case c("inputs");
  expect_refused(c, "synthesize --dataset '" + c.data.string() + "' --out '" + c.data.string() + "'", 2,
                 "is the input folder");
  // The same folder by another name: a trailing slash, a symlink.
  expect_refused(c, "synthesize --dataset '" + c.data.string() + "' --out '" + c.data.string() + "/.'", 2,
                 "is the input folder");
  fs::create_directory_symlink(c.data, c.root / "alias");
  expect_refused(c, "validate --dataset '" + c.data.string() + "' --out '" + (c.root / "alias").string() + "'", 2,
                 "is the input folder");
  // An output file that is a symlink to the tolerances the command reads.
  write_file(c.root / "tol.toml", "[korzen]\nnormal_force_N = { relative = 0.5 }\n");
  fs::remove(c.out / "summary.csv");
  fs::create_symlink(c.root / "tol.toml", c.out / "summary.csv");
  const auto tol_before = read_file(c.root / "tol.toml");
  expect_refused(c, c.args("validate") + " --tolerances '" + (c.root / "tol.toml").string() + "'", 2,
                 "summary.csv: --out: is a file this command reads");
  BOOST_TEST(read_file(c.root / "tol.toml") == tol_before);
}

// Class 3: acceptance that checked nothing fails and says so.
BOOST_AUTO_TEST_CASE(class3_vacuous_acceptance_fails) {
  Case c("vacuous");
  const fs::path tol = c.root / "tolerances.toml";
  auto check = [&](const std::string& text, const std::string& says, const std::string& models = "korzen,booth-cema") {
    write_file(tol, text);
    const auto data_before = snapshot(c.data);
    const auto r = run_chutelab(c.args("validate") + " --models " + models + " --tolerances '" + tol.string() + "'");
    BOOST_TEST_INFO(text << "\nstderr: " << r.err);
    BOOST_TEST(r.exit_code == 1);
    BOOST_TEST(r.out.find("ACCEPTANCE FAILED") != std::string::npos);
    BOOST_TEST(r.out.find("acceptance passed") == std::string::npos);
    BOOST_TEST(r.err.find(says) != std::string::npos);
    BOOST_TEST((snapshot(c.data) == data_before));
    BOOST_TEST(!staging_left(c.root));
  };
  check("", "no limit in the file, so acceptance checked nothing");
  check("# limits to come\n", "no limit in the file, so acceptance checked nothing");
  check("[dem]\nnormal_force_N = { relative = 0.1 }\n", "dem.normal_force_N: this limit checked no value");
  // Korzen predicts no stream limits: a limit on them checks nothing.
  check("[korzen]\ntrajectory_upper_y_mm = { absolute = 5 }\n", "korzen.trajectory_upper_y_mm: this limit checked no value",
        "korzen");
  // A folder given as the tolerances file is bad input, not an empty acceptance.
  fs::create_directories(c.root / "tolfolder");
  expect_refused(c, c.args("validate") + " --tolerances '" + (c.root / "tolfolder").string() + "'", 2,
                 "tolfolder: --tolerances: is a folder, not a file");
}

// Class 4: values no rig can have are refused where they are written.
BOOST_AUTO_TEST_CASE(class4_nonsense_is_refused) {
  {
    Case c("flow");
    const long line = set_cell(c.data / "conditions.csv", "V3-41,", 2, "1e308");
    expect_refused(c, c.args("validate"), 2, "conditions.csv:" + std::to_string(line) + ": ");
    expect_refused(c, c.args("validate"), 2, "mass_flow_tph: mass flow 1e+308 t/h is beyond any conveyor");
  }
  {
    Case c("speed");
    set_cell(c.data / "conditions.csv", "V3-41,", 1, "3e5");
    expect_refused(c, c.args("validate"), 2, "belt_speed_mps: belt speed 300000 m/s is beyond any conveyor");
  }
  {
    Case c("density");
    std::string s = read_file(c.data / "setup.toml");
    const auto at = s.find("bulk_density_kgm3");
    s.replace(at, s.find('\n', at) - at, "bulk_density_kgm3 = 5000");
    write_file(c.data / "setup.toml", s);
    expect_refused(c, c.args("validate"), 2, "bulk_density_kgm3: bulk density 5000 kg/m^3 is above the solid density");
  }
  {
    // An input uncertainty wider than any rig: u_input must not vanish without a word.
    Case c("input-u");
    write_file(c.data / "setup.toml", read_file(c.data / "setup.toml") + "\n[uncertainty]\nbelt_speed_mps = 5e307\n");
    expect_refused(c, c.args("validate"), 2,
                   "uncertainty.belt_speed_mps: uncertainty 5e+307 is wider than the whole range the input can take (50)");
  }
  {
    Case c("tiny-u");
    std::string m = read_file(c.data / "measurements.csv");
    m += "V3-41,exit_velocity_mps,2.0,1e-300\n";
    write_file(c.data / "measurements.csv", m);
    expect_refused(c, c.args("diagnose"), 2, "uncertainty: uncertainty 1e-300 m/s is below what any instrument states");
  }
  {
    Case c("traj");
    std::string t = read_file(c.data / "trajectory.csv");
    write_file(c.data / "trajectory.csv", t + "V3-41,upper,5000,0,2\n");
    expect_refused(c, c.args("validate"), 2, "x_mm: x = 5000 mm is past the plate face");
    write_file(c.data / "trajectory.csv", t + "V3-41,upper,-20,0,2\n");
    expect_refused(c, c.args("validate"), 2, "x_mm: x = -20 mm is behind the pulley centre");
  }
  {
    // The command line has the same bounds as conditions.csv (otherwise the estimate would print inf).
    Case c("estimate");
    const std::string row = "estimate --dataset '" + c.data.string() + "' --condition V3-41";
    expect_refused(c, row + " --belt-speed 5e307", 2, "--belt-speed: belt speed 5e+307 m/s is beyond any conveyor");
    expect_refused(c, row + " --mass-flow 5e307", 2, "--mass-flow: mass flow 5e+307 t/h is beyond any conveyor");
    expect_refused(c, row + " --sweep belt_speed=1:5e307:1", 2, "--sweep: belt speed 5e+307 m/s is beyond");
  }
  {
    Case c("models");
    expect_refused(c, c.args("validate") + " --models korzen,korzen", 2, "--models: model 'korzen' is listed twice");
  }
}

// Class 5: what is written reads back: RFC 4180 CSV, valid UTF-8 in the report.
BOOST_AUTO_TEST_CASE(class5_outputs_read_back) {
  Case c("readback");
  for (const char* f : {"conditions.csv", "measurements.csv", "trajectory.csv"}) {
    std::string s = read_file(c.data / f);
    for (std::size_t at; (at = s.find("\nV3-41,")) != std::string::npos;) s.replace(at, 7, "\n\"V3,41\",");
    for (std::size_t at; (at = s.find("\nV2-26,")) != std::string::npos;) s.replace(at, 7, "\nK\xF6ln,");
    write_file(c.data / f, s);
  }
  const auto data_before = snapshot(c.data);
  const auto r = run_chutelab(c.args("validate"));
  BOOST_TEST_INFO(r.err);
  BOOST_TEST(r.exit_code == 0);
  BOOST_TEST((snapshot(c.data) == data_before));
  for (const char* f : {"predictions.csv", "errors.csv"}) {
    const std::string s = read_file(c.out / f);
    BOOST_TEST(s.find("\n\"V3,41\",") != std::string::npos);
    BOOST_TEST(s.find("\nV3,41,") == std::string::npos);
    BOOST_TEST(s.find("\nK\xC3\xB6ln,") != std::string::npos);  // Latin-1 read as such, written as UTF-8
  }
  // A dataset made from it is one encoding, UTF-8, throughout.
  const fs::path synth = c.root / "synth";
  const auto sr = run_chutelab("synthesize --dataset '" + c.data.string() + "' --out '" + synth.string() + "'");
  BOOST_TEST(sr.exit_code == 0, sr.err);
  for (const char* f : {"conditions.csv", "measurements.csv", "trajectory.csv"}) {
    BOOST_TEST_INFO(f);
    BOOST_TEST(read_file(synth / f).find("K\xC3\xB6ln") != std::string::npos);
    BOOST_TEST(read_file(synth / f).find("K\xF6ln") == std::string::npos);
  }
  const std::string html = read_file(c.out / "report.html");
  BOOST_TEST(html.find("K\xC3\xB6ln") != std::string::npos);
  BOOST_TEST(html.find("K\xF6ln") == std::string::npos);
  BOOST_TEST(read_file(c.out / "keep.txt") == "not ours\n");
  BOOST_TEST(!staging_left(c.root));
}

// Class 5 in import-digitised: a condition name with a comma is written quoted into the new dataset.
BOOST_AUTO_TEST_CASE(class5_imported_rows_read_back) {
  const fs::path root = fresh_dir("harden-import"), src = root / "grima", ex = fs::path(CHUTELAB_SOURCE_DIR) / "datasets";
  fs::create_directories(src);
  for (const auto& f : fs::directory_iterator(ex / "grima2010")) {
    std::string s = read_file(f.path());
    if (f.path().extension() == ".csv")
      for (std::size_t at; (at = s.find("\nV3-41,")) != std::string::npos;) s.replace(at, 7, "\n\"V3,41\",");
    write_file(src / f.path().filename(), s);
  }
  std::string mapping = read_file(ex / "digitised-example" / "mapping.toml");
  for (std::size_t at; (at = mapping.find("\"V3-41\"")) != std::string::npos;) mapping.replace(at, 7, "\"V3,41\"");
  write_file(root / "mapping.toml", mapping);
  const auto r = run_chutelab("import-digitised --dataset '" + src.string() + "' --mapping '" + (root / "mapping.toml").string() +
                              "' --input '" + (ex / "digitised-example" / "fig-a-stream-limits.csv").string() +
                              "' --input '" + (ex / "digitised-example" / "fig-b-forces.json").string() + "' --out '" +
                              (root / "new").string() + "'");
  BOOST_TEST(r.exit_code == 0, r.err);
  BOOST_TEST(read_file(root / "new" / "trajectory.csv").find("\n\"V3,41\",upper,") != std::string::npos);
  BOOST_TEST(read_file(root / "new" / "measurements.csv").find("\n\"V3,41\",normal_force_N,") != std::string::npos);
  const auto v = run_chutelab("validate --dataset '" + (root / "new").string() + "' --out '" + (root / "v").string() + "'");
  BOOST_TEST(v.exit_code == 0, v.err);
  BOOST_TEST(!staging_left(root));
}

// Class 6: the message points at the real problem.
BOOST_AUTO_TEST_CASE(class6_messages_point_the_right_way) {
  Case c("messages");
  const std::string cond = read_file(c.data / "conditions.csv");
  std::string semi = cond;
  for (char& ch : semi)
    if (ch == ',') ch = ';';
  write_file(c.data / "conditions.csv", semi);
  expect_refused(c, c.args("validate"), 2, "the header is separated by semicolons, not commas");
  std::string cr = cond;
  for (char& ch : cr)
    if (ch == '\n') ch = '\r';
  write_file(c.data / "conditions.csv", cr);
  expect_refused(c, c.args("validate"), 2, "lines end with CR only");
  write_file(c.data / "conditions.csv", cond);
  fs::rename(c.data / "trajectory.csv", c.root / "t.csv");
  fs::create_directories(c.data / "trajectory.csv");
  expect_refused(c, c.args("validate"), 2, "trajectory.csv: is a folder, not a file");
  fs::remove(c.data / "trajectory.csv");
  fs::rename(c.root / "t.csv", c.data / "trajectory.csv");

  expect_refused(c, c.args("valdate"), 2, "did you mean 'validate'?");
  expect_refused(c, c.args("validate") + " --modles korzen", 2, "did you mean --models?");
  // The typo is named first, not what it caused ("--dataset is required").
  const auto typo = expect_refused(c, "validate --datset '" + c.data.string() + "' --out '" + c.out.string() + "'", 2,
                                   "validate: unknown option --datset; did you mean --dataset?");
  BOOST_TEST(typo.err.find("required") == std::string::npos);

  const std::string setup = read_file(c.data / "setup.toml");
  write_file(c.data / "setup.toml", setup + "\n[materal]\nfriction_plate = 0.3\n");
  expect_refused(c, c.args("validate"), 2, "materal: unknown table [materal]");
  write_file(c.data / "setup.toml", setup);

  // The same bad condition: diagnose names the same file and line as validate (plate_distance_mm
  // inside the pulley: the models refuse the condition after reading).
  fs::remove(c.data / "trajectory.csv");  // its points would be refused first, past the moved plate
  const long line_no = set_cell(c.data / "conditions.csv", "V3-41,", 3, "50");
  const std::string where = "conditions.csv:" + std::to_string(line_no) + ": plate_distance_mm";
  const auto v = expect_refused(c, c.args("validate"), 2, where);
  const auto d = expect_refused(c, c.args("diagnose"), 2, where);
  BOOST_TEST(v.err == d.err);
}

// Class 8: a big dataset is summarised in the report rather than drawn condition by condition (the
// linear cost is measured in bench/log/SCALE.md, not timed here).
BOOST_AUTO_TEST_CASE(class8_big_datasets_are_summarised) {
  Case c("big");
  std::string cond = "condition,belt_speed_mps,mass_flow_tph,plate_distance_mm,plate_top_mm\n";
  std::string meas = "condition,quantity,value,uncertainty\n";
  for (int i = 0; i < 150; ++i) {
    const double v = 2.0 + 3.0 * (i % 30) / 29.0, f = 20.0 + (i / 30) * 5.0;
    cond += fmt::format("C{},{:.4f},{:.2f},400,250\n", i, v, f);
    meas += fmt::format("C{},normal_force_N,{:.4f},0.1\n", i, 0.25 * v * f);
  }
  write_file(c.data / "conditions.csv", cond);
  write_file(c.data / "measurements.csv", meas);
  fs::remove(c.data / "trajectory.csv");
  const auto data_before = snapshot(c.data);
  const auto r = run_chutelab(c.args("validate"));
  BOOST_TEST_INFO(r.err);
  BOOST_TEST(r.exit_code == 0);
  BOOST_TEST((snapshot(c.data) == data_before));
  const std::string md = read_file(c.out / "report.md");
  BOOST_TEST(md.find("Shown: the 60 conditions of largest misfit") != std::string::npos);
  BOOST_TEST(md.find("90 more are in predictions.csv and errors.csv") != std::string::npos);
  BOOST_TEST(count_lines(read_file(c.out / "errors.csv")) == 1 + 2 * 150);  // every value, both models
}

BOOST_AUTO_TEST_SUITE_END()
