#pragma once
// A recorded input that may be wrong (effects/registry.h, EffectInfo::Kind::record): the rig as it
// really was is the record with one number changed. Each input is one file in effects/ that says
// which number and how its strength (truth minus record, in the unit of the boundary) changes it.
#include <functional>
#include <optional>
#include <stdexcept>
#include <memory>
#include <string>
#include <string_view>
#include <utility>

#include "analytical/effect.h"
#include "core/input_error.h"
#include "core/rig.h"
#include "effects/registry.h"

namespace chutelab::effects {

class RecordedInput final : public analytical::Effect {
 public:
  using Apply = std::function<void(Station&, double)>;
  RecordedInput(std::string name, double strength, Apply apply, RecordLimits limits = {})
      : name_(std::move(name)), strength_(strength), apply_(std::move(apply)), limits_(std::move(limits)) {}
  std::string name() const override { return name_; }
  // Throws InputError (field: the record's name) where the input as really built is impossible.
  void adjust_station(Station& s) const override {
    const auto recorded = limits_.value ? limits_.value(s) : std::nullopt;
    apply_(s, strength_);
    if (!recorded) return;
    if (const auto now = limits_.value(s))
      if (std::string p = limits_.problem(*now, *recorded); !p.empty()) throw InputError("", 0, name_, p);
  }

 private:
  std::string name_;
  double strength_;
  Apply apply_;
  RecordLimits limits_;
};

// Strengths of offsets in mm or degrees, and of relative errors in %, against SI records.
inline constexpr double kMm = 1e-3;
inline constexpr double kPercent = 1e-2;

// A record effect's station change and its limits, declared once: `make` builds the change at a
// strength and checks the limits, `limits` tells the callers that check a value before any run.
inline void set_record(EffectInfo& e, RecordedInput::Apply apply, RecordLimits limits) {
  e.kind = EffectInfo::Kind::record;
  e.limits = limits;
  e.make = [name = e.name, apply = std::move(apply), limits = std::move(limits)](double strength) {
    return std::make_shared<RecordedInput>(name, strength, apply, limits);
  };
}

// The limits of a rig field (core/rig.h: the physical range the dataset reader holds its key to).
inline RecordLimits rig_field_limits(std::string_view key, std::string what, std::string unit,
                                     std::function<double(const Station&)> value) {
  for (const auto& f : rig_fields())
    if (f.key == key)
      return {std::move(what), std::move(unit), f.to_si, f.min, f.max, false,
              [value = std::move(value)](const Station& s) { return std::optional<double>(value(s)); }};
  throw std::logic_error("no rig field " + std::string(key));
}

// EffectInfo::width_in_unit of an offset whose unit is `unit` in SI (kMm, units::deg): a stated
// uncertainty does not depend on the station.
inline std::function<double(const Station&, double)> offset_width(double unit) {
  return [unit](const Station&, double u) { return u / unit; };
}

// ... of a relative error in %: the stated uncertainty against the recorded value at that station.
inline std::function<double(const Station&, double)> relative_width(double (*recorded)(const Station&)) {
  return [recorded](const Station& s, double u) { return u / recorded(s) / kPercent; };
}

}  // namespace chutelab::effects
