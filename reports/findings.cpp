// The seed's qualitative findings as checked by validation/seed_findings: one row per claim, so a
// reader sees which part of a "partly reproduced" finding failed and on what numbers.
#include <fmt/format.h>

#include "reports/common.h"

namespace chutelab::reports {

Table findings_table(const std::vector<validation::SeedFinding>& findings) {
  Table t;
  t.id = "seed-findings";
  t.caption = "The seed's qualitative findings (Grima and Wypych 2010), checked on this dataset";
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
      row.push_back({!c.testable ? "untestable" : c.holds ? "yes" : "no", "", false, "", true});
      row.push_back({c.evidence, "", false, "", true});
      t.rows.push_back(std::move(row));
      first = false;
    }
  }
  t.notes.push_back("A finding is reproduced when every testable claim holds, partly reproduced when some do. "
                    "Agreement means |E| ≤ 2 u_val (or 5 % where no uncertainty is known); \"varies\" means a chi-square "
                    "test rejects a constant ratio at p < 0.01 (or a spread above 5 % without uncertainties). Finding 6 "
                    "(sensitivity, seed Table 6) needs its own runs: chutelab sensitivity.");
  return t;
}

}  // namespace chutelab::reports
