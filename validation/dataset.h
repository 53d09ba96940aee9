#pragma once
// A dataset folder (DESIGN.md §2): setup.toml, conditions.csv, measurements.csv, trajectory.csv.
// Reading either gives a complete, checked Dataset or throws one InputError naming file, line and
// field; nothing is half-read.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "core/quantity.h"
#include "core/rig.h"

namespace chutelab::validation {

struct SourceLine {
  std::string file;
  long line = 0;
};

struct Measurement {
  std::string condition;
  Quantity quantity = Quantity::normal_force;
  double value = 0.0;                  // SI
  std::optional<double> uncertainty;   // SI, one standard deviation; absent when unknown
  SourceLine where;
};

struct TrajectoryPoint {
  std::string condition;
  Boundary boundary = Boundary::centre;
  double x = 0.0, y = 0.0;             // m
  std::optional<double> uncertainty;   // m
  SourceLine where;
};

struct Dataset {
  std::filesystem::path dir;
  Setup setup;
  std::vector<Station> stations;       // one per conditions.csv row, overrides applied
  std::vector<SourceLine> station_lines;
  std::vector<Measurement> measurements;
  std::vector<TrajectoryPoint> trajectory;

  const Station* station(std::string_view condition) const;
  const SourceLine* station_line(std::string_view condition) const;
};

enum class MeasurementsRequired { no, yes };

Setup read_setup(const std::filesystem::path& file);
Dataset read_dataset(const std::filesystem::path& dir,
                     MeasurementsRequired need = MeasurementsRequired::yes);
// The rig's conditions only (e.g. for estimate/synthesize on a dataset without measurements).
std::vector<Station> read_conditions(const std::filesystem::path& file, const Setup& setup,
                                     std::vector<SourceLine>* lines = nullptr);

// Station from a setup and explicit operating values (all SI).
Station make_station(const Setup& setup, std::string condition, double belt_speed,
                     double mass_flow, double plate_distance, double plate_top,
                     std::optional<double> stream_thickness);

}  // namespace chutelab::validation
