#pragma once
// Where a sphere touches a wall: the contact geometry alone (normal, overlap, contact point), as
// LAMMPS' fix wall/gran computes only the geometry and hands it to the contact law the pairs use
// (dem/wall_forces.h). Planes and cylinders have one element; a triangle mesh has one per triangle.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <variant>

#include "dem/types.h"
#include "dem/walls/closest_point.h"
#include "dem/walls/wall.h"

namespace chutelab::dem {

// One element touched by a sphere.
struct WallHit {
  Vec3 n;        // unit, from the sphere centre towards the wall
  double delta;  // overlap
  Vec3 point;    // contact point on the wall surface
  TriFeature feature;
};

inline bool plane_contact(const Plane& p, const Vec3& x, double r, WallHit& g) {
  const Vec3 rel = x - p.point;
  const double s = rel.dot(p.normal);
  if (s >= r) return false;
  if (std::abs(rel.dot(p.axis_u)) > p.half_u || std::abs(rel.dot(p.axis_v)) > p.half_v) return false;
  g.n = -p.normal;
  g.delta = r - s;
  g.point = x - s * p.normal;
  g.feature = TriFeature::face;
  return true;
}

inline bool cylinder_contact(const Cylinder& c, const Vec3& x, double r, WallHit& g) {
  const Vec3 rel = x - c.point;
  const double a = rel.dot(c.axis);
  if (a < c.axial_min || a > c.axial_max) return false;
  const Vec3 radial = rel - a * c.axis;
  const double rho = radial.norm();
  if (!(rho > 0.0)) return false;
  const Vec3 out = radial / rho;
  const double gap = c.inside ? c.radius - rho : rho - c.radius;  // centre to surface
  if (gap >= r) return false;
  g.n = c.inside ? out : Vec3(-out);
  g.delta = r - gap;
  g.point = c.point + a * c.axis + c.radius * out;
  g.feature = TriFeature::face;
  return true;
}

// The triangles elements[0, count) of mesh wall w that a sphere (centre x, radius r) touches:
// hit[k] = 1 with the geometry in geo[k]. Within the mesh, face contacts win over edge contacts and
// edges over vertices, so a sphere on a flat or convex seam touches once.
void mesh_contacts(const Wall& w, const TriangleMesh& m, const std::int32_t* elements, std::size_t count, const Vec3& x,
                   double r, WallHit* geo, char* hit);

// The contacts of a sphere with the candidate elements elements[0, count) of wall w (its current
// pose); hit must be zero on entry.
inline void wall_contacts(const Wall& w, const std::int32_t* elements, std::size_t count, const Vec3& x, double r,
                          WallHit* geo, char* hit) {
  if (const auto* m = std::get_if<TriangleMesh>(&w.current)) {
    mesh_contacts(w, *m, elements, count, x, r, geo, hit);
  } else if (const auto* p = std::get_if<Plane>(&w.current)) {
    for (std::size_t k = 0; k < count; ++k) hit[k] = plane_contact(*p, x, r, geo[k]);
  } else {
    for (std::size_t k = 0; k < count; ++k) hit[k] = cylinder_contact(std::get<Cylinder>(w.current), x, r, geo[k]);
  }
}

}  // namespace chutelab::dem
