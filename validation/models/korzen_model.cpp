// The Korzen impact-plate model (reference study Eqs 1-7) as a harness model: plate forces, V_p, V_a and the
// impact point on Korzen's own centroid assumption (0.5 h_b).
#include <cmath>
#include <fmt/format.h>

#include "analytical/impact_zone.h"
#include "analytical/transfer_station.h"
#include "validation/models/models.h"

namespace chutelab::validation {
namespace {

class KorzenModel final : public Model {
 public:
  std::string name() const override { return "korzen"; }
  std::string description() const override {
    return "Korzen impact-plate model (reference study Eqs 1-7) on the 0.5 h_b streamline";
  }
  ModelPrediction predict(const Station& st, const analytical::EffectList& effects,
                          const PredictRequest& request) const override {
    return predict_from(analytical::analyse_transfer(st, effects), effects, request);
  }
  bool reads_transfer_analysis() const override { return true; }
  ModelPrediction predict_from(const analytical::TransferAnalysis& a, const analytical::EffectList&,
                               const PredictRequest& request) const override {
    using analytical::Streamline;
    const auto& k = a.korzen;
    const auto& hit = *a.line(Streamline::korzen_centroid).hit;
    ModelPrediction p;
    p.values[Quantity::normal_force] = k.normal_force;
    p.values[Quantity::shear_force] = k.shear_force;
    p.values[Quantity::resultant_force] = k.resultant_force;
    p.values[Quantity::impact_velocity] = hit.speed;
    if (k.exit_speed) p.values[Quantity::exit_velocity] = *k.exit_speed;
    p.values[Quantity::impact_point_y] = hit.point.position.y();
    p.trajectory.assign(request.trajectory.size(), std::nullopt);
    // The band the stream strikes, Korzen's forces spread evenly over it (analytical/impact_zone.h):
    // the mean pressure inside, none outside.
    const auto z = analytical::impact_zone(a);
    p.plate_zone = PlateZone{z.top_y, z.bottom_y, z.centroid_y, z.width, z.mean_pressure};
    for (const auto& q : request.plate) {
      const bool inside = q.y <= z.top_y && q.y >= z.bottom_y && std::abs(q.z) <= 0.5 * z.width;
      if (q.quantity == "plate_pressure_Pa") p.plate.emplace_back(inside ? z.mean_pressure : 0.0);
      else if (q.quantity == "plate_shear_stress_Pa") p.plate.emplace_back(inside ? z.mean_shear_stress : 0.0);
      else p.plate.emplace_back(std::nullopt);
    }
    if (request.curves)
      p.curves.push_back(streamline_curve(a, Streamline::korzen_centroid, "centre (0.5 h_b)"));
    p.notes.push_back(k.stationary_flow
                          ? fmt::format("stationary flow; V_a from Eq 4 ({} iterations), R_s from Eq 6",
                                        k.iterations)
                          : "no stationary flow (Eq 3): Eq 4 has no solution, R_s from Eq 7");
    return p;
  }
};

}  // namespace

ModelPtr make_korzen_model() { return std::make_shared<KorzenModel>(); }

}  // namespace chutelab::validation
