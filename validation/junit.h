#pragma once
// Acceptance results as JUnit XML (`validate --junit FILE`), the format Jenkins and GitLab show in
// their test views (the Ant/Jenkins layout; tests/validation/junit.xsd is the schema it is checked
// against).
//
// One <testsuite> per model, one <testcase> per condition x quantity that a tolerance applies to:
// - passed when every checked value is within its limits (a stream boundary is one test case over
//   all its measured points);
// - <failure> with measured, predicted, error E = S - D and the limit exceeded, in the quantity's
//   unit;
// - <skipped> when a tolerance applies but the model does not predict the quantity.
// When no tolerance applied to any comparison, nothing was accepted: the file then holds a single
// <testcase name="acceptance"> with an <error> saying why, so a CI view never shows it as green.
//
// `beside`: a second result reported beside the acceptance and never deciding it (validate's models
// with an effect fitted here, beside the models as delivered): one more <testsuite> per model, named
// "<dataset>.<model>.<beside_label>", whose test cases are all <skipped> with a message saying
// "not judged" and what the values would have given, so that no CI view fails, or passes, on them.
#include <string>

#include "validation/harness.h"
#include "validation/tolerances.h"

namespace chutelab::validation {

struct JunitSummary {
  int tests = 0, failures = 0, errors = 0, skipped = 0;  // the judged result's
  int beside = 0, beside_outside = 0;  // test cases beside (all skipped), those outside tolerance
  bool nothing_checked() const { return errors > 0; }
};

// tolerances may be null (none given); the text is deterministic for the same inputs.
std::string junit_xml(const ValidationResult& r, const Tolerances* tolerances, JunitSummary* summary = nullptr,
                      const ValidationResult* beside = nullptr, const std::string& beside_label = "");

}  // namespace chutelab::validation
