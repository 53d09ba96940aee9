#pragma once
// One condition's log turned into the means of the plate's quantities, each with its uncertainty's
// parts, the window it came from, and what the log says about itself: the zero's drift, a creep,
// the belt's speed and flow against the recorded operating point.
//
// - The zero of each plate channel is the mean of the unloaded parts before and after the load
//   (steady_log.h), taken as a straight line between them (a drift is assumed linear in time, and
//   said so); it is subtracted from every sample. A drift beyond its noise is flagged.
// - The quantities are functions of the channels' window means (R_n the normal cells' sum, R_s the
//   shear cells', R their resultant, y_R the normal cells' moment over their sum). Each is read as a
//   series linearised about those means, q(t) = f(m) + sum_i df/dy_i (y_i(t) - m_i), whose mean is
//   f(m) and whose scatter is that of the quantity, so that one rule (correlated_mean.h) gives every
//   quantity's standard error, and the same gradients carry the zeros', gains' and resolution's
//   parts (uncertainty_budget.h).
// - Creep, a slow trend through the window, is tested on the plate's load (R_n; R_s without normal
//   cells), where it stands clearest above the noise: the line through the window's samples against
//   the t-quantile of kFlagAlpha (correlated_mean.h gives its standard error). Found, it is flagged,
//   reported as each quantity's change over the window in its unit, and every force is corrected
//   back to the load's start by the same fraction (a load cell creeps from the moment it is loaded,
//   and the plate's cells alike; the impact point, a ratio of forces, is left as it is), the
//   correction's uncertainty a part of the budget.
#include <optional>
#include <string>
#include <vector>

#include "core/quantity.h"
#include "logs/correlated_mean.h"
#include "logs/layout.h"
#include "logs/log_file.h"
#include "logs/steady_log.h"
#include "logs/uncertainty_budget.h"

namespace chutelab::logs {

// The false-alarm rate of each drift or creep test on a log that has neither (two-sided).
inline constexpr double kFlagAlpha = 0.01;

struct QuantityReading {
  Quantity quantity = Quantity::normal_force;
  double value = 0.0;            // SI, corrected for creep when flagged
  Budget budget;                 // budget.u: the stated uncertainty, SI
  CorrelatedMean stats;          // of the window's samples
  double creep_change = 0.0;     // SI: the trend's change over the window
  double creep_u = 0.0;          // SI: its standard uncertainty
  bool creep = false;            // flagged (and corrected)
  double creep_correction = 0.0; // SI, added to the window's mean
};

struct ChannelZero {
  std::string column;
  bool from_layout = false;      // no unloaded part: the layout's zero, unchecked
  double before = 0.0, after = 0.0;  // output unit (N), the tares
  double u_before = 0.0, u_after = 0.0, dof = kInfiniteDof;
  double drift = 0.0, u_drift = 0.0;  // after - before
  bool drift_flag = false;
};

struct OperatingCheck {
  Role role = Role::belt_speed;
  std::string column;
  double logged = 0.0, u = 0.0;  // SI (m/s; kg/s)
  double recorded = 0.0;         // SI, the condition's record
  double relative() const { return logged / recorded - 1.0; }
  bool off = false;              // beyond 3 u: the record and its instrument disagree
};

struct ConditionReading {
  std::string condition;
  std::filesystem::path file;
  double dt = 0.0;
  LogSegments segments;
  std::vector<ChannelZero> zeros;
  std::vector<QuantityReading> quantities;
  std::vector<OperatingCheck> checks;
  std::vector<std::string> warnings;
  // For the report's chart: the plate's load as logged (nominal zeros, N), at most ~600 points, the
  // zero line (the sum of the plate channels' zeros at the tares' centres) and R_n's trend.
  std::vector<double> chart_t, chart_load;
  double zero_t0 = 0.0, zero_v0 = 0.0, zero_t1 = 0.0, zero_v1 = 0.0;
  double trend_slope = 0.0;      // N/s, of the load through the window
  bool drift_flagged() const;
  bool creep_flagged() const;
  bool flagged() const { return drift_flagged() || creep_flagged(); }
  const QuantityReading* find(Quantity q) const;
};

// `recorded_*`: the condition's operating point (SI: m/s, kg/s), compared with the belt's own
// channels where the layout has them.
ConditionReading read_condition(const Log& log, const Layout& layout, const std::string& condition,
                                std::optional<double> recorded_speed, std::optional<double> recorded_flow);

}  // namespace chutelab::logs
