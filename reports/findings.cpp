// The reference study's qualitative findings as checked by validation/reference_findings: one row per claim, so a
// reader sees which part of a "partly reproduced" finding failed and on what numbers. A claim this dataset cannot
// test (a model not run, no condition of the kind, no sensitivity study) does not apply to the rig: it gets no row,
// and one note under the table says which were left out and why.
#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "reports/common.h"
#include "validation/reference_findings.h"

namespace chutelab::reports {

namespace {

std::string join_and(const std::vector<std::string>& parts) {
  if (parts.size() < 2) return parts.empty() ? std::string() : parts.front();
  std::string o;
  for (std::size_t k = 0; k + 1 < parts.size(); ++k) o += (k ? ", " : "") + parts[k];
  return o + " and " + parts.back();
}

}  // namespace

bool any_testable(const std::vector<validation::ReferenceFinding>& findings) {
  return std::any_of(findings.begin(), findings.end(), [](const auto& f) {
    return std::any_of(f.claims.begin(), f.claims.end(), [](const auto& c) { return c.testable; });
  });
}

Table findings_table(const std::vector<validation::ReferenceFinding>& findings) {
  Table t;
  t.id = "reference-findings";
  t.caption = "The reference study's qualitative findings (Grima and Wypych 2010), checked on this dataset";
  t.columns = {{"", "#", "", true}, {"", "finding", "", true}, {"", "verdict", "", true},
               {"", "claim", "", true}, {"", "holds", "", true}, {"", "evidence", "", true}};
  std::vector<std::string> whole, partial, reasons;
  bool sixth = false;
  for (const auto& f : findings) {
    bool first = true;
    std::size_t left_out = 0;
    for (const auto& c : f.claims) {
      if (!c.testable) {
        ++left_out;
        if (std::find(reasons.begin(), reasons.end(), c.evidence) == reasons.end()) reasons.push_back(c.evidence);
        continue;
      }
      std::vector<Cell> row;
      row.push_back({first ? std::to_string(f.number) : "", "", false, "", true});
      row.push_back({first ? f.statement : "", "", false, "", true});
      Cell verdict{first ? std::string(validation::name(f.status)) : "", "", false, "", true};
      verdict.strong = first;
      row.push_back(verdict);
      row.push_back({c.text, "", false, "", true});
      row.push_back({c.holds ? "yes" : c.undecided ? "undecided" : "no", "", false, "", true});
      row.push_back({c.evidence, "", false, "", true});
      t.rows.push_back(std::move(row));
      first = false;
      sixth = sixth || f.number == 6;
    }
    if (left_out == f.claims.size()) whole.push_back(std::to_string(f.number));
    else if (left_out > 0)
      partial.push_back(fmt::format("{} of finding {}", left_out == 1 ? std::string("one claim") : fmt::format("{} claims", left_out),
                                    f.number));
  }
  t.notes.push_back(std::string("A finding is reproduced when every testable claim holds, partly reproduced when some do "
                                "(or some are undecided: a tie within the uncertainty, e.g. finding 5's excess error of "
                                "0.5 h_b must exceed 2 standard uncertainties). Agreement means |E| ≤ 2 u_val (or 5 % "
                                "where no uncertainty is known); \"varies\" means a chi-square test rejects a constant "
                                "ratio at p < 0.01 (or a spread above 5 % without uncertainties).") +
                    (sixth ? " Finding 6 comes from a sensitivity study given to the validation among its studies." : ""));
  if (!whole.empty() || !partial.empty()) {
    std::vector<std::string> what;
    if (!whole.empty()) what.push_back(fmt::format("finding{} {}", whole.size() > 1 ? "s" : "", join_and(whole)));
    for (auto& p : partial) what.push_back(std::move(p));
    t.notes.push_back(fmt::format("Not testable on this dataset, so left out: {} ({}).", join_and(what),
                                  fmt::join(reasons, "; ")));
  }
  return t;
}

}  // namespace chutelab::reports
