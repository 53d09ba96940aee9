#pragma once
// Small value types shared by the DEM engine. SI units throughout.
#include <Eigen/Core>
#include <Eigen/Geometry>

// Contact laws are tiny functions called from one hot loop; the loop is too large for GCC's inliner
// budget, so they are forced inline.
#define CHUTELAB_INLINE [[gnu::always_inline]] inline

namespace chutelab::dem {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;

// Axis-aligned box [lo, hi].
struct Box {
  Vec3 lo = Vec3::Zero();
  Vec3 hi = Vec3::Zero();
  bool contains(const Vec3& p) const {
    return p.x() >= lo.x() && p.y() >= lo.y() && p.z() >= lo.z() && p.x() <= hi.x() &&
           p.y() <= hi.y() && p.z() <= hi.z();
  }
  bool empty() const { return !(hi.x() > lo.x() && hi.y() > lo.y() && hi.z() > lo.z()); }
};

// Velocity field of a rigid body: v(p) = linear + omega x (p - centre).
struct RigidVelocity {
  Vec3 linear = Vec3::Zero();
  Vec3 omega = Vec3::Zero();
  Vec3 centre = Vec3::Zero();
  Vec3 at(const Vec3& p) const { return linear + omega.cross(p - centre); }
  bool zero() const { return linear.isZero(0.0) && omega.isZero(0.0); }
};

}  // namespace chutelab::dem
