// mass_flow_bias: the recorded mass flow is not the flow that reached the plate.
//
// Physics: the reference study set its feeder "at approximately 20 and 40 tph" and recalculated the flow from
// the bin's load cells (section 4.1); a calibration error or spillage before the pulley makes the
// true flow m_true = (1 + b) m_recorded. Every force scales with it (Eq 5, 6, 7) and, where the
// stream thickness comes from continuity, so does h_b and with it the impact point. b is a
// fraction, 0 = the record is right; physical range -0.3 to +0.3.
// Hook: the operating point (the measurement of an input). DEM: honoured — the feed inserts
// (1 + b) m_recorded.
#include "effects/registry.h"

namespace chutelab::effects {
namespace {

class MassFlowBias final : public analytical::Effect {
 public:
  explicit MassFlowBias(double b) : b_(b) {}
  std::string name() const override { return "mass_flow_bias"; }
  void adjust_operating_point(analytical::OperatingPoint& op) const override {
    op.mass_flow *= 1.0 + b_;
  }

 private:
  double b_;
};

const Registration registration({
    "mass_flow_bias", "flow_bias", "", "inputs",
    "m_true = (1 + b) m_recorded: all forces scale with (1 + b); h_b from continuity grows with it.",
    "Grima & Wypych (2010) section 4.1 (mass flow recalculated from load-cell data)",
    0.0, -0.3, 0.3, 0.1, [](double v) { return std::make_shared<MassFlowBias>(v); },
    "an independent mass-flow reading (a belt scale, timed bin weights, or the free-stream mass flux stream_mass_flow_tph)"});

}  // namespace
}  // namespace chutelab::effects
