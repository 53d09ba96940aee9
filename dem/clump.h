#pragma once
// Rigid multi-sphere particles ("clumps"): a non-spherical grain made of overlapping spheres that move
// as one rigid body (Favier et al. 1999, reference [24] of the reference study, whose shaped pellet
// is two overlapping 4.4 mm spheres, Fig. 4c). Contacts are sphere contacts of the member spheres; the body's
// mass and inertia are those of the UNION of the spheres (overlaps counted once), not the sum, or a
// clump of strongly overlapping spheres would be too heavy and its rotation too slow.
//
// A ClumpShape is a template in its own principal frame: origin at the centre of mass, axes along the
// principal axes of inertia, so the inertia tensor is diagonal and the free rotation can be split into
// rotations about body axes (dem/rigid_rotation.h).
#include <string>
#include <vector>

#include "dem/types.h"

namespace chutelab::dem {

struct ClumpSphere {
  Vec3 offset = Vec3::Zero();  // centre, m (body frame)
  double radius = 0.0;         // m
};

// Volume properties of a solid (unit density): V, centroid, and the inertia tensor per unit density
// about the centroid, J = integral (|r|^2 I - r r^T) dV over the solid (kg m^2 per kg/m^3).
struct VolumeProperties {
  double volume = 0.0;  // m^3
  Vec3 centroid = Vec3::Zero();
  Mat3 inertia = Mat3::Zero();
  bool exact = false;   // closed form (no point lies in three spheres) or numerical quadrature
};

// Union of spheres. Exact by inclusion-exclusion when no point lies inside three spheres (then the
// union is the spheres minus their pairwise lenses, and a lens is two spherical caps, each integrated in
// closed form); otherwise a midpoint-rule quadrature on a grid of `cells` per longest box side.
VolumeProperties union_of_spheres(const std::vector<ClumpSphere>& spheres, int cells = 160);
// The quadrature alone (the fallback above, and a cross-check).
VolumeProperties union_of_spheres_quadrature(const std::vector<ClumpSphere>& spheres, int cells);

struct ClumpShape {
  std::string name;
  std::vector<ClumpSphere> spheres;     // principal frame, origin at the centre of mass
  double volume = 0.0;                  // m^3 of the union
  Vec3 principal_inertia = Vec3::Zero();  // per unit density, kg m^2 / (kg/m^3), ascending
  double bounding_radius = 0.0;         // m, max |offset| + radius: a sphere holding the clump

  // Moves the spheres to the centre of mass and rotates them to the principal axes (right-handed).
  // Throws InputError for no spheres or a non-positive radius.
  static ClumpShape from_spheres(std::vector<ClumpSphere> spheres, std::string name = "clump");
  // The reference study's shaped pellet (Fig. 4c): two spheres of diameter d whose centres are `spacing` apart.
  static ClumpShape two_sphere(double sphere_diameter, double spacing, std::string name = "two-sphere");
  // Pellet of the reference study's Table 1 at scale 1:1 (Fig. 4c): two 4.4 mm spheres, spaced 0.45 mm so that the
  // mean of the three axis widths, (3 x 4.4 + 0.45) / 3 mm, is the measured average pellet diameter
  // d_ave = 4.55 mm ("determined by averaging the measured widths ... across 3 axes", reference study §4).
  static ClumpShape reference_pellet();

  ClumpShape scaled(double factor) const;  // every length times factor
  double largest_sphere_radius() const;
  // Diameter of the sphere of equal volume, m.
  double equivalent_diameter() const;
};

}  // namespace chutelab::dem
