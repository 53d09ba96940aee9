#pragma once
// What the designer's drawings (reports/design.h: the SVG, the DXF) take from an estimate: the
// analytical chain's streamline paths, release and impact points, impact zone and Korzen verdict,
// computed here so that the drawings only draw.
#include "analytical/transfer_station.h"
#include "reports/design.h"

namespace chutelab::api {

reports::DesignDrawing design_drawing(const analytical::TransferAnalysis& a);

}  // namespace chutelab::api
