#pragma once
// estimate's sweep: one input stepped over a range, the rest of the design held, every point through
// the same estimate as a single design (api/estimate.h). What the command line's `estimate --sweep`
// and the Python package's sweep call.
//
//   api::SweepOptions o;
//   o.dataset = "datasets/grima2010";
//   o.condition = "V5-44";
//   o.sweep = "belt_speed=2:6:1";
//   const api::SweepResult r = api::sweep(o);   // throws InputError, key "sweep", ...
//   r.csv();
#include <optional>
#include <string>
#include <vector>

#include "api/estimate.h"
#include "core/input_error.h"
#include "core/rig.h"
#include "effects/registry.h"

namespace chutelab::api {

struct SweepSpec {
  enum class Kind { condition, rig, effect };
  Kind kind = Kind::condition;
  std::string option;     // condition inputs: the estimate option it replaces, e.g. "plate_distance"
  std::string column;     // the swept value's name with its unit, e.g. "plate_distance_mm"
  std::string label;      // for pictures, e.g. "plate distance (mm)"
  const RigField* field = nullptr;
  const effects::EffectInfo* effect = nullptr;
  double from = 0.0, to = 0.0, step = 0.0;
  std::vector<double> values() const;  // from + i step, i = 0.., up to and including `to`
};

// NAME is a condition input (belt_speed, mass_flow, plate_distance, plate_top, stream_thickness, in
// the units of their options), a conditions.csv override column (plate_angle_deg, belt_incline_deg,
// pulley_diameter_mm, friction_plate, ... ; the unit suffix may be left out) or an effect name
// (its strength). Throws InputError (key "sweep") with what is wrong and what is allowed.
SweepSpec parse_sweep(const std::string& text);

// Sets the swept value on a resolved station (rig fields) or effect list (effects).
void apply_sweep_value(const SweepSpec& s, double value, Station& st);

struct SweepRow {
  double value = 0.0;
  std::optional<EstimatePoint> point;  // absent where the design has no answer (see note)
  // Why there is no answer, or what is partial; other inputs in it are mentions (core/input_error.h),
  // shown in a front end's words by the outputs below.
  std::string note;
  std::string why;                     // the input the note is about (InputError::field), "" = none
  std::optional<double> plate_top_mm, plate_bottom_mm;  // y of the plate's edges at this point
};

// Errors name the keys of EstimateOptions and "sweep".
struct SweepOptions : EstimateOptions {
  std::string sweep;                   // NAME=FROM:TO:STEP (parse_sweep); the swept input left unset
};

struct SweepResult {
  SweepSpec spec;
  std::vector<SweepRow> rows;
  std::vector<effects::EffectSetting> settings;  // the fixed effects (the swept one, if any, is per row)
  // The outputs, with the mentions in the rows' notes shown by `names` (the key itself without).
  std::string table(const FieldNames& names = {}) const;
  std::string csv(const FieldNames& names = {}) const;
  std::string json(const FieldNames& names = {}) const;
  std::string svg(const FieldNames& names = {}) const;  // the chart of impact points and plate forces, a file
};

// Every point of the sweep. Inputs that are wrong at every point (a missing option, a bad file) throw
// InputError; a point with no answer (the stream misses the plate, the load does not fit the belt) is
// a row with its note. Throws InputError (key "sweep") when no point has an answer.
SweepResult sweep(const SweepOptions& o);

std::string sweep_table(const SweepSpec& s, const std::vector<SweepRow>& rows, const FieldNames& names = {});
std::string sweep_csv(const SweepSpec& s, const std::vector<SweepRow>& rows, const FieldNames& names = {});
// `settings` are the fixed effects (the swept one, if any, is added per row).
std::string sweep_json(const SweepSpec& s, const std::vector<SweepRow>& rows,
                       const std::vector<effects::EffectSetting>& settings, const FieldNames& names = {});
std::string sweep_chart(const SweepSpec& s, const std::vector<SweepRow>& rows, const FieldNames& names = {});

}  // namespace chutelab::api
