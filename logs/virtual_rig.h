#pragma once
// The virtual rig: logs written from a known truth (any model's prediction of a condition) through
// the sensor model (sensor_model.h), so that the log import (log_reading.h) can be tested against
// what it should find. The plate hangs on two normal load cells, at the plate's top and bottom
// edges, and one shear cell; a tachometer reads the belt's speed and a belt scale its flow.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "logs/layout.h"
#include "logs/sensor_model.h"

namespace chutelab::logs {

struct TrueCondition {
  std::string condition;
  double normal = 0.0, shear = 0.0;      // N, the plate's true mean loads
  double impact_y = 0.0;                 // m, rig y of the point of application of R_n
  double belt_speed = 0.0;               // m/s, as recorded (the real belt runs (1 + belt_speed_error) faster)
  double mass_flow = 0.0;                // kg/s
};

// A series whose fluctuation about its mean stands for the stream's (e.g. the steady part of a DEM
// run's plate loads, dem/station's timeseries.csv), looped over the log's loaded part.
struct Fluctuation {
  std::vector<double> t;                  // s, equally spaced
  std::vector<double> normal, shear, impact_y;  // N, N, m
};
// The steady window of a DEM run's timeseries.csv (t_s, normal_force_N, shear_force_N,
// impact_point_y_mm), found by the DEM's own rule; InputError naming the file when it has none.
Fluctuation read_dem_series(const std::filesystem::path& file);

// The layout of the virtual rig's logs: cells at y_upper and y_lower (m).
Layout virtual_layout(const SensorModel& m, double y_upper, double y_lower);

// One condition's log as CSV text. Deterministic in `seed`.
std::string virtual_log(const TrueCondition& truth, const SensorModel& m, const Layout& layout, std::uint64_t seed,
                        const Fluctuation* fluctuation = nullptr);

}  // namespace chutelab::logs
