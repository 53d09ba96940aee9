// What commands write, and only that: one test per class of defect in outputs, through the real
// binary as a user runs it. A command replaces or removes only what chutelab wrote (the folder's
// record, OUT/.chutelab-manifest); outputs are placed all together or not at all, on any file
// system; messages name what the user gave.
#include <boost/test/unit_test.hpp>

#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fmt/format.h>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "cli_runner.h"
#include "tree_snapshot.h"

using namespace chutelab::test;
namespace fs = std::filesystem;

namespace {

const fs::path kSrc = CHUTELAB_SOURCE_DIR;
const fs::path kRig = kSrc / "datasets" / "liggghts-rig";
const fs::path kDemCache = kSrc / "tests" / "peer" / "dem-cache";

// A copy of the bundled LIGGGHTS rig and an --out beside it.
struct Sandbox {
  fs::path root, data, out;
  explicit Sandbox(const std::string& name) {
    root = fresh_dir("outputs-" + name);
    data = root / "data";
    out = root / "out";
    fs::create_directories(data);
    for (const auto& f : fs::directory_iterator(kRig)) fs::copy_file(f.path(), data / f.path().filename());
  }
  static std::string q(const fs::path& p) { return fmt::format("'{}'", p.string()); }
  std::string args(const std::string& cmd, const fs::path& to = {}) const {
    return cmd + " --dataset " + q(data) + " --out " + q(to.empty() ? out : to);
  }
};

RunResult ok(const std::string& args, int code = 0) {
  const auto r = run_chutelab(args);
  BOOST_TEST(r.exit_code == code, "chutelab " << args.substr(0, 300) << "\nstderr: " << r.err.substr(0, 2000));
  return r;
}

// The promise for a refusal: exit 2, one line saying `says`, nothing changed under `root`.
RunResult refused(const fs::path& root, const std::string& args, const std::string& says) {
  const auto before = snapshot(root);
  const auto r = run_chutelab(args);
  BOOST_TEST_INFO("chutelab " << args.substr(0, 300) << "\nstderr: " << r.err.substr(0, 2000));
  BOOST_TEST(r.exit_code == 2);
  BOOST_TEST(count_lines(r.err) == 1);
  BOOST_TEST(r.err.find(says) != std::string::npos);
  BOOST_TEST((snapshot(root) == before));
  BOOST_TEST(!staging_left(root));
  return r;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(outputs)

// Issue 50, class 2: a command removes or replaces only what chutelab wrote. Ownership by name
// removed a user's own dem/ folder from --out, a tolerances.toml of theirs when synthesizing into
// it, and `diagnose` into the folder of a `validate` removed its report (docs/diagnosis.md's own
// walk-through does exactly that).
BOOST_AUTO_TEST_CASE(class2_only_what_chutelab_wrote_is_removed) {
  Sandbox s("owned");
  // The user's own dem/ folder and notes inside --out: validate without the DEM leaves them.
  write_file(s.out / "dem" / "mine.txt", "my notes\n");
  write_file(s.out / "notes.txt", "mine\n");
  ok(s.args("validate"));
  BOOST_TEST(read_file(s.out / "dem" / "mine.txt") == "my notes\n");
  BOOST_TEST(read_file(s.out / "notes.txt") == "mine\n");
  BOOST_TEST(fs::exists(s.out / "report.html"));
  BOOST_TEST(fs::is_regular_file(s.out / ".chutelab-manifest"));
  // docs/diagnosis.md: validate, then diagnose into the same folder. The report stays.
  const auto report = read_file(s.out / "report.md");
  const auto d = ok(s.args("diagnose"));
  BOOST_TEST(read_file(s.out / "report.md") == report);
  for (const char* f : {"report.html", "predictions.csv", "errors.csv", "summary.csv", "diagnosis.md", "diagnosis.csv"})
    BOOST_TEST(fs::exists(s.out / f), f);
  BOOST_TEST(d.err.find("removed") == std::string::npos, d.err);
  // An earlier run of the same command: what it wrote and this run does not is removed, and said.
  ok(s.args("validate") + " --diagnose");
  const auto again = ok(s.args("validate"));
  BOOST_TEST(!fs::exists(s.out / "diagnosis.csv"));
  BOOST_TEST(!fs::exists(s.out / "diagnosis.md"));
  BOOST_TEST(again.err.find("removed from") != std::string::npos);
  BOOST_TEST(again.err.find("diagnosis.csv, diagnosis.md") != std::string::npos, again.err);
  // ... unless the user changed it since: then it is theirs, kept, and said.
  ok(s.args("validate") + " --diagnose");
  write_file(s.out / "diagnosis.md", read_file(s.out / "diagnosis.md") + "\nmy comment\n");
  const auto kept = ok(s.args("validate"));
  BOOST_TEST(read_file(s.out / "diagnosis.md").find("my comment") != std::string::npos);
  BOOST_TEST(!fs::exists(s.out / "diagnosis.csv"));
  BOOST_TEST(kept.err.find("kept") != std::string::npos, kept.err);
  // A file of the user's where chutelab would write one is refused, not overwritten: the user's
  // report.md in a new folder, and the diagnosis.md they edited (no longer chutelab's).
  const fs::path mine = s.root / "mine";
  write_file(mine / "report.md", "my report\n");
  refused(s.root, s.args("validate", mine), "report.md: --out: chutelab did not write it");
  refused(s.root, s.args("validate", s.out) + " --diagnose", "diagnosis.md: --out: chutelab did not write it");
  fs::remove(s.out / "diagnosis.md");
  // A file chutelab wrote, edited by the user, is refused as changed.
  write_file(s.out / "summary.csv", read_file(s.out / "summary.csv") + "x\n");
  refused(s.root, s.args("validate"), "summary.csv: --out: was changed since chutelab wrote it");
  fs::remove(s.out / "summary.csv");
  // A copy of a chutelab file (another time, the same bytes) is still chutelab's.
  ok(s.args("validate"));
  const std::string errors = read_file(s.out / "errors.csv");
  fs::remove(s.out / "errors.csv");
  write_file(s.out / "errors.csv", errors);
  ok(s.args("validate"));
  // A tolerances.toml of the user's in the folder synthesize writes a dataset into: it would be read
  // as part of the new dataset, and it is not chutelab's to remove: refused, left as it is.
  const fs::path synth = s.root / "synth";
  write_file(synth / "tolerances.toml", "[korzen]\nnormal_force_N = { relative = 0.1 }\n");
  refused(s.root, "synthesize --dataset " + s.q(s.data) + " --out " + s.q(synth),
          "tolerances.toml: --out: chutelab did not write it, and it would be read as part of what synthesize writes");
  // Without it, a dataset; synthesized again over its own earlier one, replaced.
  fs::remove(synth / "tolerances.toml");
  ok("synthesize --dataset " + s.q(s.data) + " --out " + s.q(synth));
  const std::string first = read_file(synth / "measurements.csv");
  ok("synthesize --dataset " + s.q(s.data) + " --out " + s.q(synth) + " --seed 2");
  BOOST_TEST(read_file(synth / "measurements.csv") != first);
  // A record naming a file outside the folder (the manifest is a text file anyone may edit) reaches
  // nothing outside it.
  const std::string keep = "keep me\n";
  write_file(s.root / "outside.txt", keep);
  std::uint64_t h = 1469598103934665603ull;  // the manifest's FNV-1a, so that only the path is wrong
  for (unsigned char c : keep) h = (h ^ c) * 1099511628211ull;
  write_file(s.out / ".chutelab-manifest", read_file(s.out / ".chutelab-manifest") +
                                                fmt::format("file\tvalidate\t{}\t0\t{:016x}\t../outside.txt\n"
                                                            "file\tvalidate\t{}\t0\t{:016x}\t{}\n",
                                                            keep.size(), h, keep.size(), h,
                                                            (s.root / "outside.txt").string()));
  ok(s.args("validate") + " --models korzen");
  BOOST_TEST(read_file(s.root / "outside.txt") == "keep me\n");
  BOOST_TEST(!staging_left(s.root));
}

// Class 2 inside a folder: the DEM's per-condition files are chutelab's, a file the user put among
// them is not. validate with the DEM (its runs from the recorded cache of tests/peer: no run here),
// then without: chutelab's files under dem/ go, the user's stays with its folder.
BOOST_AUTO_TEST_CASE(class2_a_users_file_inside_chutelabs_folder_stays) {
  Sandbox s("dem-folder");
  const std::string dem = " --models korzen,dem --dem-quality standard --dem-ladder off --dem-cache-only --dem-cache " +
                          Sandbox::q(kDemCache);
  // The user's own dem/ folder: chutelab adds its files and leaves the user's.
  write_file(s.out / "dem" / "mine.txt", "my notes\n");
  ok(s.args("validate") + dem);
  BOOST_TEST(fs::is_regular_file(s.out / "dem" / "V3-41" / "timeseries.csv"));
  BOOST_TEST(read_file(s.out / "dem" / "mine.txt") == "my notes\n");
  write_file(s.out / "dem" / "V3-41" / "theirs.txt", "also mine\n");
  const auto r = ok(s.args("validate"));
  BOOST_TEST(r.err.find("dem/ (") != std::string::npos, r.err);
  BOOST_TEST(read_file(s.out / "dem" / "mine.txt") == "my notes\n");
  BOOST_TEST(read_file(s.out / "dem" / "V3-41" / "theirs.txt") == "also mine\n");
  BOOST_TEST(!fs::exists(s.out / "dem" / "V3-41" / "timeseries.csv"));
  BOOST_TEST(!fs::exists(s.out / "dem" / "V2-26"));  // a folder chutelab made, now empty: gone
  BOOST_TEST(!staging_left(s.root));
}

// Class 7: outputs are all or nothing. --svg and --dxf naming one file were both written (the second
// over the first); an export that could not be written ended in exit 2 ("nothing written") after the
// others had been written, and a --junit that could not be written did so after --out was filled.
BOOST_AUTO_TEST_CASE(class7_outputs_are_placed_together_or_not_at_all) {
  Sandbox s("together");
  const std::string est = "estimate --dataset " + Sandbox::q(s.data) + " --condition V3-41";
  auto q = [&](const char* f) { return Sandbox::q(s.root / f); };
  // One file for two flags: refused, naming both.
  refused(s.root, est + " --svg " + q("d.out") + " --dxf " + q("d.out"), "d.out: --dxf: is also the file of --svg");
  // The last export cannot be written (a folder in its way): none is.
  fs::create_directories(s.root / "p.csv");
  refused(s.root, est + " --svg " + q("a.svg") + " --dxf " + q("a.dxf") + " --points " + q("p.csv"),
          "p.csv: --points: is a folder");
  // ... nor when the folder of the last one cannot be made (a file where it must be).
  write_file(s.root / "file", "x\n");
  refused(s.root, est + " --svg " + q("a.svg") + " --points " + Sandbox::q(s.root / "file" / "p.csv"), "--points: ");
  // Each in place when all can be, a new folder made for one.
  ok(est + " --svg " + q("a.svg") + " --dxf " + q("a.dxf") + " --points " + Sandbox::q(s.root / "new" / "p.csv"));
  BOOST_TEST(read_file(s.root / "a.svg").find("<svg") != std::string::npos);
  BOOST_TEST(read_file(s.root / "a.dxf").find("SECTION") != std::string::npos);
  BOOST_TEST(read_file(s.root / "new" / "p.csv").find("x_mm") != std::string::npos);
  // validate --junit that cannot be written: --out is not made, and the message names --junit.
  refused(s.root, s.args("validate") + " --junit " + Sandbox::q(s.root / "file" / "junit.xml"), "--junit: ");
  BOOST_TEST(!fs::exists(s.out));
  // ... nor changed when it holds an earlier run.
  ok(s.args("validate") + " --diagnose");
  refused(s.root, s.args("validate") + " --junit " + Sandbox::q(s.root / "file" / "junit.xml"), "--junit: ");
  BOOST_TEST(fs::exists(s.out / "diagnosis.md"));
  // --junit inside --out (the CI guide's layout) is the user's file, replaced run after run.
  ok(s.args("validate") + " --junit " + Sandbox::q(s.out / "junit.xml"));
  ok(s.args("validate") + " --junit " + Sandbox::q(s.out / "junit.xml"));
  BOOST_TEST(read_file(s.out / "junit.xml").find("<testsuites") != std::string::npos);
  // ... but never a file --out gets from the run.
  refused(s.root, s.args("validate") + " --junit " + Sandbox::q(s.out / "summary.csv"), "--junit: ");
  BOOST_TEST(!staging_left(s.root));
}

namespace {
// Runs a shell script; its exit status.
int sh(const fs::path& dir, const std::string& script) {
  write_file(dir / "script.sh", script);
  const int status = std::system(("sh '" + (dir / "script.sh").string() + "' >'" + (dir / "script.out").string() +
                                  "' 2>&1").c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}
}  // namespace

// Class 12: an --out on another file system (here a link to one, /dev/shm) or a mount point ended in
// "Invalid cross-device link", and so did a --junit or --svg there; the staging folder now lies on
// --out's own file system, and a move that still crosses one (a mount point inside --out) is a copy
// renamed into place.
BOOST_AUTO_TEST_CASE(class12_outputs_on_another_file_system) {
  Sandbox s("devices");
  struct stat a {}, b {};
  const fs::path shm = fs::path("/dev/shm") / fmt::format("chutelab-test-{}", ::getpid());
  std::error_code ec;
  fs::create_directories(shm / "out", ec);
  if (ec || ::stat(s.root.c_str(), &a) != 0 || ::stat(shm.c_str(), &b) != 0 || a.st_dev == b.st_dev) {
    BOOST_TEST_MESSAGE("no second file system at /dev/shm: the cross-device part is not run");
  } else {
    fs::create_directory_symlink(shm, s.root / "shm");
    const fs::path link = s.root / "shm";
    ok(s.args("validate", link / "out") + " --junit " + Sandbox::q(link / "junit.xml"));
    BOOST_TEST(fs::exists(shm / "out" / "report.html"));
    BOOST_TEST(read_file(shm / "junit.xml").find("<testsuites") != std::string::npos);
    ok("estimate --dataset " + Sandbox::q(s.data) + " --condition V3-41 --svg " + Sandbox::q(link / "x.svg") +
       " --dxf " + Sandbox::q(s.root / "x.dxf"));
    BOOST_TEST(fs::exists(shm / "x.svg"));
    BOOST_TEST(fs::exists(s.root / "x.dxf"));
    // --out on this disk, the --junit file on the other: placed across.
    ok(s.args("validate") + " --junit " + Sandbox::q(link / "j2.xml"));
    BOOST_TEST(fs::exists(shm / "j2.xml"));
    BOOST_TEST(!staging_left(shm));
  }
  fs::remove_all(shm, ec);
  // A mount point as --out, and one inside it (OUT/dem), in a mount namespace of a user namespace
  // (no root needed; skipped where the kernel allows none).
  const fs::path mnt = s.root / "mnt";
  fs::create_directories(mnt / "dem");
  const int probe = sh(s.root, "unshare --user --map-root-user --mount sh -c 'mount -t tmpfs none " + mnt.string() + "'");
  if (probe != 0) {
    BOOST_TEST_MESSAGE("no user namespaces here: the mount-point part is not run");
  } else {
    const std::string dem = " --models korzen,dem --dem-quality standard --dem-ladder off --dem-cache-only --dem-cache " +
                            Sandbox::q(kDemCache);
    const int rc = sh(s.root,
                      "unshare --user --map-root-user --mount sh -e -c '"
                      "mount -t tmpfs none \"" + mnt.string() + "\"; mkdir \"" + (mnt / "dem").string() + "\"; "
                      "mount -t tmpfs none \"" + (mnt / "dem").string() + "\"; " +
                      "\"" + CHUTELAB_BINARY + "\" validate --dataset \"" + s.data.string() + "\" --out \"" +
                      mnt.string() + "\"" + dem + "; "
                      "test -f \"" + (mnt / "report.html").string() + "\"; "
                      "test -f \"" + (mnt / "dem" / "V3-41" / "timeseries.csv").string() + "\"; "
                      "\"" + CHUTELAB_BINARY + "\" validate --dataset \"" + s.data.string() + "\" --out \"" +
                      mnt.string() + "\"; "
                      "test ! -e \"" + (mnt / "dem" / "V3-41").string() + "\"; "
                      "! ls -a \"" + mnt.string() + "\" \"" + (mnt / "dem").string() + "\" | grep partial'");
    BOOST_TEST(rc == 0, read_file(s.root / "script.out"));
  }
}

// Class 12: a result that cannot reach its reader is no success: `estimate > /dev/full` exited 0.
BOOST_AUTO_TEST_CASE(class12_a_failed_write_to_stdout_fails) {
  const fs::path dir = fresh_dir("outputs-stdout");
  const std::string bin = std::string("'") + CHUTELAB_BINARY + "'";
  if (!fs::exists("/dev/full")) return;
  for (const char* fmt_ : {"table", "json", "csv"}) {
    const int rc = sh(dir, bin + " estimate --belt-speed 4 --mass-flow 35 --plate-distance 450 --format " + fmt_ +
                               " >/dev/full");
    BOOST_TEST(rc == 2, fmt_);
    BOOST_TEST(read_file(dir / "script.out").find("chutelab: standard output: cannot write the results") !=
               std::string::npos, read_file(dir / "script.out"));
  }
  Sandbox s("stdout");
  BOOST_TEST(sh(dir, bin + " " + s.args("validate") + " >/dev/full") == 2);
}

// Class 12: a message names the flag the user gave (an --input's problems were said as --effect's,
// a --junit's or --dxf's as --out's), and the documented end of a range is inside it (-0.9 for a
// gain error whose range is [-0.3, 0.3] widened by its span was refused as below
// -0.8999999999999999).
BOOST_AUTO_TEST_CASE(class12_messages_name_what_was_given) {
  Sandbox s("flags");
  refused(s.root, s.args("validate") + " --input plate_angle=abc", "--input: 'plate_angle=abc': 'abc' is not a number");
  refused(s.root, s.args("validate") + " --input plate_angle=1 --input plate_angle=2", "--input: plate_angle given twice");
  refused(s.root, s.args("synthesize") + " --input plate_angle=fit", "--input: 'plate_angle=fit': fitting needs");
  refused(s.root, s.args("synthesize") + " --input plate_angle=1e6", "--input: 'plate_angle=1e6'");
  write_file(s.root / "file", "x\n");
  const auto j = refused(s.root, s.args("validate") + " --junit " + Sandbox::q(s.root / "file" / "j.xml"), "--junit: ");
  BOOST_TEST(j.err.find("--out") == std::string::npos, j.err);
  const auto d = refused(s.root, "estimate --belt-speed 4 --mass-flow 35 --plate-distance 450 --dxf " +
                                     Sandbox::q(s.root / "file" / "d.dxf"), "--dxf: ");
  BOOST_TEST(d.err.find("--out") == std::string::npos, d.err);
  // The ends of the widened range, as its message states them.
  refused(s.root, s.args("synthesize") + " --effect load_cell_gain=-0.91 --allow-out-of-range", "must lie in [-0.9, 0.9]");
  ok(s.args("synthesize") + " --effect load_cell_gain=-0.9 --allow-out-of-range");
  ok(s.args("synthesize") + " --effect load_cell_gain=0.9 --allow-out-of-range");
}

// A diagnosis (asked for by --effect, --input, --add-missing or --diagnose) needs an analytical model:
// with the DEM alone, validate is refused before its baseline runs, not after (an empty cache with
// --dem-cache-only makes a run an error of its own, so the refusal must name the models instead).
BOOST_AUTO_TEST_CASE(a_diagnosis_without_an_analytical_model_is_refused_before_any_run) {
  Sandbox s("dem-only");
  const fs::path empty = s.root / "empty-cache";
  fs::create_directories(empty);
  const std::string dem = " --models dem --dem-quality standard --dem-cache-only --dem-cache " + Sandbox::q(empty);
  for (const std::string asked : {" --effect air_drag=0.5", " --input belt_speed=fit", " --add-missing", " --diagnose"})
    refused(s.root, s.args("validate") + dem + asked, "the diagnosis needs an analytical model in --models");
}

// A record wrong at one condition, as the diagnosis names it (plate_distance@V3-41), is an input of
// its own: it corrects that condition's station and no other; an unknown condition or a physical
// effect at one condition is refused.
BOOST_AUTO_TEST_CASE(a_record_at_one_condition_is_an_input) {
  Sandbox s("at-condition");
  refused(s.root, s.args("validate") + " --input plate_distance@V9-99=10", "--input: 'plate_distance@V9-99=10': no condition is named V9-99");
  refused(s.root, s.args("validate") + " --effect air_drag@V3-41=0.3", "only a recorded input can be wrong at one condition");
  refused(s.root, s.args("validate") + " --input plate_distance@V3-41=-1e4", "--input: 'plate_distance@V3-41=-1e4'");
  ok(s.args("synthesize", s.root / "plain") + " --seed 5");
  ok(s.args("synthesize", s.root / "moved") + " --seed 5 --input plate_distance@V3-41=60");
  const auto plain = read_file(s.root / "plain" / "measurements.csv"), moved = read_file(s.root / "moved" / "measurements.csv");
  std::istringstream a(plain), b(moved);
  std::set<std::string> differ;
  for (std::string x, y; std::getline(a, x) && std::getline(b, y);)
    if (x != y) differ.insert(x.substr(0, x.find(',')));
  BOOST_TEST((differ == std::set<std::string>{"V3-41"}), plain << "\n---\n" << moved);
  ok(s.args("validate", s.root / "v") + " --input plate_distance@V3-41=60");
}

BOOST_AUTO_TEST_SUITE_END()
