#include "api/log_report.h"

#include <cmath>
#include <fmt/format.h>

namespace chutelab::api {

std::vector<reports::LogChart> log_charts(const logs::LogImport& li) {
  std::vector<reports::LogChart> out;
  const bool normal = li.layout.has(logs::Role::normal);
  for (const auto& c : li.conditions) {
    reports::LogChart ch;
    ch.condition = c.condition;
    ch.file = c.file.filename().string();
    ch.y_label = normal ? "R_n as logged (N)" : "R_s as logged (N)";
    ch.t = c.chart_t;
    ch.v = c.chart_load;
    ch.window_start = c.segments.window.start;
    ch.window_end = c.segments.window.end;
    ch.steady = c.segments.steady;
    ch.zero_t0 = c.zero_t0;
    ch.zero_v0 = c.zero_v0;
    ch.zero_t1 = c.zero_t1;
    ch.zero_v1 = c.zero_v1;
    // The trend through the window on the logged scale: the quantity's line plus the zero under it.
    const logs::QuantityReading* q = c.find(normal ? Quantity::normal_force : Quantity::shear_force);
    if (q && c.segments.window.ok()) {
      const double mean = q->value - q->creep_correction, tc = c.segments.window.centre();
      const double slope = std::isfinite(q->stats.slope) ? q->stats.slope : 0.0;
      auto zero_at = [&](double t) {
        return c.zero_t1 > c.zero_t0 ? c.zero_v0 + (c.zero_v1 - c.zero_v0) * (t - c.zero_t0) / (c.zero_t1 - c.zero_t0)
                                     : c.zero_v0;
      };
      ch.trend_t0 = c.segments.window.start;
      ch.trend_t1 = c.segments.window.end;
      ch.trend_v0 = mean + slope * (ch.trend_t0 - tc) + zero_at(ch.trend_t0);
      ch.trend_v1 = mean + slope * (ch.trend_t1 - tc) + zero_at(ch.trend_t1);
    }
    out.push_back(std::move(ch));
  }
  return out;
}

std::vector<std::string> log_lines(const logs::LogImport& li) {
  std::vector<std::string> out;
  for (const auto& c : li.conditions) {
    std::string s = fmt::format("{} (logs/{}): ", c.condition, c.file.filename().string());
    if (c.segments.window.ok())
      s += fmt::format("{} window {:.1f}-{:.1f} s", c.segments.steady ? "steady" : "NOT steady,", c.segments.window.start,
                       c.segments.window.end);
    for (const auto& q : c.quantities) {
      const auto& qi = info(q.quantity);
      s += fmt::format("; {} {:.4g} ± {:.2g} {}", qi.symbol, q.value * qi.to_boundary, q.budget.u * qi.to_boundary,
                       qi.unit);
    }
    if (!c.warnings.empty()) s += fmt::format(". {}", fmt::join(c.warnings, ". "));
    out.push_back(s);
  }
  return out;
}

}  // namespace chutelab::api
