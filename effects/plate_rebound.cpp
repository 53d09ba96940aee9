// plate_rebound: part of the stream bounces off the plate instead of joining the layer on it.
//
// Physics: Korzen's control volume assumes the stream loses its whole normal momentum on the
// plate (R_n = m_s V_pn, reference study Eq 5). If particles rebound with an effective stream restitution
// e_s, they carry normal momentum back and R_n = m_s V_pn (1 + e_s); the sliding layer, and so
// R_s, is unchanged. e_s is dimensionless, 0 = the reference study's model; physical range 0-0.6, well below
// the single-particle restitution (0.66 on mild steel, reference study Table 2) because most particles strike
// the layer already on the plate, not the bare plate.
// Hook: plate interaction. DEM: ignored, with a note in the prediction. e_s corrects Korzen's
// control volume, in which no normal momentum comes back off the plate; a DEM resolves the rebound
// itself (particle-plate and particle-particle restitution, the layer on the plate), so its R_n
// already contains it. No DEM input gives a chosen e_s: at quick quality the DEM's own
// e_s = R_n / (m_s V_pn) - 1 moved only from 0.05 to 0.14 on the tiny test rig (2.5 kg/s, 3 m/s)
// and from 0.03 to 0.06 at V3-41 of the LIGGGHTS rig as the particle-plate restitution went from
// 0.2 to 1.0: the layer on the plate takes the blows, and no plate restitution reaches this
// effect's range.
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
