#pragma once
// CEMA load cross-section on the belt: the flat belt carries a circular-segment surcharge of chord W
// and height h_b; the 3-roll troughed belt carries a trapezoid on the rolls topped by a circular
// surcharge arc meeting the load edges at the surcharge angle (CEMA, Belt Conveyors for Bulk
// Materials, 6th ed., ch. 4). Heights are measured from the belt surface under the load's centre.
#include "core/rig.h"

namespace chutelab::analytical {

struct LoadShape {
  double area = 0.0;             // m^2
  double height = 0.0;           // h_b, m: top of the load above the belt centre line
  double centroid_height = 0.0;  // a1, m: centroid above the belt centre line
  double contact_width = 0.0;    // m, belt width wetted by the load, measured along the belt
};

// Circular segment of chord `chord` and rise `height` (0 < height <= chord/2).
LoadShape flat_segment(double chord, double height);

// Troughed load touching `contact_width` of belt (centre roll + equal lengths up each wing).
// When the contact width is no more than the centre roll the load is a segment on the centre roll
// with the surcharge angle at its edges.
LoadShape troughed_load(const Trough& trough, double contact_width);

// The load shape of a belt carrying a stream of thickness h_b: the flat belt keeps its loaded
// width as chord; the troughed belt keeps its surcharge angle and widens its contact.
// Throws InputError when no shape of that height fits the belt.
LoadShape load_shape_for_thickness(const Belt& belt, double thickness);

// The load shape carrying `mass_flow` at `belt_speed` (continuity: A = m / (rho_bl V_b)).
// Throws InputError when the belt cannot carry the flow.
LoadShape load_shape_for_flow(const Belt& belt, double mass_flow, double bulk_density,
                              double belt_speed);

// The fullest load the belt holds: the flat belt's half disc on its loaded width, the troughed
// belt's load touching its whole loaded width. Its area is the bound load_shape_for_flow checks
// (the belt's capacity is this area times rho_bl V_b), its height the bound of
// load_shape_for_thickness.
LoadShape largest_load(const Belt& belt);

// The part of `load`'s cross-section below height e above the belt centre line (0 <= e <= h_b),
// m^2: the whole area at e = h_b. `load` is a shape of `belt` (one of the functions above).
double load_area_below(const Belt& belt, const LoadShape& load, double e);

}  // namespace chutelab::analytical
