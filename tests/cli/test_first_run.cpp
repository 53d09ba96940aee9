// The first run as a newcomer sees it: scripts/run.sh's validate on the bundled datasets/hidden-effect
// (one effect the models lack, air drag; datasets/hidden-effect/HOW-MADE.md) shows the whole loop in
// a few lines, in the quantities' units, and ends with the report's path. A wrongly chosen effect
// gets a note that the data point elsewhere.
#include <boost/test/unit_test.hpp>
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

// Every command the console and the report print as a hint runs as printed: the estimate with the
// effect added, the diagnosis of a plain validation, the fit of a candidate the report names.
BOOST_AUTO_TEST_CASE(every_printed_hint_runs_as_printed) {
  const fs::path root = fresh_dir("first-run-paste");
  const auto added = run_chutelab("validate --dataset '" + kHidden + "' --add-missing --quiet --out '" +
                                  (root / "a").string() + "'");
  BOOST_REQUIRE(added.exit_code == 0);
  run_hints(added.out.substr(added.out.find("In short: ")), 1);
  const auto plain = run_chutelab("validate --dataset '" + kHidden + "' --quiet --out '" + (root / "p").string() + "'");
  BOOST_REQUIRE(plain.exit_code == 0);
  BOOST_TEST(flat(plain.out).find("To see which physical effect would explain it: chutelab validate") !=
             std::string::npos, plain.out);
  run_hints(plain.out.substr(plain.out.find("In short: ")), 1);
  // The report's hint for a candidate not applied (validate --diagnose), read as report.md renders it.
  const auto diagnosed = run_chutelab("validate --dataset '" + kHidden + "' --diagnose --quiet --out '" +
                                      (root / "d").string() + "'");
  BOOST_REQUIRE(diagnosed.exit_code == 0);
  const std::string md = read_file(root / "d" / "report.md");
  const auto at = md.find("To see the models with it: chutelab validate");
  BOOST_REQUIRE_MESSAGE(at != std::string::npos, md.substr(0, 4000));
  std::string rendered;
  for (std::size_t k = at; k < md.size() && md[k] != '\n'; ++k) {
    if (md[k] == '\\' && k + 1 < md.size()) ++k;  // a Markdown escape shows the character after it
    rendered += md[k];
  }
  BOOST_TEST(rendered.find("--effect air_drag=fit") != std::string::npos, rendered);
  run_hints(rendered, 1);
}

BOOST_AUTO_TEST_SUITE_END()
