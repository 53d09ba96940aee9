#include "api/validate.h"

#include <algorithm>
#include <cctype>
#include <string_view>
#include <fmt/format.h>

#include "core/input_error.h"
#include "reports/plain_summary.h"
#include "validation/failed_values.h"

namespace chutelab::api {
namespace {

// A unit after its number ("8.0 %", "4 m/s,"): kept on the number's line, where a reader looks for it.
bool is_unit(const std::string& word) {
  const std::string bare = word.substr(0, word.find_last_not_of(",.;:)") + 1);
  for (const char* u : {"%", "mm", "m/s", "t/h", "N", "m", "s", "kg", "kg/m³"})
    if (bare == u) return true;
  return false;
}

// Words to lines of at most `width` characters, each after the first indented.
std::string wrap(const std::string& text, std::size_t width, const std::string& first, const std::string& indent) {
  std::vector<std::string> words;
  for (std::size_t at = 0; at < text.size();) {
    const std::size_t end = std::min(text.find(' ', at), text.size());
    std::string word = text.substr(at, end - at);
    at = end + 1;
    if (word.empty()) continue;
    if (!words.empty() && is_unit(word) && std::isdigit(static_cast<unsigned char>(words.back().back())))
      words.back() += " " + word;
    else
      words.push_back(std::move(word));
  }
  std::string out, line = first;
  bool empty = true;
  for (const auto& word : words) {
    if (!empty && line.size() + 1 + word.size() > width) {
      out += line + "\n";
      line = indent;
      empty = true;
    }
    line += (empty ? "" : " ") + word;
    empty = false;
  }
  return out + line + "\n";
}

// The acceptance in one line of its own, after everything else: what decides the exit code, and
// what is reported beside it without deciding (docs/guide-ci.md, "What the exit code judges").
std::string acceptance_lines(const reports::ReportInput& in, const std::string& added, const FieldNames& names) {
  const auto& judged = in.accepted();
  if (!judged.acceptance_checked) return {};
  const std::string who = in.accepted_with_effects && in.with_effects ? "the models with " + added
                                                                       : std::string("the models as delivered");
  std::string o =
      judged.acceptance_failed
          ? fmt::format("acceptance: FAILED for {}: {} of {} checked values outside tolerance{} (exit code 1)\n", who,
                        judged.failed_count(), judged.checked_count(),
                        judged.acceptance_problems.empty() ? "" : ", and limits that checked nothing")
          : fmt::format("acceptance: passed for {}: {} values checked\n", who, judged.checked_count());
  if (const auto* other = in.beside_acceptance()) {
    const std::string what = in.accepted_with_effects ? std::string("the models as delivered") : "with " + added;
    o += wrap(fmt::format("{} of {} checked values outside tolerance {}; reported beside the acceptance, not "
                          "judged{}",
                          other->failed_count(), other->checked_count(), what,
                          in.accepted_with_effects ? ""
                                                   : " (to judge the models with an effect, give it a fixed strength "
                                                     "and " + said_text(mention("accept_with_effects"), names) + ")"),
              110, "beside:     ", "            ");
  }
  return o;
}

}  // namespace

std::string validate_summary(const reports::ReportInput& in, bool added_missing, const std::string& report_path,
                             const FieldNames& names) {
  std::string o;
  const bool after = in.with_effects != nullptr;
  const bool effects_judged = after && in.accepted_with_effects;
  o += (after ? "before: " : "") + in.baseline->brief(!effects_judged) + "\n";
  if (!after)
    for (const auto& l : reports::misfit_lines(in, 5)) o += l + "\n";
  if (in.diagnosis) o += wrap(in.diagnosis->verdict, 110, "missing: ", "         ");
  std::vector<std::string> added;
  for (const auto& e : in.effects) added.push_back(reports::effect_words(e, true));
  if (after) {
    o += fmt::format("after:  + {}: {}\n", fmt::join(added, " + "), in.with_effects->brief(effects_judged));
    for (const auto& l : reports::misfit_lines(in, 5)) o += l + "\n";
  } else if (added_missing) {
    o += "after:  nothing added: no candidate effect explains the misfit significantly\n";
  }
  if (const auto w = reports::effect_choice_warning(in); !w.empty()) o += wrap(w, 110, "note: ", "      ");
  // The values the acceptance judged; errors.csv holds the last result, which is that one only
  // when no effect was added or the effects are judged.
  const auto& judged = in.accepted();
  o += validation::failure_table_text(judged, 40,
                                      &judged == (after ? in.with_effects : in.baseline)
                                          ? "errors.csv, column tolerance, and in report.md"
                                          : "report.md, \"Outside tolerance\"");
  std::string words;
  for (const auto& s : reports::in_short(in)) words += (words.empty() ? "" : " ") + s;
  if (!words.empty()) {
    o += '\n';
    o += wrap(words, 100, "In short: ", "");
  }
  o += acceptance_lines(in, fmt::format("{}", fmt::join(added, " + ")), names);
  o += fmt::format("report: {}\n", report_path);
  return o;
}

}  // namespace chutelab::api
