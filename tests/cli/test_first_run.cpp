// The first run as a newcomer sees it: scripts/run.sh's validate on the bundled datasets/hidden-effect
// (one effect the models lack, air drag; datasets/hidden-effect/HOW-MADE.md) shows the whole loop in
// a few lines, in the quantities' units, and ends with the report's path. A wrongly chosen effect
// gets a note that the data point elsewhere.
#include <algorithm>
#include <boost/test/unit_test.hpp>
#include <fmt/format.h>
#include <set>
#include <cstdlib>
#include <filesystem>
#include <sys/wait.h>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "cli_runner.h"

using namespace chutelab::test;
namespace fs = std::filesystem;

namespace {

const std::string kHidden = std::string(CHUTELAB_SOURCE_DIR) + "/datasets/hidden-effect";
const std::string kStudies = std::string(CHUTELAB_SOURCE_DIR) + "/bench/calibration," + CHUTELAB_SOURCE_DIR +
                             "/bench/sensitivity";

std::vector<std::string> lines_of(const std::string& s) {
  std::vector<std::string> out;
  std::istringstream in(s);
  for (std::string l; std::getline(in, l);) out.push_back(l);
  return out;
}

std::string line_starting(const std::vector<std::string>& lines, const std::string& start) {
  for (const auto& l : lines)
    if (l.starts_with(start)) return l;
  return {};
}

// Wrapped lines joined again, so that a phrase is found wherever the line broke.
std::string flat(std::string s) {
  for (auto& c : s)
    if (c == '\n') c = ' ';
  return s;
}

// "RMS E/u_val 2.05 -> 0.93": the combined figure before and after.
std::pair<double, double> fall(const std::string& text) {
  static const std::regex re(R"(RMS E/u_val ([0-9.]+) -> ([0-9.]+))");
  std::smatch m;
  BOOST_REQUIRE_MESSAGE(std::regex_search(text, m, re), "no 'RMS E/u_val X -> Y' in: " + text);
  return {std::stod(m[1]), std::stod(m[2])};
}

// Every "chutelab COMMAND ..." the text prints, as a command line: the words up to the one that ends
// its sentence or parenthesis.
std::vector<std::string> printed_commands(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(flat(text));
  std::vector<std::string> words;
  for (std::string w; in >> w;) words.push_back(w);
  for (std::size_t i = 0; i < words.size(); ++i) {
    if (words[i] != "chutelab" && words[i] != "(chutelab") continue;
    std::string cmd;
    for (std::size_t j = i + 1; j < words.size(); ++j) {
      std::string w = words[j];
      bool last = false;
      while (!w.empty() && (w.back() == ')' || w.back() == ':' || w.back() == '.' || w.back() == ',' || w.back() == ';')) {
        w.pop_back();
        last = true;
      }
      cmd += (cmd.empty() ? "" : " ") + w;
      if (last) break;
    }
    out.push_back(cmd);
  }
  return out;
}

// Runs every hint of `text` as printed (in a fresh working folder, where the hints' out/ goes).
void run_hints(const std::string& text, std::size_t expected) {
  const auto hints = printed_commands(text);
  BOOST_TEST(hints.size() == expected, text);
  const fs::path cwd = fresh_dir("first-run-hints");
  for (const auto& h : hints) {
    BOOST_TEST_CONTEXT("chutelab " << h) {
      // As a user pastes it: a shell in that folder, `chutelab` being the binary under test.
      const std::string line = "cd '" + cwd.string() + "' && '" + std::string(CHUTELAB_BINARY) + "' " +
                               h + " >out.txt 2>err.txt </dev/null";
      const int status = std::system(line.c_str());
      BOOST_TEST((WIFEXITED(status) && WEXITSTATUS(status) == 0), read_file(cwd / "err.txt"));
    }
  }
}

}  // namespace

BOOST_AUTO_TEST_SUITE(first_run)

