#pragma once
// A model predicts one condition in the measurement vocabulary (DESIGN.md §2). The harness,
// the diagnosis and the report see models only through this interface.
#include <Eigen/Core>
#include <array>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "analytical/effect.h"
#include "core/campaign.h"
#include "core/quantity.h"
#include "core/rig.h"

namespace chutelab::analytical {
struct TransferAnalysis;
}

namespace chutelab::validation {

struct TrajectoryQuery {
  Boundary boundary = Boundary::centre;
  double x = 0.0;  // m
};

// Something a model draws in the x-y plane (m): a polyline (streamlines, stream limits) or a cloud
// of points (a DEM's particles), optionally with one value per point that pictures map to colour.
struct Curve {
  enum class Kind { line, points };
  std::string name{};
  std::vector<Eigen::Vector2d> points{};
  Kind kind = Kind::line;
  std::vector<double> value{};  // empty, or one per point
  std::string value_label{};    // e.g. "speed (m/s)"
};

// A point of the plate face where a quantity of dataset.h's plate_quantities() is wanted.
struct PlateQuery {
  std::string quantity;
  double y = 0.0, z = 0.0;  // m
};

// A wall's map for pictures (the report's heat maps): triangles in the face's (z, y) plane, m.
struct SurfaceMap {
  std::string name;                                  // "plate"
  std::vector<std::array<Eigen::Vector2d, 3>> cells;  // corners (z, y)
  std::vector<double> pressure;                      // Pa, per cell
  std::vector<double> wear_rate;                     // m/s of depth, per cell (all wear models)
  double peak_pressure_y = 0.0;                      // m, peak of the profile across the face
  double pressure_centre_y = 0.0;                    // m
};

// The analytical band a stream strikes (analytical/impact_zone.h), for pictures and comparisons.
struct PlateZone {
  double top_y = 0.0, bottom_y = 0.0, centroid_y = 0.0;  // m
  double width = 0.0;                                     // m, centred on z = 0
  double mean_pressure = 0.0;                             // Pa
};

// What a caller wants besides the quantities.
struct PredictRequest {
  std::span<const TrajectoryQuery> trajectory;  // stream points to predict
  bool curves = true;                           // polylines for pictures (not needed by fits)
  // The model's own discretisation uncertainty (an expensive model's extra runs); a fit's probe
  // runs do not need it.
  bool discretisation = true;
  // A run for an effect's signature (a difference of two such runs): an expensive model may make it
  // at a cheaper setting than its predictions (the DEM's --signature-quality).
  bool signature = false;
  std::span<const PlateQuery> plate = {};       // plate points to predict
};

// The uncertainties are standard uncertainties (one sd), SI, of V&V 20's parts: `uncertainty` and
// `trajectory_uncertainty` the statistical part of u_num (e.g. a DEM mean's standard error),
// `discretisation` and `trajectory_discretisation` its discretisation part (e.g. GCI-style
// ladders in time step and particle size, validation/gci.h); absent = not estimated. `input_uncertainty` and
// `trajectory_input_uncertainty` (u_input) are filled by the harness from the dataset's stated
// input uncertainties (validation/input_uncertainty.h), not by the model.
struct ModelPrediction {
  QuantityValues values;                          // SI
  QuantityValues uncertainty;                     // SI, one sd of the prediction (e.g. DEM mean)
  std::vector<std::optional<double>> trajectory;  // y (m) per query, absent where not predicted
  std::vector<std::optional<double>> trajectory_uncertainty;     // m per query (statistical)
  QuantityValues discretisation;                                 // SI, u_num's discretisation part
  std::vector<std::optional<double>> trajectory_discretisation;  // m per query
  QuantityValues input_uncertainty;                              // SI, u_input (harness)
  std::vector<std::optional<double>> trajectory_input_uncertainty;  // m per query (harness)
  std::vector<Curve> curves;
  std::vector<std::optional<double>> plate;       // SI per plate query, absent where not predicted
  std::vector<std::optional<double>> plate_uncertainty;  // SI, one sd, per plate query (may be shorter)
  std::vector<SurfaceMap> maps;                   // pressure and wear maps (DEM)
  std::optional<PlateZone> plate_zone;            // the analytical impact zone
  std::vector<std::string> notes;                 // e.g. "R_s from Eq 7 (no stationary flow)"
  // Loads whose steady mean came from a window they still moved through (a DEM's "R_s", "impact
  // point": the build-up on the plate still forming; bench/WINDOW.md). Their ± does not cover it.
  std::vector<std::string> unsteady;
};

// An expensive model's prediction of one condition as a campaign job (core/campaign.h): `job`
// runs anywhere (any MPI rank or worker thread) and returns the run's complete result as text;
// `accept` hands that text to the model on every rank, after which predict() of the same station
// and effects uses it instead of running (validation/campaign_runs.h).
struct ModelJob {
  std::string id;  // identity of the run (e.g. its cache key): equal ids are one run
  // Not empty for a run made only to estimate the prediction's discretisation uncertainty (one
  // rung of a ladder, validation/gci.h): what differs, e.g. "2 dt", "17.0 mm particles".
  std::string ladder_rung;
  campaign::Job job;
  std::function<void(const std::string&)> accept;
};

class Model {
 public:
  virtual ~Model() = default;
  virtual std::string name() const = 0;
  virtual std::string description() const = 0;
  // Cheap models answer in microseconds; an expensive one (DEM) says so, and the diagnosis then
  // works with analytical signatures applied as differences (DESIGN.md §5).
  virtual bool expensive() const { return false; }
  // Whether the model itself responds to the effects (beyond the fixed ones) at this station: an
  // expensive model that does is run with a candidate effect on to obtain its own signature; one
  // that does not (the default) takes its signatures from the cheap models (DESIGN.md §5).
  // Whether its signature runs (PredictRequest::signature) differ from its predictions (a cheaper
  // setting); when not, the prediction without candidates is their reference.
  virtual bool cheaper_signatures() const { return false; }
  virtual bool represents(const Station&, const analytical::EffectList& fixed,
                          const analytical::EffectList& with_candidate) const {
    (void)fixed;
    (void)with_candidate;
    return false;
  }
  virtual ModelPrediction predict(const Station& station, const analytical::EffectList& effects,
                                  const PredictRequest& request) const = 0;
  // A model that reads nothing but the analytical chain (analytical::analyse_transfer of the
  // station with these effects) answers from an analysis it is given, the same as predict(): a
  // caller predicting several such models of one condition, as a fit does hundreds of times per
  // condition, then runs the chain once for all of them.
  virtual bool reads_transfer_analysis() const { return false; }
  // Inline, as every other virtual here: an out-of-line one would become the class's key function and
  // take its type information out of the designer's WebAssembly build, which has no model.cpp.
  virtual ModelPrediction predict_from(const analytical::TransferAnalysis& /*analysis*/,
                                       const analytical::EffectList& /*effects*/,
                                       const PredictRequest& /*request*/) const {
    throw std::logic_error("model '" + std::string(name()) + "' does not predict from an analytical chain");
  }
  // False for fixed results (another code's exported predictions): predict() cannot honour a
  // candidate effect, so the diagnosis keeps using signatures for it instead of confirming by a run.
  virtual bool runs_with_effects() const { return true; }
  // The runs predict(station, effects, request) would do, as jobs (the run and, for u_num's
  // discretisation part, its ladder's); none for a model that answers at once.
  virtual std::vector<ModelJob> campaign_jobs(const Station& /*station*/, const analytical::EffectList& /*effects*/,
                                              const PredictRequest& /*request*/) const {
    return {};
  }
};

using ModelPtr = std::shared_ptr<const Model>;

struct ModelSettings;  // validation/models/model_settings.h

// All models chutelab knows, in report order.
std::vector<std::string> model_names();
// Throws InputError (field "models") naming the unknown model and the known ones. Besides the
// registry's names: "external:NAME=DIR", another code's results (validation/models/external_model.h).
// The expensive models ("dem", "liggghts") are made with `settings`; without them, with their
// defaults (no dataset [dem] table, the default cache, no output folder).
ModelPtr make_model(const std::string& name);
// An empty list, an empty item ("korzen,,booth-cema") and a model named twice, before any is made.
void check_model_names(const std::vector<std::string>& names);
ModelPtr make_model(const std::string& name, const ModelSettings& settings);
// Also refuses what check_model_names() refuses.
std::vector<ModelPtr> make_models(const std::vector<std::string>& names);
std::vector<ModelPtr> make_models(const std::vector<std::string>& names, const ModelSettings& settings);

}  // namespace chutelab::validation
