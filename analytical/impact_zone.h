#pragma once
// Where the stream strikes the plate, analytically: the band of the plate face between the hits of
// Booth's outer streamlines (lower limit e = 0, upper limit e = h_b; a stream_spread effect turns
// them apart, so it widens the band), as wide as the load on the belt (the chord W: Booth's flight
// has no lateral force, so the stream keeps its loaded width), clipped to the plate. Korzen's normal
// force R_n (reference study Eq 5) and shear force R_s (Eq 6/7) of the part of the stream that meets
// the plate (analytical/stream_catch.h: all of it unless some passes over the top edge or falls past
// the foot) spread evenly over that band give the mean pressure and shear stress a designer compares
// with a DEM or pressure-film map. The even spread is the simplest reading that conserves the force;
// the real profile peaks near the centroid's hit.
#include "analytical/stream_catch.h"
#include "analytical/transfer_station.h"

namespace chutelab::analytical {

struct ImpactZone {
  double top_along = 0.0;     // m below the plate's top edge (edge of the band nearest the top)
  double bottom_along = 0.0;  // m below the plate's top edge
  double top_y = 0.0;         // m, y of the band's top edge on the face
  double bottom_y = 0.0;      // m
  double centroid_y = 0.0;    // m, hit of the CEMA centroid streamline
  double width = 0.0;         // m, across the plate (z), centred on z = 0
  double area = 0.0;          // m^2 of plate face loaded
  double mean_pressure = 0.0;      // Pa, R_n of the caught part / area
  double mean_shear_stress = 0.0;  // Pa, R_s of the caught part / area
  bool top_clipped = false;        // part of the stream passes above the top edge
  bool bottom_clipped = false;     // part of the stream falls past the plate's foot
  StreamCatch caught;              // how much of the stream the band takes, and its forces
  double length() const { return bottom_along - top_along; }
};

// The impact zone of an analysed condition. The centroid lines are on the plate (analyse_transfer
// guarantees it), so the band is never empty.
ImpactZone impact_zone(const TransferAnalysis& a);

}  // namespace chutelab::analytical
