// Booth trajectories with the CEMA load-shape centroid (the reference study's "Booth/CEMA hybrid"): stream
// limits, the centroid's impact point and its speed at the plate.
#include "analytical/transfer_station.h"
#include "validation/models/models.h"

namespace chutelab::validation {
namespace {

class BoothCemaModel final : public Model {
 public:
  std::string name() const override { return "booth-cema"; }
  std::string description() const override {
    return "Booth discharge trajectories, CEMA load-shape centroid";
  }
  ModelPrediction predict(const Station& st, const analytical::EffectList& effects,
                          const PredictRequest& request) const override {
    return predict_from(analytical::analyse_transfer(st, effects), effects, request);
  }
  bool reads_transfer_analysis() const override { return true; }
  ModelPrediction predict_from(const analytical::TransferAnalysis& a, const analytical::EffectList& effects,
                               const PredictRequest& request) const override {
    using analytical::Streamline;
    const Station& st = a.station;
    const auto& hit = *a.line(Streamline::cema_centroid).hit;
    ModelPrediction p;
    p.values[Quantity::impact_velocity] = hit.speed;
    p.values[Quantity::impact_point_y] = hit.point.position.y();
    // The layer on the belt moves at the discharge speed of Booth's analysis (V_b unless an effect
    // slows it), and the whole delivered flow flies (continuity).
    analytical::DischargeInput di{st.belt.belt_radius(), a.operating.belt_speed, st.belt.incline, st.gravity, 0.0, 0.0};
    for (const auto& e : effects) e->adjust_discharge(di, st);
    p.values[Quantity::belt_layer_velocity] = di.speed;
    p.values[Quantity::stream_mass_flow] = a.operating.mass_flow;
    p.trajectory.reserve(request.trajectory.size());
    for (const auto& q : request.trajectory) {
      const Streamline s = q.boundary == Boundary::upper   ? Streamline::upper
                           : q.boundary == Boundary::lower ? Streamline::lower
                                                           : Streamline::cema_centroid;
      const auto pt = a.line(s).trajectory.at_x(q.x);
      p.trajectory.push_back(pt ? std::optional<double>(pt->position.y()) : std::nullopt);
    }
    if (request.curves) {
      p.curves.push_back(streamline_curve(a, Streamline::upper, "upper"));
      p.curves.push_back(streamline_curve(a, Streamline::cema_centroid, "centre (CEMA a1)"));
      p.curves.push_back(streamline_curve(a, Streamline::lower, "lower"));
    }
    return p;
  }
};

}  // namespace

ModelPtr make_booth_cema_model() { return std::make_shared<BoothCemaModel>(); }

}  // namespace chutelab::validation
