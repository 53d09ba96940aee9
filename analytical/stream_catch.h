#pragma once
// Which part of the stream the plate catches, and the forces of that part.
//
// Booth's streamlines are the layers of the belt load: the layer at height e above the belt (under
// the load's centre) leaves the pulley at radius R_b + e. Every layer rides the belt at V_b
// (continuity, A = m_s / (rho_bl V_b)), so the layers below e carry the share of the mass flow that
// the load's cross-section below e is of the whole (load_area_below). Where a layer crosses the
// plate line is flown for four layers (e = 0, a1, h_b/2, h_b) and taken linearly in e between them:
// exact for a high-speed discharge without forces in flight (the layers leave horizontally at V_b
// from heights R_b + e, so their parabolas are one curve shifted by e), and the way a spread effect,
// which turns only the two limits, is shared among the layers between them. A layer crossing the
// plate line above the top edge passes over the plate; one crossing below the foot falls past it;
// neither loads the plate. A limit that never reaches the plate line is taken to cross it at the
// foot (as the impact zone does): its layers count as caught.
//
// The forces of the caught part: Korzen's Eqs 5-7 are linear in the mass flow, and the caught layers
// are taken to strike with the Korzen centroid's speed and angle (analyse_transfer refuses a stream
// whose centroids miss the plate, so the caught part always holds the centroid's layer): the caught
// fraction of R_n and R_s. The layers' speeds and angles at the plate differ by a few per cent
// across h_b (estimate's streamline table shows them), which bounds what this assumption moves.
#include <optional>

#include "analytical/transfer_station.h"

namespace chutelab::analytical {

struct StreamCatch {
  double caught = 1.0;     // fraction of the mass flow that meets the plate face
  double over_top = 0.0;   // fraction passing above the plate's top edge
  double past_foot = 0.0;  // fraction falling past the plate's foot
  double normal_force = 0.0;  // N, R_n of the caught part
  double shear_force = 0.0;   // N, R_s of the caught part
  std::optional<double> top_edge_layer;   // m, e of the layer that meets the top edge (some pass over)
  std::optional<double> foot_edge_layer;  // m, e of the layer that meets the foot (some fall past)
  bool whole() const { return over_top == 0.0 && past_foot == 0.0; }
};

StreamCatch stream_catch(const TransferAnalysis& a);

}  // namespace chutelab::analytical
