#pragma once
// The two frames the station's sensors measure in: the carrying belt near the head pulley and the
// impact plate's face. Both in the chutelab frame (DESIGN.md §1: origin at the head-pulley centre,
// x towards the plate, y up, z lateral), which is also the DEM frame (gravity (0, -g, 0)).
#include <cmath>

#include "dem/types.h"

namespace chutelab::dem::station {

struct BeltFrame {
  Vec3 tangent_point = Vec3::Zero();  // where the carrying belt meets the pulley (top when flat)
  Vec3 along = Vec3::UnitX();         // unit, direction of travel of the carrying side
  Vec3 up = Vec3::UnitY();            // unit normal of the belt surface, towards the load
  double radius = 0.0;                // R_b, pulley axis to belt surface
  // Belt coordinate of a point: < 0 upstream of the tangent point.
  double s(const Vec3& x) const { return (x - tangent_point).dot(along); }
  // Height above the (flat) belt surface.
  double h(const Vec3& x) const { return (x - tangent_point).dot(up); }
};

// The plate face: a rectangle through the top edge at (Z, plate_top), leaning its top towards the
// pulley by beta (DESIGN.md §1 and README "Extensions": alpha_p + beta is the angle of incidence).
struct PlateFrame {
  Vec3 top_edge = Vec3::Zero();   // (Z, plate_top, 0)
  Vec3 into = Vec3::UnitX();      // unit normal into the plate: R_n > 0 pushes the plate this way
  Vec3 down = -Vec3::UnitY();     // unit along the face, downward: R_s > 0 drags the plate this way
  Vec3 reference = Vec3::Zero();  // load-cell moment reference: the face point at y = 0
  double height = 0.0, width = 0.0, angle = 0.0;
  // Distance of a point in front of the face (> 0 on the stream's side).
  double in_front(const Vec3& x) const { return (top_edge - x).dot(into); }
  // Distance along the face above the reference point (of the point's projection).
  double up_from_reference(const Vec3& x) const { return -(x - reference).dot(down); }
  // y of the face point that lies `a` above the reference along the face.
  double y_at(double a) const { return reference.y() + a * std::cos(angle); }
  // Lowest point of the face.
  Vec3 bottom_edge() const { return top_edge + height * down; }
  // x of the face at height y.
  double face_x(double y) const { return top_edge.x() + (top_edge.y() - y) * std::tan(angle); }
};

}  // namespace chutelab::dem::station
