#pragma once
// The library of candidate physical effects (DESIGN.md §4). Each effect is one file in effects/
// that describes its physics and registers itself with one line; nothing else needs to change.
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "analytical/effect.h"

namespace chutelab::effects {

// record: what the input as really built (the record corrected by a strength) must stay within: the
// dataset reader's own range for it (a belt of no thickness, particles of no size, a plate behind
// the pulley have no answer). A strength that takes it outside at a station makes that station
// impossible: a fit counts the trial infeasible, a value given is refused naming its option.
struct RecordLimits {
  std::string what;               // "belt thickness"
  std::string unit;               // of the reader's column or key: "mm", "deg", "m/s", "kg/m³"
  double to_si = 1.0;             // unit -> SI
  double lower = 0.0, upper = 0.0;  // in `unit`
  bool open_below = false;        // `lower` itself is impossible (a plate at x = 0)
  // The input at a station, SI; absent where the station does not state it (a condition without a
  // stream thickness has none to be wrong). Empty: the record has no station limit (an instrument's).
  std::function<std::optional<double>(const Station&)> value = {};
  // "" when `si` lies within; else why not, in words, beside the recorded value it came from.
  std::string problem(double si, double recorded_si) const;
};

struct EffectInfo {
  std::string name;          // DESIGN.md §4 name, e.g. "air_drag"
  std::string parameter;     // name of the strength parameter with unit, e.g. "drag_coefficient"
  std::string unit;          // unit of the parameter at the boundary ("" = dimensionless)
  std::string stage;         // where it hooks in: discharge, flight, plate, measurement, ...
  std::string physics;       // the equation and its meaning, one paragraph
  std::string source;        // where the physics comes from
  double neutral = 0.0;      // the value that switches the effect off
  double lower = 0.0;        // physical range; a fit stays inside it
  double upper = 0.0;
  double typical = 0.0;      // a realistic non-neutral strength (for synthetic tests and docs)
  std::function<std::shared_ptr<const analytical::Effect>(double)> make;
  // An independent measurement that confirms or rules the effect out, for when the data at hand
  // cannot tell it from another candidate ("" = none beyond chutelab's vocabulary).
  std::string check = {};
  // physics: an effect the models miss. record: a recorded input that may be wrong (the plate
  // further than the drawing says); its strength is the truth minus the record, in `unit`.
  enum class Kind { physics, record };
  Kind kind = Kind::physics;
  // record: how far the input is plausibly off, one standard deviation in `unit`, when the dataset
  // states no uncertainty for it (a documented default: a taped distance, a nameplate speed). An
  // input three of these off is suspicious, thirty is a typo; the diagnosis charges a candidate the
  // implausibility of its fitted strength (validation/diagnosis.h).
  double prior_width = 0.0;
  // record: the input's name in the dataset's stated uncertainties (InputUncertainties: belt_speed,
  // mass_flow, plate_distance, plate_top, stream_thickness, or a rig field as "section.key"), and
  // the stated one-sigma uncertainty (SI) expressed in `unit` at a station.
  std::string input = {};
  std::function<double(const Station&, double)> width_in_unit = {};
  // record: the number may differ between conditions (a plate moved between tests, a belt run at
  // other speeds), not only for the whole rig (a drawing error): the diagnosis then asks which.
  // Such a candidate acts through adjust_station alone.
  bool per_condition = false;
  // record: its physical limits and where a station states it (declared with `make` by
  // effects/recorded_input.h's set_record).
  RecordLimits limits = {};
  // How the effect grows with an operating variable where its physics says so (air drag: its force
  // with the speed squared), so that a diagnosis finding the data want another dependence can say
  // it in those terms ("grows about linearly with speed, not with its square").
  struct Growth {
    std::string what;    // "the drag"
    std::string driver;  // "belt speed"
    double power = 0.0;  // of the driver
  };
  std::optional<Growth> growth = std::nullopt;
};

// The first station where `e` at `strength` leaves the rig without a physical answer, in words
// naming the condition ("" = none).
std::string impossible_at(const EffectInfo& e, double strength, const std::vector<Station>& stations);
// Whether any station states the record `e` corrects: false for a stream thickness where no
// condition gives one (correcting it would change nothing). Always true for physics.
bool stated_anywhere(const EffectInfo& e, const std::vector<Station>& stations);

// How far a fit may go past the physical range when it asks what strength the data want, whatever
// physics allows (a negative drag coefficient: particles faster than ballistic): the physical range
// widened by its own span on each side. The effects' formulas stay defined there; where the
// analytical chain has no answer, a trial gives a large misfit, as inside the range. Its ends are the
// decimals the messages state (-0.3 - 0.6 is -0.9, not the -0.8999999999999999 of the sum).
struct Range {
  double lower = 0.0, upper = 0.0;
};
Range extended_range(const EffectInfo& e);
bool in_physical_range(const EffectInfo& e, double strength);

// All registered effects, sorted by name.
const std::vector<EffectInfo>& library();
const EffectInfo* find(const std::string& name);

// Called once per effect file through a static Registration object.
struct Registration {
  explicit Registration(EffectInfo info);
};

// "NAME=VALUE" or "NAME=fit" (fit only where allow_fit); throws InputError naming the flag.
struct EffectSetting {
  const EffectInfo* info = nullptr;
  std::optional<double> value;  // absent: fit to the data
};
// `outside_range`: strengths beyond the physical range (within extended_range) are accepted: only
// to make test data that break physics on purpose. `key`: the input the text came from, named in
// every message (effect; input for a recorded input's error).
EffectSetting parse_setting(const std::string& text, bool allow_fit, bool outside_range = false,
                            const std::string& key = "effect");
analytical::EffectList instantiate(const std::vector<EffectSetting>& fixed);

}  // namespace chutelab::effects
