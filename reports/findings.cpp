// The reference study's qualitative findings as checked by validation/reference_findings: one row per claim, so a
// reader sees which part of a "partly reproduced" finding failed and on what numbers.
#include <cmath>

#include <fmt/format.h>

#include "reports/common.h"
#include "reports/sensitivity_study.h"

namespace chutelab::reports {

namespace {
const char* kTable6 =
    "Sensitivity (the reference study's Table 6): LSD vs Hertz-Mindlin, sphere vs two-sphere clump, dt = t_c/10 vs t_c/20 and "
    "shear modulus x10 or /10 change the mean plate force little; larger particles give a similar mean force "
    "with larger fluctuations.";
const char* kMeanClaim = "contact model, shape, time step and G change the mean R by no more than the limit";
const char* kSizeClaim = "the fluctuation of R grows with the particle diameter";
}  // namespace

validation::ReferenceFinding sensitivity_finding(const SensitivityStudy* s, std::string_view validated) {
  validation::ReferenceFinding f{6, kTable6};
  if (!s) {
    const std::string why = "no sensitivity study given (chutelab sensitivity, then validate --studies DIR)";
    f.claims = {{kMeanClaim, false, false, why}, {kSizeClaim, false, false, why}};
  } else {
    const auto& v = s->verdict;
    // Which rig the numbers are from: the main job validates one dataset with a study of another.
    const std::string where =
        s->dataset_name.empty()
            ? fmt::format("{} (dataset not recorded)", s->condition)
            : fmt::format("{} of {}{}", s->condition, s->dataset_name,
                          !validated.empty() && validated != s->dataset_name ? " (not this dataset)" : "");
    // Variants --only left out: sizes are keyed "d=...".
    std::vector<std::string> mean_out, size_out;
    for (const auto& k : v.variants_left_out) (k.rfind("d=", 0) == 0 ? size_out : mean_out).push_back(k);
    std::string not_run;
    if (!mean_out.empty()) not_run = fmt::format("; not run: {}", fmt::join(mean_out, ", "));
    f.claims.push_back({kMeanClaim, v.mean_tested, v.mean_tested && v.mean_insensitive && mean_out.empty(),
                        v.mean_tested ? fmt::format("{}, {} quality: largest change {:+.1f} % ({}), limit ±{:g} %{}", where,
                                                    s->quality, v.worst_change, v.worst_variant, s->limit_percent, not_run)
                                      : "no contact, shape, dt or G variant ran"});
    f.claims.back().undecided = v.mean_tested && v.mean_insensitive && !mean_out.empty();
    std::vector<std::string> fl;
    for (const auto& [d, sd] : v.size_fluctuation) fl.push_back(fmt::format("{:.1f} N at {:.1f} mm", sd, d * 1e3));
    std::vector<std::string> out = size_out;
    for (double d : v.sizes_left_out) out.push_back(fmt::format("{:g} mm", std::round(d * 1e4) / 10.0));
    // A size of the reference study's Table 6 that did not run leaves the claim unchecked there:
    // undecided if it holds on the sizes that ran (one that fails there fails anyway).
    const bool all_sizes = out.empty();
    f.claims.push_back({kSizeClaim, v.size_tested, v.size_tested && v.fluctuation_grows && all_sizes,
                        v.size_tested ? fmt::format("sd of R: {}; the sizes move the mean by up to {:.1f} %{}",
                                                    fmt::join(fl, ", "), v.size_mean_spread,
                                                    all_sizes ? std::string()
                                                              : fmt::format("; not run: {} (so not decided over the "
                                                                            "reference study's sizes)", fmt::join(out, ", ")))
                                      : "fewer than two particle sizes ran"});
    f.claims.back().undecided = v.size_tested && v.fluctuation_grows && !all_sizes;
  }
  f.status = validation::status_of(f.claims);
  return f;
}

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
                    "comes from a sensitivity study (chutelab sensitivity) given with --studies.");
  return t;
}

}  // namespace chutelab::reports