BOOST_AUTO_TEST_CASE(the_main_job_shows_the_loop_in_a_few_lines) {
  const fs::path out = fresh_dir("first-run") / "hidden-effect";
  const auto r = run_chutelab("validate --dataset '" + kHidden + "' --add-missing --studies '" + kStudies +
                              "' --out '" + out.string() + "'");
  BOOST_TEST_MESSAGE(r.out);
  BOOST_REQUIRE(r.exit_code == 0);
  // The analytical models print no progress: stderr stays empty.
  BOOST_TEST(r.err.empty(), r.err);
  const auto lines = lines_of(r.out);
  // scripts/run.sh adds two lines (the build, the command): at most 30 in all: a first run a newcomer reads.
  BOOST_TEST(lines.size() + 2 <= 30u);
  // before, what is missing, after with the effect named and its fitted value, the report last.
  BOOST_TEST(lines.front().starts_with("before: hidden-effect: 8 conditions x 2 models; RMS E/u_val"));
  BOOST_TEST(line_starting(lines, "missing: ").find("air_drag") != std::string::npos);
  BOOST_TEST(line_starting(lines, "after:  + air drag (drag coefficient 0.").find(", fitted): hidden-effect: ") !=
             std::string::npos);
  BOOST_TEST(lines.back() == "report: " + (out / "report.html").string());
  // The report is titled by the folder the user gave, not by setup.toml's name (grima2010, the rig).
  const std::string md = read_file(out / "report.md");
  BOOST_TEST(md.starts_with("# chutelab validation report: hidden-effect\n"), md.substr(0, 200));
  BOOST_TEST(read_file(out / "report.html").find("<title>chutelab validation: hidden-effect</title>") !=
             std::string::npos);
  // Every quantity line speaks in per cent or mm, before -> after.
  int quantity_lines = 0;
  for (const auto& l : lines)
    if (l.starts_with("  ") && l.find(" -> ") != std::string::npos) {
      ++quantity_lines;
      BOOST_TEST((l.find(" %") != std::string::npos || l.find(" mm") != std::string::npos), l);
    }
  BOOST_TEST(quantity_lines >= 3);
  // The closing words name the effect and the error's fall, and the fall is real (HOW-MADE.md: the
  // data hold air drag at C_d 0.7 and noise of the stated uncertainties, so with it the RMS is near 1).
  const auto at = r.out.find("In short: ");
  BOOST_REQUIRE(at != std::string::npos);
  const std::string words = flat(r.out.substr(at, r.out.find("\nreport: ") - at));
  BOOST_TEST(words.find("Adding air drag (drag coefficient 0.") != std::string::npos, words);
  const auto [before, after] = fall(words);
  BOOST_TEST(before > 1.5);
  BOOST_TEST(after < 1.2);
  BOOST_TEST(words.find("(chutelab estimate --dataset " + kHidden + " --condition ") != std::string::npos, words);
  BOOST_TEST(words.find(" --effect air_drag=0.") != std::string::npos, words);
  // A unit is never cut from its number at a line break.
  for (const auto& l : lines)
    for (const char* unit : {"% ", "mm ", "m/s", "t/h"}) BOOST_TEST(!l.starts_with(unit), l);
  // Engineering words: no statistic on the console, nor on the report's first screen (its header,
  // verdict and first chart's section); they are under "How sure is this?".
  const std::string first_screen = md.substr(0, md.find("\n## ", md.find("## Where the models fail") + 1));
  for (const char* w : {"chi^2", "χ²", "BIC", " p = ", "p (adjusted", "Bonferroni"}) {
    BOOST_TEST(r.out.find(w) == std::string::npos, w);
    BOOST_TEST(first_screen.find(w) == std::string::npos, w << " in:\n" << first_screen);
  }
  BOOST_TEST(md.find("## How sure is this?") != std::string::npos);
}

// diagnose's verdict, its first paragraph on the console, is in the quantities' words too; the
// statistics follow under "How sure is this?" in diagnosis.md.
BOOST_AUTO_TEST_CASE(the_diagnosis_verdict_carries_no_statistics) {
  const fs::path out = fresh_dir("first-run-diagnose");
  const auto r = run_chutelab("diagnose --dataset '" + kHidden + "' --quiet --out '" + out.string() + "'");
  BOOST_REQUIRE(r.exit_code == 0);
  const std::string verdict = r.out.substr(0, r.out.find("\n\n") == std::string::npos ? r.out.find("\n- ")
                                                                                    : r.out.find("\n\n"));
  BOOST_TEST(verdict.find("air_drag") != std::string::npos, verdict);
  for (const char* w : {"chi^2", "χ²", "BIC", " p = ", "p (adjusted", "Bonferroni"})
    BOOST_TEST(verdict.find(w) == std::string::npos, w << " in: " << verdict);
  BOOST_TEST(read_file(out / "diagnosis.md").find("How sure is this? chi^2 ") != std::string::npos);
}

