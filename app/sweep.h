#pragma once
// `estimate --sweep NAME=FROM:TO:STEP`: one input stepped over a range, the rest of the design
// held, every point through the same estimate as a single design.
#include <optional>
#include <string>
#include <vector>

#include "api/estimate.h"
#include "core/rig.h"
#include "effects/registry.h"

namespace chutelab::app {

using api::EstimatePoint;
using api::estimate_json;
using api::estimate_scalars;
using api::json_number;
using api::json_string;
using api::ModelValues;

struct SweepSpec {
  enum class Kind { condition, rig, effect };
  Kind kind = Kind::condition;
  std::string flag;       // condition inputs: the estimate flag it replaces, e.g. "--plate-distance"
  std::string column;     // the swept value's name with its unit, e.g. "plate_distance_mm"
  std::string label;      // for pictures, e.g. "plate distance (mm)"
  const RigField* field = nullptr;
  const effects::EffectInfo* effect = nullptr;
  double from = 0.0, to = 0.0, step = 0.0;
  std::vector<double> values() const;  // from + i step, i = 0.., up to and including `to`
};

// NAME is a condition input (belt_speed, mass_flow, plate_distance, plate_top, stream_thickness, in
// the units of their flags), a conditions.csv override column (plate_angle_deg, belt_incline_deg,
// pulley_diameter_mm, friction_plate, ... ; the unit suffix may be left out) or an effect name
// (its strength). Throws InputError (field "--sweep") with what is wrong and what is allowed.
SweepSpec parse_sweep(const std::string& text);

// Sets the swept value on a resolved station (rig fields) or effect list (effects).
void apply_sweep_value(const SweepSpec& s, double value, Station& st);

struct SweepRow {
  double value = 0.0;
  std::optional<EstimatePoint> point;  // absent where the design has no answer (see note)
  std::string note;
  std::string why;                     // the input the note is about (InputError::field), "" = none
  std::optional<double> plate_top_mm, plate_bottom_mm;  // y of the plate's edges at this point
};

std::string sweep_table(const SweepSpec& s, const std::vector<SweepRow>& rows);
std::string sweep_csv(const SweepSpec& s, const std::vector<SweepRow>& rows);
// `settings` are the fixed effects (the swept one, if any, is added per row).
std::string sweep_json(const SweepSpec& s, const std::vector<SweepRow>& rows,
                       const std::vector<effects::EffectSetting>& settings);
std::string sweep_chart(const SweepSpec& s, const std::vector<SweepRow>& rows);

}  // namespace chutelab::app
