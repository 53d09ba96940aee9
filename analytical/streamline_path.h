#pragma once
// The path of one streamline as a designer draws and exports it: from the point where the belt
// meets the pulley (the top of the wrap, at the streamline's height above the belt) round the
// pulley to its release point, then its flight to the plate line (or 1 s of flight when it never
// gets there). One function for the drawing, the DXF, the CSV and estimate's JSON, so the points
// are the same numbers everywhere.
#include <vector>

#include <Eigen/Core>

#include "analytical/transfer_station.h"

namespace chutelab::analytical {

// Points in m, DESIGN.md frame (origin at the pulley centre, x towards the plate, y up).
std::vector<Eigen::Vector2d> streamline_path(const TransferAnalysis& a, Streamline which);

}  // namespace chutelab::analytical