// A record wrong at one condition (NAME@CONDITION) is that record: the summary says to correct it
// and how to check it, as for the record rig-wide, not to add it as physics.
BOOST_AUTO_TEST_CASE(a_record_at_one_condition_is_said_as_a_record) {
  const fs::path dir = fresh_dir("first-run-record-at");
  const std::string grima = std::string(CHUTELAB_SOURCE_DIR) + "/datasets/grima2010";
  BOOST_REQUIRE(run_chutelab("synthesize --dataset '" + grima + "' --effect belt_speed@V4-41=15 --seed 5 --out '" +
                             (dir / "ds").string() + "'").exit_code == 0);
  const auto r = run_chutelab("validate --dataset '" + (dir / "ds").string() + "' --add-missing --quiet --out '" +
                              (dir / "out").string() + "'");
  BOOST_REQUIRE(r.exit_code == 0);
  const std::string md = read_file(dir / "out" / "report.md");
  BOOST_TEST(md.find("Correcting the recorded belt speed@V4-41") != std::string::npos, md.substr(0, 2000));
  BOOST_TEST(md.find("a tachometer on the belt") != std::string::npos);
  BOOST_TEST(md.find("Adding belt speed@V4-41") == std::string::npos);
}

BOOST_AUTO_TEST_CASE(an_effect_the_data_do_not_point_to_gets_a_note) {
  const fs::path out = fresh_dir("first-run-wrong");
  const auto r = run_chutelab("validate --dataset '" + kHidden + "' --effect belt_slip=fit --quiet --out '" +
                              out.string() + "'");
  BOOST_TEST_MESSAGE(r.out);
  BOOST_REQUIRE(r.exit_code == 0);
  BOOST_TEST(line_starting(lines_of(r.out), "after:  + belt slip (slip fraction ").size() > 0u);
  std::string note;
  for (const auto& l : lines_of(r.out))
    if (l.starts_with("note: ") || (!note.empty() && l.starts_with("      "))) note += l.substr(5);
  BOOST_TEST(note.find("The measurements point to air_drag, not to belt_slip") != std::string::npos, note);
  BOOST_TEST(flat(r.out).find("The measurements point to air drag instead") != std::string::npos);
  // Its hint (validate --add-missing) runs as printed.
  run_hints(r.out.substr(r.out.find("In short: ")), 1);
}

