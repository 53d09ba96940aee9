#include "dem/walls/triangle_mesh.h"

#include <map>
#include <tuple>

namespace chutelab::dem {

TriangleMesh TriangleMesh::from_soup(const std::vector<std::array<Vec3, 3>>& soup, std::string source) {
  TriangleMesh m;
  m.source = std::move(source);
  std::map<std::tuple<double, double, double>, std::int32_t> index;  // exact-coordinate welding
  for (const auto& tri : soup) {
    std::array<std::int32_t, 3> t{};
    for (int k = 0; k < 3; ++k) {
      const auto key = std::make_tuple(tri[k].x(), tri[k].y(), tri[k].z());
      auto it = index.find(key);
      if (it == index.end()) {
        it = index.emplace(key, static_cast<std::int32_t>(m.vertices.size())).first;
        m.vertices.push_back(tri[k]);
      }
      t[k] = it->second;
    }
    m.triangles.push_back(t);
  }
  return m;
}

void TriangleMesh::transform(const Mat3& rotation, const Vec3& translation) {
  for (auto& v : vertices) v = rotation * v + translation;
}

void TriangleMesh::scale(double factor) {
  for (auto& v : vertices) v *= factor;
}

Box TriangleMesh::bounds() const {
  Box b;
  if (vertices.empty()) return b;
  b.lo = b.hi = vertices.front();
  for (const auto& v : vertices) {
    b.lo = b.lo.cwiseMin(v);
    b.hi = b.hi.cwiseMax(v);
  }
  return b;
}

}  // namespace chutelab::dem
