// The reference study's qualitative findings as checked by validation/reference_findings: one row per claim, so a
// reader sees which part of a "partly reproduced" finding failed and on what numbers.
#include <cmath>

#include <fmt/format.h>

#include "reports/common.h"
#include "validation/reference_findings.h"

namespace chutelab::reports {

Table findings_table(const std::vector<validation::ReferenceFinding>& findings) {
  Table t;
  t.id = "reference-findings";
  t.caption = "The reference study's qualitative findings (Grima and Wypych 2010), checked on this dataset";
  t.columns = {{"", "#", "", true}, {"", "finding", "", true}, {"", "verdict", "", true},
               {"", "claim", "", true}, {"", "holds", "", true}, {"", "evidence", "", true}};
  for (const auto& f : findings) {
    bool first = true;
    for (const auto& c : f.claims) {
      std::vector<Cell> row;
      row.push_back({first ? std::to_string(f.number) : "", "", false, "", true});
      row.push_back({first ? f.statement : "", "", false, "", true});
      Cell verdict{first ? std::string(validation::name(f.status)) : "", "", false, "", true};
      verdict.strong = first;
      row.push_back(verdict);
      row.push_back({c.text, "", false, "", true});
      row.push_back({!c.testable ? "untestable" : c.holds ? "yes" : c.undecided ? "undecided" : "no", "", false, "", true});
      row.push_back({c.evidence, "", false, "", true});
      t.rows.push_back(std::move(row));
      first = false;
    }
  }
  t.notes.push_back("A finding is reproduced when every testable claim holds, partly reproduced when some do (or some "
                    "are undecided: a tie within the uncertainty, e.g. finding 5's excess error of 0.5 h_b must exceed "
                    "2 standard uncertainties). "
                    "Agreement means |E| ≤ 2 u_val (or 5 % where no uncertainty is known); \"varies\" means a chi-square "
                    "test rejects a constant ratio at p < 0.01 (or a spread above 5 % without uncertainties). Finding 6 "
                    "comes from a sensitivity study (chutelab sensitivity) given to the validation among its studies.");
  return t;
}

}  // namespace chutelab::reports
