#pragma once
// The designer's pictures: one design (pulley, belt, streamlines, plate, impact point and the
// Korzen readout) and a sweep chart (impact points and plate forces against one input). The same
// code draws `estimate --svg` on the terminal and the designer's page in the browser (compiled to
// WebAssembly), so the two cannot disagree.
#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "core/quantity.h"
#include "core/rig.h"

namespace chutelab::reports {

// The four streamlines drawn, in the order of the analytical chain's (analytical/transfer_station.h).
enum class Streamline { lower, upper, cema_centroid, korzen_centroid };
inline constexpr std::array<Streamline, 4> kAllStreamlines = {
    Streamline::lower, Streamline::upper, Streamline::cema_centroid, Streamline::korzen_centroid};

// A design as the drawings take it: the station and what the estimate computed for it (the
// drawings compute no physics; api/design_drawing.h fills this from the analytical chain). SI, the
// DESIGN.md frame (origin at the pulley centre, x towards the plate, y up).
struct DesignDrawing {
  struct Line {
    std::vector<Eigen::Vector2d> path;  // m: round the pulley and in flight (analytical/streamline_path.h)
    Eigen::Vector2d release = Eigen::Vector2d::Zero();  // m, where it leaves the pulley
    bool high_speed = false;            // Booth: left at the tangent point
    double release_ratio = 0.0;         // K = V^2 / (g r)
    struct Hit {
      Eigen::Vector2d point = Eigen::Vector2d::Zero();  // m
      double alpha = 0.0;               // rad below the horizontal
      bool on_plate = false;
    };
    std::optional<Hit> hit;             // absent when it never reaches the plate line
  };
  // The analytical impact zone (analytical/impact_zone.h).
  struct Zone {
    double top_along = 0.0, bottom_along = 0.0;  // m below the plate's top edge
    double top_y = 0.0, bottom_y = 0.0;          // m
    double width = 0.0;                          // m
    double mean_pressure = 0.0, mean_shear_stress = 0.0;  // Pa
    bool top_clipped = false, bottom_clipped = false;
  };
  Station station;
  double load_height = 0.0;             // h_b, m
  double load_contact_width = 0.0;      // m, the load's width on the belt
  bool thickness_from_continuity = false;
  std::array<Line, 4> lines;            // by Streamline
  Zone zone;
  bool stationary_flow = false;         // Korzen's Eq 3
  std::string shear_equation;           // "Eq 6" or "Eq 7"
  double plate_friction = 0.0;          // mu_pw as the plate acts
  const Line& line(Streamline s) const { return lines[static_cast<std::size_t>(s)]; }
};

// `korzen` is what the Korzen model reports for this design (measurement effects applied), shown
// beside the drawing; the drawing itself is the physical stream of `d`.
std::string design_svg(const DesignDrawing& d, const QuantityValues& korzen, std::string_view id = "design");

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
