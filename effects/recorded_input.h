#pragma once
// A recorded input that may be wrong (effects/registry.h, EffectInfo::Kind::record): the rig as it
// really was is the record with one number changed. Each input is one file in effects/ that says
// which number and how its strength (truth minus record, in the unit of the boundary) changes it.
#include <functional>
#include <memory>
#include <string>
#include <utility>

#include "analytical/effect.h"

namespace chutelab::effects {

class RecordedInput final : public analytical::Effect {
 public:
  using Apply = std::function<void(Station&, double)>;
  RecordedInput(std::string name, double strength, Apply apply)
      : name_(std::move(name)), strength_(strength), apply_(std::move(apply)) {}
  std::string name() const override { return name_; }
  void adjust_station(Station& s) const override { apply_(s, strength_); }

 private:
  std::string name_;
  double strength_;
  Apply apply_;
};

// Strengths of offsets in mm or degrees, and of relative errors in %, against SI records.
inline constexpr double kMm = 1e-3;
inline constexpr double kDeg = 3.14159265358979323846 / 180.0;
inline constexpr double kPercent = 1e-2;

// EffectInfo::make of a record: the station with `apply` done at the strength asked for.
inline std::function<std::shared_ptr<const analytical::Effect>(double)> recorded_input(std::string name,
                                                                                       RecordedInput::Apply apply) {
  return [name = std::move(name), apply = std::move(apply)](double strength) {
    return std::make_shared<RecordedInput>(name, strength, apply);
  };
}

// EffectInfo::width_in_unit of an offset whose unit is `unit` in SI (kMm, kDeg): a stated
// uncertainty does not depend on the station.
inline std::function<double(const Station&, double)> offset_width(double unit) {
  return [unit](const Station&, double u) { return u / unit; };
}

// ... of a relative error in %: the stated uncertainty against the recorded value at that station.
inline std::function<double(const Station&, double)> relative_width(double (*recorded)(const Station&)) {
  return [recorded](const Station& s, double u) { return u / recorded(s) / kPercent; };
}

}  // namespace chutelab::effects
