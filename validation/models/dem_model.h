#pragma once
// The DEM of the transfer station (dem/station) as a harness model, "dem" in --models.
//
// Each condition is one DEM run (minutes), so results are cached by every input that matters
// (dem/station/cache.h); a repeated validate is instant. Effects the DEM honours act on its inputs:
// the operating point (mass_flow_bias: feed rate), the plate interaction's friction
// (plate_friction: particle-plate sliding friction), forces in flight (air_drag: a body force) and
// an adhesive stress at the belt (belt_adhesion: particle-belt and particle-pulley cohesion,
// dem/station/belt_cohesion.h); measurement effects (load_cell_offset) are applied by the harness
// to every model. Effects that change the analytical discharge in other ways or the release
// (belt_slip, stream_spread) or the stream restitution (plate_rebound: the DEM's rebound comes from
// its contacts, and no DEM input sets a stream restitution) have no DEM counterpart and are ignored
// with a note in the prediction.
//
// Effects are recognised by what they do, not by name: each is asked what it changes in a probe
// of every analytical stage, so a new effect with a flight force, an operating-point change or a
// holding stress at the belt is honoured by the DEM without code here.
#include <memory>
#include <mutex>
#include <optional>
#include <string>

#include "analytical/effect.h"
#include "dem/station/run.h"
#include "dem/station/scene.h"
#include "dem/station/settings.h"
#include "validation/model.h"

namespace chutelab::validation {

// The dataset's [dem] table, read once, when a run first needs it.
struct DemTableOnce {
  std::once_flag read;
  dem::station::DemTable table;
};

struct DemModelConfig {
  dem::station::SettingsOverrides overrides;  // e.g. --dem-quality; beats the dataset's [dem]
  std::string setup_file;    // the dataset's setup.toml, for its optional [dem] table
  std::optional<std::string> setup_text;  // its text as read with the dataset (else read from setup_file)
  // Shared by the copies of this configuration (the "dem" and "liggghts" models of one dataset).
  std::shared_ptr<DemTableOnce> table_once = std::make_shared<DemTableOnce>();
  // The [dem] table of setup_file (empty without one), read at the first call; InputError as
  // read_dem_table (a failed read is tried again by the next call).
  const dem::station::DemTable& dem_table() const;
  bool use_cache = true;
  bool cache_only = false;   // a run missing from the cache is an error, not a run
  // Runs with effects continue the steady state of the same run without them (dem/station/run.h
  // Restart) when the effects change only what can act on a running station: the flow fed, the
  // particle-plate friction, forces in flight, the belt's adhesion. The runs without effects then
  // keep their final state in the cache folder (~9 MB at standard quality). Off by default: it
  // saves little and measures a later state (bench/RESTART.md).
  bool restart = false;
  // u_num's discretisation part (validation/gci.h): one more run at 2 dt, and, when the run
  // coarse-grains the dataset's particles, two more at r d and r^2 d.
  bool ladder = true;
  double ladder_ratio = 1.25;
  // The dataset's conditions. With more than three, the time-step ladder runs at three of them that
  // span the belt speeds and flows (the slowest, the middle, the fastest) and is carried to every
  // condition (bench/LADDER.md, carried_time_step): per value, its own standard error times the
  // largest u_disc / u_stat seen where a ladder there saw only noise, or its value times the largest
  // u_disc / |f| seen where one resolved a difference, whichever is larger. ladder_all ladders every
  // condition itself.
  std::vector<Station> ladder_conditions;
  bool ladder_all = false;
  // Settings of the runs that give effect signatures (PredictRequest::signature); unset: the
  // predictions' own. A signature is a difference of two runs at the same settings.
  std::optional<dem::station::Quality> signature_quality;
  std::string cache_dir;     // "" = dem::station::ResultCache::default_dir()
  bool progress = false;     // progress on stderr
  std::string output_dir;    // "" = none; else per condition: CSV series, side view, VTK
};

// The registry's "dem" model is made by make_model with ModelSettings::dem (models/model_settings.h).
ModelPtr make_dem_model(const DemModelConfig& c);

// What a list of effects changes in a DEM run of a station.
struct DemEffectInputs {
  Station station;                           // operating point after the effects
  dem::station::ExternalInputs external;     // plate friction, flight acceleration, belt adhesion
  std::vector<std::string> notes;            // honoured / ignored, effect by effect
  std::string key;                           // canonical text of what the DEM sees
};
DemEffectInputs dem_effect_inputs(const Station& st, const analytical::EffectList& effects);

// Where the difference between the runs of `base` and `fx` first acts, when a run of `fx` can
// continue the steady state of a run of `base` (the same rig, settings and belt speed; only the flow
// fed, the plate friction, the flight force or the belt adhesion differ); none otherwise, or when
// nothing differs.
std::optional<dem::station::ChangeAt> restart_change(const DemEffectInputs& base, const DemEffectInputs& fx);

// The cache key of a DEM run: kStationModelVersion, the station after effects, the resolved
// settings, the contents of STL files and the effect inputs.
std::string dem_cache_key(const DemEffectInputs& fx, const dem::station::RunSettings& settings,
                          const dem::station::DemTable& table);

// A finished station run (either engine) as the harness's prediction: the steady means with their
// standard errors, the stream limits at the requested points, curves and side view, and notes.
ModelPrediction dem_station_prediction(const dem::station::StationResult& r, const DemEffectInputs& fx,
                                       const PredictRequest& request);

// Canonical text of a station (every field, full precision), for cache keys.
std::string canonical_station(const Station& st);

}  // namespace chutelab::validation
