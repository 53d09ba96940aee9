#pragma once
// A triangle mesh wall (impact plate, chute, belt). Vertices with equal coordinates are welded so that
// a sphere touching an edge or vertex shared by several triangles makes one contact, not several.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "dem/types.h"

namespace chutelab::dem {

struct TriangleMesh {
  std::vector<Vec3> vertices;                        // welded vertices
  std::vector<std::array<std::int32_t, 3>> triangles; // indices into vertices
  std::string source;                                // file it came from, for messages

  // Builds a welded mesh from a triangle soup (3 corners per triangle).
  static TriangleMesh from_soup(const std::vector<std::array<Vec3, 3>>& soup, std::string source = {});
  void transform(const Mat3& rotation, const Vec3& translation);  // p -> R p + t
  void scale(double factor);
  Box bounds() const;
};

}  // namespace chutelab::dem
