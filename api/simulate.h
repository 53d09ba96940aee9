#pragma once
// simulate: one DEM run of one condition of a dataset (dem/station), its steady means with their
// standard errors, and a cache entry that a later validate with the same settings finds.
#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "api/output_plan.h"
#include "core/rig.h"
#include "dem/station/run.h"
#include "dem/station/settings.h"

namespace chutelab::api {

// The DEM run's settings, result and its figures under the library's names: a front end reaches
// them through api/, never through dem/ (the house's door, docs/DESIGN.md).
using DemField = dem::station::DemField;
using DemKind = dem::station::DemKind;
using DemValue = dem::station::DemValue;
using SettingsOverrides = dem::station::SettingsOverrides;
using RunSettings = dem::station::RunSettings;
using StationResult = dem::station::StationResult;
using PlateMap = dem::station::PlateMap;
using MeanWithError = dem::station::Estimate;  // a steady mean and its standard error
using dem::station::dem_fields;
using dem::station::wear_fields;
using dem::station::peak_pressure_y;
using dem::station::pressure_centre_y;
using dem::station::window_drifts;

// Errors name the keys "dataset", "condition", the options of the [dem] settings
// (dem::station::dem_fields()), "threads", "wear.KEY", "effect", "vtk_every".
struct SimulateOptions {
  std::filesystem::path dataset;           // "" = default_dataset
  std::filesystem::path default_dataset;
  std::string condition;                   // a row of conditions.csv
  // What beats the dataset's [dem] table (and the preset): settings by their options, threads, wear
  // inputs (dem::station::wear_fields() keys).
  dem::station::SettingsOverrides settings;
  std::vector<std::string> effects;        // NAME=VALUE (those with a DEM counterpart act)
  // Interval of the particle series (s) in the folder prepare_output returns (vtk/); unset: `every`
  // below when there is a folder.
  std::optional<double> vtk_every;
  double default_vtk_every = 0.05;
  bool store_in_cache = true;              // a later validate --models dem with these settings is instant
  bool progress = false;                   // a progress bar on stderr
  // Told the run's inputs; returns the folder for the particle series written during the run ("" =
  // none). With vtk_every set it must be given.
  PrepareOutput prepare_output;
};

// The options alone, before any file is read. Throws InputError naming the key.
void check(const SimulateOptions& o);

struct SimulateResult {
  Setup setup;
  Station station;                          // the condition after the effects
  dem::station::RunSettings settings;
  dem::station::StationResult run;
  std::vector<std::string> effect_notes;    // which effects acted on the DEM, which did not
  // The files of a finished run (timeseries.csv, ..., side_view.vtk) into `dir`.
  void write_files(const std::filesystem::path& dir) const;
};

SimulateResult simulate(const SimulateOptions& o);

}  // namespace chutelab::api
