#pragma once
// Which physical effect is missing? For each candidate effect (and each pair), fit its strength to
// all measurements and trajectory points weighted by their uncertainties, and judge whether the
// improvement is more than chance across all the candidates tried.
#include <optional>
#include <string>
#include <vector>

#include "validation/dataset.h"
#include "validation/model.h"

namespace chutelab::validation {

// How a model's normalised residuals of one quantity move with one operating variable.
struct ResidualPattern {
  std::string model;
  std::string quantity;          // boundary name
  std::string driver;            // "belt speed", "mass flow", "flight time", "drop height"
  int n = 0;
  double mean_normalised = 0.0;  // mean E/u over the conditions (bias)
  double rms_normalised = 0.0;
  double correlation = 0.0;      // Pearson r between E/u and the driver
  bool notable = false;          // bias or trend beyond what noise gives
};

struct EffectFit {
  std::vector<std::string> effects;       // one name, or two for a pair
  std::vector<std::string> parameters;    // parameter names with units
  std::vector<double> estimate;           // boundary units of each parameter
  std::vector<double> uncertainty;        // one standard deviation, from the fit's covariance
  double chi2_before = 0.0;
  double chi2_after = 0.0;
  double delta_bic = 0.0;                 // BIC(with effect) - BIC(baseline); < 0 is better
  double explained_fraction = 0.0;        // share of the excess misfit (chi2 - dof) removed
  double p_value = 1.0;                   // likelihood-ratio test, before the look-elsewhere step
  double p_adjusted = 1.0;                // after controlling for the number of candidates tried
  bool significant = false;
  int rank = 0;                           // 1 = best single effect
  // With an expensive baseline: where its response to the effect came from ("own runs", "analytical
  // only": it cannot represent the effect, "exact": a measurement effect applied to its output).
  std::string signature;
  // With an expensive baseline that runs with effects: chi^2 from the signatures, when a real run at
  // the fitted strength replaced it in chi2_after (and in what follows from it).
  std::optional<double> chi2_from_signatures;
  std::string label() const;              // "air_drag" or "air_drag + belt_slip"
};

struct DiagnosisResult {
  std::string dataset;
  std::vector<std::string> models;
  int n_data = 0;                         // measurements + trajectory points with uncertainty
  int n_without_uncertainty = 0;          // left out of chi^2
  double chi2_baseline = 0.0;
  double baseline_p_value = 1.0;          // chance of a chi^2 this large from noise alone
  std::vector<ResidualPattern> patterns;
  std::vector<std::string> failure_summary;    // sentences for an engineer
  std::vector<EffectFit> singles;         // ranked, best first
  std::vector<EffectFit> pairs;           // only pairs that beat every single by a clear margin
  bool any_significant = false;
  bool convincing = false;                // the best fit explains >= 70 % and is inside its range
  std::vector<std::string> indistinguishable;  // effects about as good as the best
  std::vector<std::string> discriminators;     // which measurement would tell them apart
  std::vector<std::string> proportional;       // candidates that move the data in proportion to the best
  std::vector<std::string> caveats;
  std::string verdict;                    // one sentence
  // With an expensive model (DEM) the ranking uses the cheap models' signatures as differences
  // (DESIGN.md §5); the recommended fit is then re-run with the expensive model for real.
  bool used_surrogate = false;
  std::optional<double> confirmed_chi2;   // chi^2 of the recommended fit from real runs
  const EffectFit* best() const;          // the recommended fit (single or pair), if significant
};

}  // namespace chutelab::validation

namespace chutelab::validation {

struct DiagnoseOptions {
  double alpha = 0.01;           // family-wise false-alarm rate over all candidates
  bool pairs = true;
  double pair_margin_bic = 6.0;  // a pair must beat the best single by this much ("strong", Kass & Raftery 1995)
  double tie_margin_bic = 2.0;   // within this of the best: indistinguishable
  // Two candidates whose fitted changes of the normalised residuals are this parallel (|cos|) move
  // the measured quantities in proportion: these data cannot tell them apart.
  double proportional_cosine = 0.98;
  // Expensive runs side by side, and threads predicting the conditions of the analytical fits
  // (0 = one per core, shared among MPI ranks).
  int jobs = 0;
  // With an expensive baseline: how many of the leading significant single candidates are re-run
  // at their fitted strengths before the ranking is final (the best pair is always re-run).
  int confirm = 3;
  // One line per fit on stderr (which, of how many, time so far) for datasets of 500 conditions or more.
  bool progress = false;
};

DiagnosisResult diagnose(const Dataset& d, const std::vector<ModelPtr>& models,
                         const DiagnoseOptions& options = {});

std::string diagnosis_csv(const DiagnosisResult& r);
std::string diagnosis_markdown(const DiagnosisResult& r);

}  // namespace chutelab::validation
