#pragma once
// A rig's log as the report shows it (one small chart a condition): the plate's load as logged, the
// steady window it was averaged over (shaded), the zero taken from the unloaded parts (a dashed line
// from the tare before to the tare after) and the trend through the window. Plain numbers only: the
// report knows nothing of logs (logs/ fills these).
#include <string>
#include <vector>

namespace chutelab::reports {

struct LogChart {
  std::string condition;
  std::string file;                  // the log's name, for the caption
  std::string y_label;               // e.g. "R_n as logged (N)"
  std::vector<double> t, v;          // s; the load
  double window_start = 0.0, window_end = 0.0;  // s
  bool steady = true;                // false: no steady state was found
  double zero_t0 = 0.0, zero_v0 = 0.0, zero_t1 = 0.0, zero_v1 = 0.0;  // the zero line
  double trend_t0 = 0.0, trend_v0 = 0.0, trend_t1 = 0.0, trend_v1 = 0.0;  // the trend through the window
  std::string note;                  // one line under the chart: drift, creep, warnings
};

// The charts side by side (a grid that wraps), as one HTML figure; "" when there are none.
std::string log_charts_html(const std::vector<LogChart>& charts, const std::string& id);

}  // namespace chutelab::reports
