#pragma once
// The layout of a rig's logs (DATASET/logs/layout.toml): which column of a log is which
// channel, its calibration, and how the plate's load cells combine into R_n, R_s, R and the impact
// point. One log a condition, `<condition>.csv` beside the layout (time and one column a channel,
// each column named with its unit: t_s, cell_upper_mV, tacho_Hz).
//
//   time_column = "t_s"
//   [[channel]]
//   column = "cell_upper_mV"       # the log's column; the unit after its last underscore
//   role = "normal"                # normal | shear | belt_speed | mass_flow
//   gain = 25.0                    # N (m/s, t/h) per channel unit
//   zero = 0.012                   # the reading with nothing on the cell, in the channel's unit
//   gain_uncertainty_percent = 0.3 # the calibration's one standard deviation
//   resolution = 0.001             # the logger's step, in the channel's unit
//   y_mm = 95.0                    # normal cells: the cell's height in the rig (for the impact point)
//
// A reading in the output unit is gain * (raw - zero); the zero is replaced by the log's own tare
// where it has unloaded parts (steady_log.h).
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace chutelab::logs {

enum class Role { normal, shear, belt_speed, mass_flow };
std::string_view name(Role r);
// The output unit a role's gain gives, as it is written in messages: N, m/s, t/h.
std::string_view unit(Role r);

struct Channel {
  std::string column;          // the log's column
  std::string unit;            // the channel's unit (the column name's suffix)
  Role role = Role::normal;
  double gain = 1.0;           // output unit per channel unit
  double zero = 0.0;           // channel unit
  double gain_u = 0.0;         // relative, one standard deviation
  double resolution = 0.0;     // channel unit
  std::optional<double> y;     // m (rig y), normal cells
  long line = 0;               // in the layout file
};

struct Layout {
  std::filesystem::path file;
  std::string time_column = "t_s";
  std::vector<Channel> channels;
  bool has(Role r) const;
  // The impact point needs every normal cell's height, two of them different.
  bool gives_impact_point() const;
};

// Reads and checks the layout; every problem is one InputError naming file, line and key.
Layout read_layout(const std::filesystem::path& file);

// The layout as TOML text (the virtual rig writes it).
std::string layout_toml(const Layout& l);

}  // namespace chutelab::logs
