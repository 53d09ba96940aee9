#pragma once
// What the scatter an explanation leaves says about the data, so that the diagnosis does not take
// its assumptions on trust:
// - a reading no explanation reaches (a transcription slip, a stuck cell) is an outlier: it is left
//   out of every fit and named;
// - a quantity that no model explains at all (a model-form error, e.g. one model's R_s off at every
//   condition) gets a discrepancy variance tau^2 added to its points' u^2, as Kennedy & O'Hagan's
//   model discrepancy in its simplest form (one constant per quantity and model), so that it cannot
//   hide an effect seen in the other quantities;
// - where the rest scatters more than the stated uncertainties say, every uncertainty is widened
//   by the Birge ratio sqrt(chi^2 / dof) (Birge 1932), so that the fitted strengths' uncertainties
//   cover the truth and the tests judge against the real scatter.
// Each step is judged at the family's false-alarm rate with a Bonferroni correction over the
// readings or quantities it could have picked, so that honest data keep their stated uncertainties.
#include <optional>
#include <string>
#include <vector>

#include "validation/misfit.h"

namespace chutelab::validation {

struct NoiseModel {
  double scale = 1.0;               // every u_val multiplied by it in fits and tests (>= 1)
  std::vector<double> discrepancy;  // per misfit group, SI; 0 = none
  std::vector<char> excluded;       // per point: an outlier left out

  static NoiseModel stated(const Misfit& m);  // as stated: scale 1, nothing added, nothing left out
  // Per point: 1 / sqrt(scale^2 + (tau / u)^2); 0 for an outlier.
  std::vector<double> weights(const Misfit& m) const;
  int excluded_count() const;
  bool settled_with(const NoiseModel& previous) const;  // the same groups and outliers, scale within 1 %
};

// The scatter of what an explanation leaves, per quantity (misfit group), in residuals weighted by
// a noise model.
struct GroupScatter {
  std::size_t group = 0;
  int n = 0;
  double chi2 = 0.0;
  double mean = 0.0;            // mean weighted residual
  double p_excess = 1.0;        // chance of a chi^2 this large if the group scattered as the noise model says
  double p_bias = 1.0;          // two-sided t-test of the mean against zero
  double p_trend = 1.0;         // the strongest slope against an operating variable
  // (both against the larger of the group's own scatter and the noise model's)
  std::string trend_driver;     // that variable
};

struct ScaleEstimate {
  double factor = 1.0;          // sqrt(chi^2 / dof) outside discrepant groups and outliers
  int dof = 0;
  double p_high = 1.0, p_low = 1.0;
};

// The reading most out of line with the explanation (its residuals `r`, unweighted), when it is
// beyond the normal quantile of alpha / (2 n), in units of its quantity's robust scatter about the
// quantity's median (median absolute deviation, never below the noise model's): nothing when none
// is, or when the outliers already left out reach `max_share` of the data. The median is the
// centre from three readings of a quantity on: a quantity the explanation misses as a whole is a
// discrepancy, not a set of bad readings.
std::optional<std::size_t> find_outlier(const Misfit& m, const NoiseModel& nm, const std::vector<double>& r,
                                        double alpha, double max_share);
// A reading left out as an outlier that the explanation (its residuals `r`) now reaches: within
// find_outlier's limit once it is counted again. A cause found after the reading was left out (a
// record wrong at its condition) can explain it; then it is no outlier.
std::optional<std::size_t> find_readmitted(const Misfit& m, const NoiseModel& nm, const std::vector<double>& r,
                                           double alpha);
// The robust deviation of every reading (as find_outlier measures it), for naming outliers.
std::vector<double> robust_deviation(const Misfit& m, const NoiseModel& nm, const std::vector<double>& r);

// The noise model that the residuals `r` (unweighted) of an explanation with k fitted strengths ask
// for: the outliers of `nm` kept, discrepant groups (each tested at alpha over the quantities) and
// the scale estimated afresh.
NoiseModel assess_noise(const Misfit& m, const NoiseModel& nm, const std::vector<double>& r, int k, double alpha,
                        ScaleEstimate* scale = nullptr);

// The discrepancy tau (SI) of one quantity that makes its readings scatter as their count says,
// given residuals `r` (unweighted) and a common scale; 0 when they already do.
double discrepancy_for(const Misfit& m, const MisfitGroup& g, const std::vector<double>& r,
                       const std::vector<char>& excluded, double scale);

// The operating variables a misfit may trend with, per point (belt speed, mass flow, drop height,
// and for trajectory points the distance along the flight).
struct Drivers {
  std::vector<std::string> names;
  std::vector<std::vector<double>> value;  // [driver][point]
};
Drivers drivers_of(const Misfit& m);

std::vector<GroupScatter> group_scatter(const Misfit& m, const NoiseModel& nm, const std::vector<double>& r,
                                        const Drivers& drivers);

}  // namespace chutelab::validation
