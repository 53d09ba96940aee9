#include "dem/walls/wall_contact_detector.h"

#include <algorithm>
#include <utility>

namespace chutelab::dem {
namespace {

bool is_edge(TriFeature f) { return f == TriFeature::edge_ab || f == TriFeature::edge_bc || f == TriFeature::edge_ca; }
bool is_vertex(TriFeature f) {
  return f == TriFeature::vertex_a || f == TriFeature::vertex_b || f == TriFeature::vertex_c;
}

// The triangles a sphere touches, each on its own (hit[q], geo[q]).
void touched_triangles(const Wall& w, const TriangleMesh& m, const std::int32_t* elements, std::size_t count,
                       const Vec3& x, double r, WallHit* geo, char* hit) {
  const double r2 = r * r;
  for (std::size_t q = 0; q < count; ++q) {
    const auto el = static_cast<std::size_t>(elements[q]);
    const auto& t = m.triangles[el];
    const Vec3& a = m.vertices[static_cast<std::size_t>(t[0])];
    // Many candidates are only within the skin. A sphere farther from the triangle's plane than its
    // radius cannot touch it, and the plane's distance is a dot product where the closest point is
    // a chain of branches. The test leaves a margin (relative 1e-9 of the radius plus the lever) far
    // above the rounding of either distance, and skips slivers (nn = inf), whose normal is inexact,
    // so it rejects only what the full test rejects.
    const Wall::FacePlane& fp = w.face_plane[el];
    const Vec3 ap = x - a;
    const double s = fp.n.dot(ap);
    const double reach = r + 1e-9 * (r + ap.cwiseAbs().sum());
    if (s * s > reach * reach * fp.nn) continue;
    const Vec3& b = m.vertices[static_cast<std::size_t>(t[1])];
    const Vec3& c = m.vertices[static_cast<std::size_t>(t[2])];
    const TriClosest cp = closest_point_on_triangle(x, a, b, c);
    const Vec3 d = cp.point - x;
    const double d2 = d.squaredNorm();
    if (d2 > r2 * (1.0 + 1e-9)) continue;  // certainly dist > r: skip the root
    const double dist = std::sqrt(d2);
    if (dist >= r || !(dist > 0.0)) continue;
    WallHit& g = geo[q];
    g.n = d / dist;
    g.delta = r - dist;
    g.point = cp.point;
    g.feature = cp.feature;
    hit[q] = 1;
  }
}

// Drops the edge and vertex contacts that a touched face or edge of the same mesh already covers:
// first edges (shadowed by a face that holds the edge, or by the same edge of an earlier
// triangle), then vertices (by a face or an edge that holds the vertex, or by the same vertex of an
// earlier triangle).
void one_contact_per_seam(const TriangleMesh& m, const std::int32_t* elements, std::size_t count, const WallHit* geo,
                          char* hit) {
  auto tri_has = [&](std::size_t q, std::int32_t vtx) {
    const auto& t = m.triangles[static_cast<std::size_t>(elements[q])];
    return t[0] == vtx || t[1] == vtx || t[2] == vtx;
  };
  // The vertices of the edge or vertex a contact lies on, lower first.
  auto feature_vertices = [&](std::size_t q, std::int32_t& a, std::int32_t& b) {
    const auto& t = m.triangles[static_cast<std::size_t>(elements[q])];
    switch (geo[q].feature) {
      case TriFeature::edge_ab: a = t[0]; b = t[1]; break;
      case TriFeature::edge_bc: a = t[1]; b = t[2]; break;
      case TriFeature::edge_ca: a = t[2]; b = t[0]; break;
      case TriFeature::vertex_a: a = b = t[0]; break;
      case TriFeature::vertex_b: a = b = t[1]; break;
      case TriFeature::vertex_c: a = b = t[2]; break;
      default: a = b = -1;
    }
    if (a > b) std::swap(a, b);
  };
  for (int pass = 1; pass <= 2; ++pass) {  // 1: edges, 2: vertices
    for (std::size_t q = 0; q < count; ++q) {
      if (!hit[q]) continue;
      const TriFeature f = geo[q].feature;
      if ((pass == 1 && !is_edge(f)) || (pass == 2 && !is_vertex(f))) continue;
      std::int32_t a, b;
      feature_vertices(q, a, b);
      bool shadowed = false;
      for (std::size_t o = 0; o < count && !shadowed; ++o) {
        if (o == q || !hit[o]) continue;
        const TriFeature fo = geo[o].feature;
        if (fo == TriFeature::face) {
          shadowed = tri_has(o, a) && tri_has(o, b);
        } else {
          const bool o_edge = is_edge(fo);
          std::int32_t oa, ob;
          feature_vertices(o, oa, ob);
          if (pass == 1 && o_edge) shadowed = (oa == a && ob == b && o < q);
          if (pass == 2 && o_edge) shadowed = (oa == a || ob == a);
          if (pass == 2 && !o_edge) shadowed = (oa == a && o < q);
        }
      }
      if (shadowed) hit[q] = 0;
    }
  }
}

}  // namespace

void mesh_contacts(const Wall& w, const TriangleMesh& m, const std::int32_t* elements, std::size_t count, const Vec3& x,
                   double r, WallHit* geo, char* hit) {
  touched_triangles(w, m, elements, count, x, r, geo, hit);
  one_contact_per_seam(m, elements, count, geo, hit);
}

}  // namespace chutelab::dem
