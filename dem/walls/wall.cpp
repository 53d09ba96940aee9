#include "dem/walls/wall.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "core/input_error.h"

namespace chutelab::dem {

Wall Wall::plane(std::string name, const Vec3& point, const Vec3& normal, int material) {
  if (!(normal.norm() > 0.0) || !normal.allFinite())
    throw InputError("", 0, fmt::format("wall '{}'", name), "plane normal must be a non-zero vector");
  Wall w;
  w.name = std::move(name);
  Plane p;
  p.point = point;
  p.normal = normal.normalized();
  // In-plane axes for an optional rectangular extent.
  const Vec3 trial = std::abs(p.normal.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY();
  p.axis_u = (trial - trial.dot(p.normal) * p.normal).normalized();
  p.axis_v = p.normal.cross(p.axis_u);
  w.shape = p;
  w.material = material;
  w.load_point = point;
  w.motion.pivot = point;
  w.set_time(0.0);
  return w;
}

Wall Wall::cylinder(std::string name, const Vec3& point, const Vec3& axis, double radius, int material,
                    bool inside) {
  if (!(radius > 0.0))
    throw InputError("", 0, fmt::format("wall '{}'", name), fmt::format("cylinder radius must be > 0 m, got {}", radius));
  if (!(axis.norm() > 0.0))
    throw InputError("", 0, fmt::format("wall '{}'", name), "cylinder axis must be a non-zero vector");
  Wall w;
  w.name = std::move(name);
  Cylinder c;
  c.point = point;
  c.axis = axis.normalized();
  c.radius = radius;
  c.inside = inside;
  w.shape = c;
  w.material = material;
  w.load_point = point;
  w.motion.pivot = point;
  w.surface.centre = point;
  w.set_time(0.0);
  return w;
}

Wall Wall::mesh(std::string name, TriangleMesh mesh, int material) {
  if (mesh.triangles.empty())
    throw InputError(mesh.source, 0, fmt::format("wall '{}'", name), "mesh has no triangles");
  Wall w;
  w.name = std::move(name);
  const Box b = mesh.bounds();
  w.load_point = 0.5 * (b.lo + b.hi);
  w.motion.pivot = w.load_point;
  w.surface.centre = w.load_point;
  w.shape = std::move(mesh);
  w.material = material;
  w.set_time(0.0);
  return w;
}

std::size_t Wall::element_count() const {
  if (const auto* m = std::get_if<TriangleMesh>(&shape)) return m->triangles.size();
  return 1;
}

void Wall::set_time(double t) {
  const double angle = motion.omega.norm() * t;
  rotation = angle > 0.0 ? Mat3(Eigen::AngleAxisd(angle, motion.omega.normalized())) : Mat3::Identity();
  pivot_now = motion.pivot + motion.velocity * t;
  if (const auto* p = std::get_if<Plane>(&shape)) {
    Plane q = *p;
    q.point = to_world(p->point);
    q.normal = rotation * p->normal;
    q.axis_u = rotation * p->axis_u;
    q.axis_v = rotation * p->axis_v;
    current = q;
  } else if (const auto* c = std::get_if<Cylinder>(&shape)) {
    Cylinder q = *c;
    q.point = to_world(c->point);
    q.axis = rotation * c->axis;
    current = q;
  } else {
    const auto& m = std::get<TriangleMesh>(shape);
    if (!std::holds_alternative<TriangleMesh>(current)) current = m;
    auto& cm = std::get<TriangleMesh>(current);
    cm.triangles = m.triangles;
    cm.vertices.resize(m.vertices.size());
    for (std::size_t k = 0; k < m.vertices.size(); ++k) cm.vertices[k] = to_world(m.vertices[k]);
    face_plane.resize(cm.triangles.size());
    for (std::size_t k = 0; k < cm.triangles.size(); ++k) {
      const auto& t = cm.triangles[k];
      const Vec3& a = cm.vertices[static_cast<std::size_t>(t[0])];
      const Vec3 ab = cm.vertices[static_cast<std::size_t>(t[1])] - a, ac = cm.vertices[static_cast<std::size_t>(t[2])] - a;
      const Vec3 nrm = ab.cross(ac);
      const double nn = nrm.squaredNorm();
      face_plane[k] = {nrm, nn > 1e-8 * ab.squaredNorm() * ac.squaredNorm() ? nn : std::numeric_limits<double>::infinity()};
    }
  }
  element_force.resize(element_count(), Vec3::Zero());
}


double reach_from_pivot(const Wall& w) {
  if (const auto* m = std::get_if<TriangleMesh>(&w.shape)) {
    double r = 0.0;
    for (const auto& v : m->vertices) r = std::max(r, (v - w.motion.pivot).norm());
    return r;
  }
  if (const auto* p = std::get_if<Plane>(&w.shape)) {
    if (!p->bounded()) return std::numeric_limits<double>::infinity();
    return (p->point - w.motion.pivot).norm() + std::hypot(p->half_u, p->half_v);
  }
  const auto& c = std::get<Cylinder>(w.shape);
  const Vec3 off = c.point - w.motion.pivot;
  const bool about_own_axis = w.motion.omega.normalized().cross(c.axis).norm() < 1e-12 &&
                              (off - off.dot(c.axis) * c.axis).norm() < 1e-12;
  if (about_own_axis) return 0.0;  // the shape maps onto itself
  if (!std::isfinite(c.axial_min) || !std::isfinite(c.axial_max)) return std::numeric_limits<double>::infinity();
  return off.norm() + std::max(std::abs(c.axial_min), std::abs(c.axial_max)) + c.radius;
}

}  // namespace chutelab::dem
