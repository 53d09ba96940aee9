#pragma once
// A dataset folder (DESIGN.md §2): setup.toml, conditions.csv, measurements.csv, trajectory.csv.
// Reading either gives a complete, checked Dataset or throws one InputError naming file, line and
// field; nothing is half-read.
#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <unordered_map>
#include <optional>
#include <span>
#include <string>
#include <utility>
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

// The stated uncertainties of a condition's inputs, one standard deviation each, SI; absent = not
// stated. Operating inputs come from conditions.csv columns `<input>_uncertainty_<unit>` (or a
// setup-wide default in setup.toml's [uncertainty] table); rig and material inputs from the
// [uncertainty] table, keyed like the setup (rig_fields()).
struct InputUncertainties {
  std::optional<double> belt_speed, mass_flow, plate_distance, plate_top, stream_thickness;
  std::vector<std::pair<const RigField*, double>> rig;  // in rig_fields() order
  bool empty() const {
    return !belt_speed && !mass_flow && !plate_distance && !plate_top && !stream_thickness && rig.empty();
  }
};
// A measured value on the plate face (optional plate_map.csv): pressure-sensitive film, a wear
// survey. Quantities (unit in the name): plate_pressure_Pa, plate_shear_stress_Pa, wear_depth_um
// (over the [dem.wear] exposure_h of operation), wear_rate_um_per_h.
struct PlatePoint {
  std::string condition;
  std::string quantity;                // boundary name
  double y = 0.0, z = 0.0;             // m, point on the face
  double value = 0.0;                  // SI (Pa; m; m/s)
  std::optional<double> uncertainty;   // SI
  double scale = 1.0;                  // SI -> boundary unit
  SourceLine where;
};
// The plate quantities and their SI -> boundary factor.
const std::vector<std::pair<std::string, double>>& plate_quantities();

// A dataset's file as read: its text and the name messages give it (the path, or for a table from
// Python a name of its own).
struct DatasetFile {
  std::string shown;
  std::string text;
  bool unread = false;  // there but unreadable, and not needed to read the dataset (tolerances.toml):
                        // whoever needs it reads it again and says why
};
// By file name: setup.toml, conditions.csv, and those of the optional files that are there.
using DatasetTexts = std::map<std::string, DatasetFile, std::less<>>;

struct Dataset {
  std::filesystem::path dir;           // where it was read from; empty for a dataset that has no folder
  // The files as read. Whatever reads the dataset later (the DEM's [dem] table, the default
  // tolerances.toml, synthesize's copies of setup.toml and conditions.csv) takes them from here,
  // never from the folder, which may have changed or gone since. Null for a dataset made in code
  // (a self-check's replica); shared by copies.
  std::shared_ptr<const DatasetTexts> sources;
  const DatasetFile* source(std::string_view name) const;
  Setup setup;
  std::vector<Station> stations;       // one per conditions.csv row, overrides applied
  std::vector<SourceLine> station_lines;
  std::vector<Measurement> measurements;
  std::vector<TrajectoryPoint> trajectory;
  std::vector<InputUncertainties> input_uncertainty;  // parallel to stations
  std::vector<PlatePoint> plate_map;

  const Station* station(std::string_view condition) const;  // by hash: called per value by reports
  const SourceLine* station_line(std::string_view condition) const;

  // Name -> index of `stations`, rebuilt when the vector changed; shared by copies, guarded by its
  // own mutex so that concurrent readers are safe.
  struct StationIndex {
    std::mutex m;
    const Station* data = nullptr;
    std::size_t size = 0;
    std::unordered_map<std::string, std::size_t> at;
  };
  std::shared_ptr<StationIndex> station_index = std::make_shared<StationIndex>();
};

enum class MeasurementsRequired { no, yes };

// `uncertainty`, when given, receives the [uncertainty] table (rig and material keys, and the
// setup-wide defaults of the operating inputs); an unknown key there is an error.
Setup read_setup(const std::filesystem::path& file, InputUncertainties* uncertainty = nullptr);
// The same from setup.toml as read once (read_setup_file), which the DEM's [dem] table is then read
// from too (dem/station/settings.h read_dem_table), not from the folder again.
Setup read_setup(const DatasetFile& setup, InputUncertainties* uncertainty = nullptr);
DatasetFile read_setup_file(const std::filesystem::path& file);
Dataset read_dataset(const std::filesystem::path& dir,
                     MeasurementsRequired need = MeasurementsRequired::yes);
// The same from files already in memory (`files` by name, as read_dataset keeps them in
// Dataset::sources): every check and message of the folder's reader. `dir` is the folder they stand
// for, empty for none.
Dataset read_dataset(const DatasetTexts& files, const std::filesystem::path& dir,
                     MeasurementsRequired need = MeasurementsRequired::yes);
// The rig's conditions only (e.g. for estimate/synthesize on a dataset without measurements).
// `uncertainties`, when given, receives one entry per row: `defaults` (e.g. from read_setup)
// completed by the row's *_uncertainty_* columns.
std::vector<Station> read_conditions(const std::filesystem::path& file, const Setup& setup,
                                     std::vector<SourceLine>* lines = nullptr,
                                     std::vector<InputUncertainties>* uncertainties = nullptr,
                                     const InputUncertainties& defaults = {});
// The row of `stations` (as read from `conditions_file`) named `condition`. None: InputError naming
// the file and `field` (the caller's word for what chose the row) with the names there are.
const Station& condition_row(const std::vector<Station>& stations, std::string_view condition,
                             const std::filesystem::path& conditions_file, std::string_view field);

// The measurement-like files (measurements.csv, trajectory.csv; also another code's exported
// predictions, validation/models/external_model.h), checked as strictly. With `d`, every condition
// must be one of its conditions; without, any non-empty name is taken.
std::vector<Measurement> read_measurements(const std::filesystem::path& file, const Dataset* d);
std::vector<TrajectoryPoint> read_trajectory(const std::filesystem::path& file, const Dataset* d);

// The operating inputs of a condition (conditions.csv's columns belt_speed_mps, mass_flow_tph,
// plate_distance_mm, plate_top_mm, stream_thickness_mm; `value` in that column's unit) against the
// bounds no conveyor reaches: beyond them the number is a unit slip and the models would print inf
// rather than say so. Throws InputError naming `field` (no file: the caller locates it).
void check_operating_input(std::string_view column, double value, const std::string& field);
// Those bounds, one row an input (in its column's unit): the designer's page sets its sliders by them.
struct OperatingLimit {
  std::string_view column;
  double min;          // exclusive when min_open
  bool min_open;
  double max;          // inclusive
};
std::span<const OperatingLimit> operating_limits();

// Station from a setup and explicit operating values (all SI).
Station make_station(const Setup& setup, std::string condition, double belt_speed,
                     double mass_flow, double plate_distance, double plate_top,
                     std::optional<double> stream_thickness);

}  // namespace chutelab::validation
