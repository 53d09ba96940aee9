#include "effects/at_condition.h"

#include <map>
#include <memory>
#include <mutex>

namespace chutelab::effects {
namespace {

class AtCondition final : public analytical::Effect {
 public:
  AtCondition(std::shared_ptr<const analytical::Effect> inner, std::string condition)
      : inner_(std::move(inner)), condition_(std::move(condition)) {}
  std::string name() const override { return inner_->name() + "@" + condition_; }
  bool acts_at(const Station& s) const override { return s.condition == condition_ && inner_->acts_at(s); }
  void adjust_station(Station& s) const override { inner_->adjust_station(s); }
  void adjust_operating_point(analytical::OperatingPoint& op) const override { inner_->adjust_operating_point(op); }
  void adjust_discharge(analytical::DischargeInput& d, const Station& s) const override {
    inner_->adjust_discharge(d, s);
  }
  bool has_flight_force() const override { return inner_->has_flight_force(); }
  Eigen::Vector2d flight_acceleration(const Eigen::Vector2d& v, const analytical::FlightContext& c) const override {
    return inner_->flight_acceleration(v, c);
  }
  void adjust_release(Boundary b, Eigen::Vector2d& v) const override { inner_->adjust_release(b, v); }
  void adjust_plate(analytical::PlateInteraction& p) const override { inner_->adjust_plate(p); }
  void adjust_measurement(QuantityValues& v) const override { inner_->adjust_measurement(v); }
  void adjust_trajectory(std::vector<std::optional<double>>& y) const override { inner_->adjust_trajectory(y); }

 private:
  std::shared_ptr<const analytical::Effect> inner_;
  std::string condition_;
};

}  // namespace

EffectInfo at_condition(const EffectInfo& record, const std::string& condition) {
  EffectInfo c = record;
  c.name = record.name + "@" + condition;
  c.make = [make = record.make, condition](double v) { return std::make_shared<AtCondition>(make(v), condition); };
  return c;
}

std::pair<std::string, std::string> split_condition(const std::string& name) {
  const auto at = name.find('@');
  if (at == std::string::npos) return {name, ""};
  return {name.substr(0, at), name.substr(at + 1)};
}

const EffectInfo* find_candidate(const std::string& name) {
  const auto [base, condition] = split_condition(name);
  const EffectInfo* e = find(base);
  if (!e || condition.empty()) return e;
  static std::mutex guard;
  static std::map<std::string, std::unique_ptr<const EffectInfo>> made;
  const std::lock_guard lock(guard);
  auto& slot = made[name];
  if (!slot) slot = std::make_unique<const EffectInfo>(at_condition(*e, condition));
  return slot.get();
}

}  // namespace chutelab::effects
