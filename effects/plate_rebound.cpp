// plate_rebound: part of the stream bounces off the plate instead of joining the layer on it.
//
// Physics: Korzen's control volume assumes the stream loses its whole normal momentum on the
// plate (R_n = m_s V_pn, seed Eq 5). If particles rebound with an effective stream restitution
// e_s, they carry normal momentum back and R_n = m_s V_pn (1 + e_s); the sliding layer, and so
// R_s, is unchanged. e_s is dimensionless, 0 = the seed's model; physical range 0-0.6, well below
// the single-particle restitution (0.66 on mild steel, seed Table 2) because most particles strike
// the layer already on the plate, not the bare plate.
// Hook: plate interaction. DEM counterpart: particle-plate restitution (a DEM plate shows rebound
// by itself).
#include "effects/registry.h"

namespace chutelab::effects {
namespace {

class PlateRebound final : public analytical::Effect {
 public:
  explicit PlateRebound(double e) : e_(e) {}
  std::string name() const override { return "plate_rebound"; }
  void adjust_plate(analytical::PlateInteraction& p) const override { p.rebound += e_; }

 private:
  double e_;
};

const Registration registration({
    "plate_rebound", "stream_restitution", "", "plate",
    "R_n = m_s V_pn (1 + e_s): rebounding particles return a fraction e_s of the normal momentum; "
    "R_s is unchanged.",
    "Korzen (1988) control volume with a rebound term; single-particle restitution in Grima & "
    "Wypych (2010) Table 2",
    0.0, 0.0, 0.6, 0.15, [](double v) { return std::make_shared<PlateRebound>(v); }});

}  // namespace
}  // namespace chutelab::effects
