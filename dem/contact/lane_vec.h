#pragma once
// The 3-vector the contact laws compute with: three plain doubles and inline arithmetic, nothing
// else. The pair loop runs the laws over chunks of contacts (dem/forces.cpp) and the compiler
// vectorises that loop across contacts only when every operation in it is plain scalar code; Eigen's
// hand-written SSE for 3-vectors hides the loop from the vectoriser. Converts to and from Vec3.
#include "dem/types.h"

namespace chutelab::dem {

struct LaneVec {
  double x, y, z;

  static LaneVec zero() { return {0.0, 0.0, 0.0}; }
  static LaneVec of(const Vec3& v) { return {v.x(), v.y(), v.z()}; }
  Vec3 eigen() const { return {x, y, z}; }

  double dot(const LaneVec& o) const { return x * o.x + y * o.y + z * o.z; }
  double squared_norm() const { return x * x + y * y + z * z; }
  LaneVec cross(const LaneVec& o) const { return {y * o.z - z * o.y, z * o.x - x * o.z, x * o.y - y * o.x}; }

  LaneVec operator+(const LaneVec& o) const { return {x + o.x, y + o.y, z + o.z}; }
  LaneVec operator-(const LaneVec& o) const { return {x - o.x, y - o.y, z - o.z}; }
  LaneVec operator-() const { return {-x, -y, -z}; }
  LaneVec operator*(double s) const { return {x * s, y * s, z * s}; }
  friend LaneVec operator*(double s, const LaneVec& v) { return {s * v.x, s * v.y, s * v.z}; }
  LaneVec& operator+=(const LaneVec& o) { return *this = *this + o; }
  LaneVec& operator-=(const LaneVec& o) { return *this = *this - o; }
  LaneVec& operator*=(double s) { return *this = *this * s; }
};

// Component-wise select (a ? b : c) written so that it stays a select, not a branch.
inline LaneVec select(bool pick_b, const LaneVec& b, const LaneVec& c) {
  return {pick_b ? b.x : c.x, pick_b ? b.y : c.y, pick_b ? b.z : c.z};
}

}  // namespace chutelab::dem
