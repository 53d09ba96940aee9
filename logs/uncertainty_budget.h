#pragma once
// The standard uncertainty of a mean read from a log, as the sum of its parts (GUM): the scatter of
// the window's samples, the zero (tare), the calibration, the logger's resolution, a creep
// correction. Each part carries its degrees of freedom (infinite for a stated calibration); the
// combined one has the Welch-Satterthwaite degrees of freedom nu, and is widened by
// sqrt(nu / (nu - 2)): the standard deviation of the t-distribution that a mean with an estimated
// standard error follows (GUM Supplement 1, 6.4.9). So a short log gets a larger u, and a warning,
// never a small one: below kMinDof the widening stops growing and the warning says the log is too short.
#include <limits>
#include <string>
#include <vector>

namespace chutelab::logs {

inline constexpr double kInfiniteDof = std::numeric_limits<double>::infinity();
// Below this many effective degrees of freedom the log is too short to say its own uncertainty.
inline constexpr double kMinDof = 4.0;

struct UncertaintyPart {
  std::string name;            // "scatter", "zero", "calibration", "resolution", "creep"
  double u = 0.0;              // SI, one standard deviation
  double dof = kInfiniteDof;
};

struct Budget {
  std::vector<UncertaintyPart> parts;
  double combined = 0.0;       // root sum of squares
  double dof = kInfiniteDof;   // Welch-Satterthwaite
  double widening = 1.0;       // sqrt(nu / (nu - 2)), nu at least kMinDof - 1
  double u = 0.0;              // combined * widening: the stated standard uncertainty
  bool too_short = false;      // dof < kMinDof
};

Budget combine(std::vector<UncertaintyPart> parts);

// The two-sided (1 - alpha) quantile of Student's t with `dof` degrees of freedom (normal's when
// infinite).
double t_quantile(double alpha, double dof);

}  // namespace chutelab::logs