// Every hint runs as printed, on every bundled dataset with measurements and on a rig that fails
// its acceptance: from a plain validation (whose hint is the diagnosis, whose hints are the fits and
// --add-missing, whose hint is the estimate), a diagnosis and the failing rig's runs, every
// "chutelab COMMAND ..." printed on the console, in report.md or in diagnosis.md is pasted into a
// shell as printed and followed in turn. Each exits 0 or 1 (a verdict), never 2 (a hint that is
// wrong) nor anything else.
BOOST_AUTO_TEST_CASE(every_hint_on_the_bundled_datasets_and_a_failing_rig_runs) {
  const fs::path cwd = fresh_dir("hints-everywhere");
  write_file(cwd / "acceptance.toml",
             "[korzen]\nnormal_force_N = { relative = 0.04 }\n[booth-cema]\nimpact_velocity_mps = { relative = 0.04 }\n");
  // The command names, as --help lists them: "chutelab's library" or "chutelab cannot" are prose.
  std::set<std::string> commands;
  {
    const auto help = run_chutelab("--help");
    const auto from = help.out.find("Subcommands:");
    BOOST_REQUIRE(from != std::string::npos);
    for (const auto& l : lines_of(help.out.substr(from)))
      if (l.starts_with("  ") && l.size() > 2 && l[2] != ' ') commands.insert(l.substr(2, l.find(' ', 2) - 2));
    BOOST_REQUIRE(commands.count("validate") && commands.count("estimate") && commands.count("diagnose"));
  }
  // Markdown as it reads: escapes, code spans' backticks and emphasis marks gone.
  auto rendered = [](const std::string& md) {
    std::string o;
    for (std::size_t k = 0; k < md.size(); ++k) {
      if (md[k] == '\\' && k + 1 < md.size()) ++k;
      else if (md[k] == '`' || md[k] == '*') continue;
      o += md[k];
    }
    return o;
  };
  // The folder after --out (relative to cwd), where the run's report.md and diagnosis.md are.
  auto out_of = [&](const std::string& cmd) {
    std::istringstream in(cmd);
    std::vector<std::string> w;
    for (std::string x; in >> x;) w.push_back(x);
    for (std::size_t i = 0; i + 1 < w.size(); ++i)
      if (w[i] == "--out") {
        std::string p = w[i + 1];
        if (p.size() > 1 && p.front() == '\'' && p.back() == '\'') p = p.substr(1, p.size() - 2);
        return fs::path(p).is_absolute() ? fs::path(p) : cwd / p;
      }
    return fs::path();
  };
  const std::string data = std::string(CHUTELAB_SOURCE_DIR) + "/datasets/";
  std::vector<std::string> queue;
  for (const char* d : {"hidden-effect", "hidden-effect-logs", "liggghts-rig", "liggghts-flowbias"})
    queue.push_back(fmt::format("validate --dataset {0}{1} --out seed/{1}", data, d));
  queue.push_back("diagnose --dataset " + data + "liggghts-rig --out seed/diagnose");
  const std::string failing = "validate --dataset " + data + "hidden-effect --tolerances acceptance.toml";
  queue.push_back(failing + " --junit seed/fail.xml --out seed/fail");
  queue.push_back(failing + " --add-missing --junit seed/fail-add.xml --out seed/fail-add");
  queue.push_back(failing + " --effect belt_slip=fit --junit seed/fail-slip.xml --out seed/fail-slip");
  const std::size_t seeds = queue.size();
  std::set<std::string> seen(queue.begin(), queue.end());
  std::vector<std::string> hints;
  for (std::size_t q = 0; q < queue.size() && q < 60; ++q) {
    const std::string cmd = queue[q];
    BOOST_TEST_CONTEXT((q < seeds ? "run: chutelab " : "hint: chutelab ") << cmd) {
      // As a user pastes it: a shell in that folder, `chutelab` being the binary under test.
      const std::string line = "cd '" + cwd.string() + "' && '" + std::string(CHUTELAB_BINARY) + "' " + cmd +
                               " >out.txt 2>err.txt </dev/null";
      const int status = std::system(line.c_str());
      const std::string out = read_file(cwd / "out.txt"), err = read_file(cwd / "err.txt");
      BOOST_TEST((WIFEXITED(status) && (WEXITSTATUS(status) == 0 || WEXITSTATUS(status) == 1)), err);
      std::string text = out + "\n" + err;
      const fs::path dir = out_of(cmd);
      for (const char* f : {"report.md", "diagnosis.md"})
        if (!dir.empty() && fs::exists(dir / f)) text += "\n" + rendered(read_file(dir / f));
      for (const auto& h : printed_commands(text)) {
        // A command name alone is a title ("chutelab estimate: condition V5-44 ..."), not a hint.
        if (h.find(' ') == std::string::npos || !commands.count(h.substr(0, h.find(' ')))) continue;
        if (seen.insert(h).second) {
          queue.push_back(h);
          hints.push_back(h);
        }
      }
    }
  }
  BOOST_TEST_MESSAGE("hints run: " << hints.size() << "\n  " << fmt::format("{}", fmt::join(hints, "\n  ")));
  // The chain reaches each kind of hint: the diagnosis, --add-missing, a candidate's fit, the estimate.
  auto any = [&](const std::string& part) {
    return std::any_of(hints.begin(), hints.end(), [&](const auto& h) { return h.find(part) != std::string::npos; });
  };
  BOOST_TEST(any(" --diagnose "));
  BOOST_TEST(any(" --add-missing "));
  BOOST_TEST(any("=fit "));
  BOOST_TEST(any("estimate --dataset "));
  BOOST_TEST(hints.size() >= 10u);
  BOOST_TEST(queue.size() < 60u);  // the chain ends: no hint prints a new command forever
}

BOOST_AUTO_TEST_SUITE_END()
