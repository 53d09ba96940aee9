#pragma once
// The designer's pictures: one design (pulley, belt, streamlines, plate, impact point and the
// Korzen readout) and a sweep chart (impact points and plate forces against one input). The same
// code draws `estimate --svg` on the terminal and the designer's page in the browser (compiled to
// WebAssembly), so the two cannot disagree.
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "analytical/transfer_station.h"
#include "core/quantity.h"

namespace chutelab::reports {

// `korzen` is what the Korzen model reports for this design (measurement effects applied), shown
// beside the drawing; the drawing itself is the physical stream of `a`.
std::string design_svg(const analytical::TransferAnalysis& a, const QuantityValues& korzen,
                       std::string_view id = "design");

struct SweepSeries {
  std::string label;                     // plain text, e.g. "CEMA centroid (booth-cema)"
  std::string colour, dash;              // dash: stroke-dasharray, "" = solid
  std::vector<std::optional<double>> y;  // one per x; absent where the point has no answer
};

struct SweepChart {
  std::string x_label;                   // with unit, e.g. "plate distance (mm)"
  std::vector<double> x;
  std::vector<SweepSeries> impact_mm;    // top panel: y on the plate, mm
  std::vector<SweepSeries> forces_N;     // bottom panel: plate forces, N (axis from 0)
  // The plate's extent in y at each x (top panel, shaded), absent where unknown.
  std::vector<std::optional<double>> plate_top_mm, plate_bottom_mm;
  // Per x: why the design has no answer there ("" = it has one); runs of one reason are marked as
  // a band with a short label and the full reason as its tooltip.
  std::vector<std::string> gap_label, gap_reason;
  // Per x: where part of the stream misses the plate (over its top edge or past its foot), a short
  // label ("" = the plate takes the whole stream) and what the plate takes there as the tooltip;
  // runs of one label are banded in both panels, since the forces drawn are the whole stream's.
  std::vector<std::string> partial_label, partial_reason;
};

std::string sweep_svg(const SweepChart& c, std::string_view id = "sweep");

// An inline picture as a file of its own (XML declaration and SVG namespace).
std::string standalone_svg(std::string_view inline_svg);

}  // namespace chutelab::reports
