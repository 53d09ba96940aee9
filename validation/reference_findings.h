#pragma once
// The reference study's qualitative findings (Grima & Wypych 2010, as its results and conclusions state
// them), checked on a validation result rather than asserted: each is split into the claims a dataset can
// test, each claim is decided from the numbers with a stated criterion, and a finding is "reproduced" only
// when every testable claim holds. Claims need particular models (korzen, booth-cema, dem) and measured
// quantities; what a dataset cannot test is said, not guessed.
#include <string>
#include <vector>

#include "validation/dataset.h"
#include "validation/harness.h"

namespace chutelab::validation {

// undecided: the claims that could be tested are within their uncertainty of either answer.
enum class FindingStatus { reproduced, partly, not_reproduced, not_testable, undecided };
std::string_view name(FindingStatus s);

struct FindingClaim {
  std::string text{};     // what is claimed
  bool testable = false;  // the models and measurements it needs are present
  bool holds = false;
  std::string evidence{}; // the numbers and the criterion (or why it cannot be tested)
  // Tested, but the numbers do not tell the claim from its opposite (a tie within the uncertainty):
  // holds is false and the claim is not counted against the finding either.
  bool undecided = false;
};

struct ReferenceFinding {
  int number = 0;             // as in the reference list
  std::string statement{};    // the reference study's finding
  std::vector<FindingClaim> claims{};
  FindingStatus status = FindingStatus::not_testable;
};

// reproduced when every testable claim holds; not reproduced when none holds and none is undecided;
// undecided when every testable claim is; otherwise partly.
FindingStatus status_of(const std::vector<FindingClaim>& claims);

// Findings 1-5 (model behaviour and model-vs-measurement patterns). Finding 6, the sensitivity
// study, needs its own runs (`chutelab sensitivity`) and is judged there.
std::vector<ReferenceFinding> check_reference_findings(const Dataset& d, const ValidationResult& r);

}  // namespace chutelab::validation
