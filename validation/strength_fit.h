#pragma once
// The strengths of candidate effects that minimise a cost (validation/misfit.h): a grid scan
// (effects with a threshold have no gradient at their neutral value) followed by GSL's
// trust-region least squares, with the covariance of a weighted least-squares estimate. On many
// conditions the grid runs on a sample of them and a Gauss-Newton polish on all finishes. And, for
// an expensive model whose own response is not linear in the strength, the minimum and its
// uncertainty from a few real evaluations (a profile of chi^2).
#include <algorithm>
#include <functional>
#include <span>
#include <vector>

#include "effects/registry.h"
#include "validation/misfit.h"

namespace chutelab::validation {

// How far a fit may go: inside the physical range, or the extended one (effects/registry.h), to
// ask what strength the data want whatever physics allows.
enum class StrengthRange { physical, extended };

// A grid only has to find the basin of the minimum, which an even sample of the conditions shows
// as well as all of them: above twice this many conditions a fit scans the grid on that many and
// polishes the minimum on all (validation/strength_fit.cpp).
inline constexpr std::size_t kGridConditions = 250;

struct FitOptions {
  StrengthRange range = StrengthRange::physical;
  std::vector<std::vector<double>> starts = {};  // extra starting points, one vector per start
  std::size_t grid_conditions = kGridConditions;  // 0: the grid reads every condition
  // Scan the range for the basin of the minimum before refining. Without it the refinement starts
  // from the best of the neutral point and `starts`: for a cause added to an explanation already
  // fitted, whose basin its own single fit found (a grid over three strengths costs 216 evaluations).
  bool grid = true;
};

enum class FitStatus {
  converged,       // the minimiser met its tolerances
  stopped,         // it ran out of iterations or could not step further: the estimate is the best seen
  grid_only,       // no more data than strengths: the grid's best point, no local refinement
};

struct StrengthFit {
  std::vector<double> estimate;     // boundary units
  std::vector<double> uncertainty;  // one sd from (J^T J)^-1 of the weighted residuals; infinite where the data say nothing
  double chi2 = 0.0;                // of the cost (weights included)
  FitStatus status = FitStatus::grid_only;
  std::vector<bool> at_bound;       // the estimate sits at an edge of the range it was fitted in
  // The cost's (weighted) residuals at the estimate where the fit kept them (a fit on many
  // conditions), else empty: a caller that needs them need not evaluate them again.
  std::vector<double> residuals;
};

StrengthFit fit_strengths(const Cost& cost, std::span<const effects::EffectInfo* const> fx,
                          const FitOptions& options = {});
// Every point as stated, inside the physical ranges (`--effect NAME=fit`).
StrengthFit fit_strengths(const Misfit& m, std::span<const effects::EffectInfo* const> fx,
                          const std::vector<std::vector<double>>& starts = {});

// One strength's chi^2 evaluated for real at a few strengths around a first estimate: a parabola
// through three of them gives the minimum and, from its curvature, the uncertainty (chi^2 rises by
// one at one sd), without the linear response a signature assumes.
struct ProfileFit {
  double estimate = 0.0, uncertainty = 0.0, chi2 = 0.0;  // the parabola's minimum and its value
  std::vector<std::pair<double, double>> points;          // (strength, chi^2) evaluated
  bool bracketed = false;  // the minimum lies between evaluated strengths and the curve is convex
  // With four or more points: the rms of chi^2 about the least-squares parabola through them all
  // (the expensive runs' own noise), whose vertex and sd are the estimate then.
  double scatter = 0.0;
  // The evaluated point of lowest chi^2 (the best real run); points must not be empty.
  std::vector<std::pair<double, double>>::const_iterator lowest() const {
    return std::min_element(points.begin(), points.end(), [](const auto& a, const auto& b) { return a.second < b.second; });
  }
};
// `step` is rounded to a round number and the strengths lie on a grid of half a step from `first`
// (itself on a grid: strength_fit.h's on_grid), so that nearby first estimates evaluate (and cache)
// the same runs. At most `budget` evaluations.
// 1, 2 or 5 times a power of ten, the nearest to x (> 0).
double round_number(double x);
// A strength rounded to a power of ten below a quarter of its sd: where an expensive model is run at
// a fitted strength, estimates that differ by less than that run (and cache) the same run, and the
// rounding moves it by at most an eighth of its uncertainty.
double on_grid(double value, double sd);

// `known`: evaluations already made (a confirming run at the first estimate), counted as points.
// The grid is anchored at `first`.
ProfileFit profile_strength(const std::function<double(double)>& chi2_at, double first, double step,
                            double lower, double upper, int budget = 5,
                            const std::vector<std::pair<double, double>>& known = {});

}  // namespace chutelab::validation
