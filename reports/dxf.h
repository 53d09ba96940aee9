#pragma once
// The design as a drawing a designer pastes into CAD: ASCII DXF R12 (AC1009), which every CAD
// program reads. Millimetres, the DESIGN.md frame (origin at the pulley centre, x towards the plate,
// y up). One layer per part: the pulley and the belt's outer circle, the plate face, the analytical
// impact zone on it, and one 2D polyline per streamline with the points of
// analytical/streamline_path.h (the numbers of `estimate --format json`, written in full precision).
#include <string>

#include "reports/design.h"

namespace chutelab::reports {

std::string design_dxf(const DesignDrawing& d);

// The DXF layer of a streamline ("STREAMLINE_UPPER", ...).
std::string dxf_layer(Streamline s);

}  // namespace chutelab::reports
