#pragma once
// A wall: a shape (plane, cylinder or triangle mesh) in its reference pose, a prescribed rigid motion
// that moves the shape, and an optional surface velocity that does not move it (a conveyor belt, a
// rotating pulley). The World accumulates the contact force and torque on every wall and the force on
// every triangle (pressure and wear maps), so a wall can be read as a load cell.
#include <string>
#include <variant>
#include <vector>

#include "dem/types.h"
#include "dem/walls/cylinder.h"
#include "dem/walls/plane.h"
#include "dem/walls/triangle_mesh.h"

namespace chutelab::dem {

// Rigid motion with constant velocities: the pivot translates with `velocity` and the shape rotates
// about the pivot with `omega` (axis fixed in space). Pose at time t is exact, not integrated.
struct WallMotion {
  Vec3 velocity = Vec3::Zero();
  Vec3 omega = Vec3::Zero();
  Vec3 pivot = Vec3::Zero();  // at t = 0
  bool moving() const { return !velocity.isZero(0.0) || !omega.isZero(0.0); }
};

using WallShape = std::variant<Plane, Cylinder, TriangleMesh>;

struct Wall {
  std::string name;
  WallShape shape;          // reference geometry (t = 0)
  int material = 0;
  WallMotion motion;
  RigidVelocity surface;    // in the reference frame; rotates and moves with the wall
  Vec3 load_point = Vec3::Zero();  // torque reference point, reference frame

  // --- state, maintained by World ---
  WallShape current;        // geometry at the current time
  Mat3 rotation = Mat3::Identity();
  Vec3 pivot_now = Vec3::Zero();
  Vec3 force = Vec3::Zero();        // total contact force on the wall, N
  Vec3 torque = Vec3::Zero();       // about the current load point, N m
  std::vector<Vec3> element_force;  // per triangle (mesh) or one entry (primitive), N
  // Per triangle of `current`: (b - a) x (c - a) and its squared norm, or +inf for a sliver (whose
  // normal is inexact); the contact pre-test's plane (a mesh's vertices only move with the wall).
  struct FacePlane {
    Vec3 n;
    double nn;
  };
  std::vector<FacePlane> face_plane;

  static Wall plane(std::string name, const Vec3& point, const Vec3& normal, int material);
  static Wall cylinder(std::string name, const Vec3& point, const Vec3& axis, double radius, int material,
                       bool inside = false);
  static Wall mesh(std::string name, TriangleMesh mesh, int material);

  // Geometry and velocity at the current time.
  Vec3 to_world(const Vec3& p_ref) const { return pivot_now + rotation * (p_ref - motion.pivot); }
  Vec3 velocity_at(const Vec3& p) const {
    Vec3 v = motion.velocity + motion.omega.cross(p - pivot_now);
    if (!surface.zero()) v += rotation * surface.linear + (rotation * surface.omega).cross(p - to_world(surface.centre));
    return v;
  }
  Vec3 angular_velocity() const { return motion.omega + rotation * surface.omega; }
  std::size_t element_count() const;
  // Sets the pose for time t (updates `current`).
  void set_time(double t);
};

// Largest distance of a wall's geometry from its pivot (for the displacement bound of a rotating
// wall); +inf for an unbounded shape that the rotation does not map onto itself.
double reach_from_pivot(const Wall& w);

}  // namespace chutelab::dem
