#pragma once
// u_input of ASME V&V 20-2009: the part of the validation uncertainty that the uncertainties of
// the simulation's inputs (belt speed, mass flow, plate position, stream thickness, rig and
// material properties, as a dataset states them: validation/dataset.h InputUncertainties) carry
// into each prediction, by the sensitivity-coefficient method:
//   u_input(S)^2 = sum_i (dS/dx_i * u_i)^2.
// - The inputs are taken as independent (no correlations are stated by any dataset format we
//   read); a correlated pair would need a covariance term.
// - Coefficients are central finite differences of a cheap model with the input moved by ± its
//   own uncertainty, (S(x + u) - S(x - u)) / 2u. A step of one standard deviation measures the
//   slope over the range the input really spans, so a mildly non-linear response is averaged
//   rather than read at a point, and the analytical chain's switches (stationary flow or not,
//   low/high-speed discharge) are straddled as the data would straddle them; it is also far above
//   rounding for closed-form models. Near a physical bound (rig_fields() ranges; positive
//   operating inputs keep at least half their value) the step shrinks on that side and the
//   difference becomes asymmetric. Where the model cannot predict on one side (the stream misses
//   the plate, ...), the one-sided difference of the other is used; where neither side predicts,
//   that quantity's u_input is not estimated (a note says which input).
// - Predictions are taken raw, before measurement-stage effects (load-cell offset, ...): those act
//   on the recorded value, not on the inputs.
// - A stream thickness uncertainty acts only on a condition that states h_b; with h_b from
//   continuity the uncertainties of mass flow, belt speed and bulk density carry it instead.
// - An expensive model (Model::expensive(): the DEM, and any model that says so) is not re-run per
//   input. Its coefficients are those of the first cheap model, in registry order, that predicts
//   the value (as the diagnosis takes effect signatures, DESIGN.md §5): absolute coefficients
//   for positions (the impact point, stream limits), and elasticities for the other quantities
//   (forces, speeds: dS/dx / S_cheap times the expensive model's own S), where both the cheap and
//   the expensive value are strictly positive; otherwise absolute. Elasticities carry the
//   relative sensitivity over where the two models differ in level, e.g. Korzen's R_s being 2-4x
//   the DEM's on the LIGGGHTS rig. Where the two differ by more than a factor of 2 (Korzen's V_a
//   near the root of its Eq 4 is 0.50 m/s against the DEM's 1.78 at V3-41 of that rig), the
//   elasticity is the cheap model's and may not be the DEM's: a note says so.
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "validation/dataset.h"
#include "validation/model.h"

namespace chutelab::validation {

// One perturbed input and the model's coefficients for it.
struct InputSensitivity {
  std::string input;                                // e.g. "belt_speed_mps", "material.friction_plate"
  double u = 0.0;                                   // SI, one standard deviation
  QuantityValues coefficient;                       // dS/dx, SI per SI; absent = not predicted either side
  std::vector<std::optional<double>> trajectory;    // dy/dx per query
};

// Coefficients of a cheap model for every input with a stated uncertainty (zero ones included).
std::vector<InputSensitivity> sensitivities(const Model& model, const Station& station,
                                            const InputUncertainties& u,
                                            const analytical::EffectList& effects,
                                            std::span<const TrajectoryQuery> queries);

struct InputUncertaintyResult {
  QuantityValues u;                                // SI; absent = not estimated
  std::vector<std::optional<double>> trajectory;   // m per query
  std::vector<std::string> notes;                  // where a part could not be estimated, and why
};

// u_input of `own` (the model's prediction at `station`). Empty (nothing estimated) when the
// dataset states no input uncertainty for the condition.
InputUncertaintyResult input_uncertainty(const Model& model, const Station& station,
                                         const InputUncertainties& u,
                                         const analytical::EffectList& effects,
                                         std::span<const TrajectoryQuery> queries,
                                         const ModelPrediction& own);

}  // namespace chutelab::validation
