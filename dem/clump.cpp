#include "dem/clump.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <Eigen/Eigenvalues>
#include <fmt/format.h>

#include "core/input_error.h"

namespace chutelab::dem {
namespace {

constexpr double pi = std::numbers::pi;

// Raw moments of a solid about the origin: V, integral r dV, integral r r^T dV.
struct Moments {
  double v = 0.0;
  Vec3 m1 = Vec3::Zero();
  Mat3 s = Mat3::Zero();
  Moments& operator+=(const Moments& o) {
    v += o.v;
    m1 += o.m1;
    s += o.s;
    return *this;
  }
  Moments& operator-=(const Moments& o) {
    v -= o.v;
    m1 -= o.m1;
    s -= o.s;
    return *this;
  }
};

// Moments of the spherical cap {|r - c| <= R, (r - c) . a >= d}, -R <= d <= R, a unit. Integrating
// discs of radius^2 = R^2 - z^2 over z in [d, R] (z along a from the centre):
//   V      = pi (2R^3/3 - R^2 d + d^3/3)
//   int z  = pi (R^2 - d^2)^2 / 4
//   int z^2 = pi (2R^5/15 - R^2 d^3/3 + d^5/5)
//   int rho^2 = pi/2 (8R^5/15 - R^4 d + 2R^2 d^3/3 - d^5/5)   (rho: distance from the axis)
// and by symmetry about the axis, int (r-c)(r-c)^T = int z^2 a a^T + (int rho^2 / 2)(I - a a^T).
Moments cap(const Vec3& c, double R, const Vec3& a, double d) {
  d = std::clamp(d, -R, R);
  const double R2 = R * R, d2 = d * d, d3 = d2 * d, d5 = d3 * d2, R5 = R2 * R2 * R;
  const double v = pi * (2.0 * R2 * R / 3.0 - R2 * d + d3 / 3.0);
  const double mz = pi * (R2 - d2) * (R2 - d2) / 4.0;
  const double szz = pi * (2.0 * R5 / 15.0 - R2 * d3 / 3.0 + d5 / 5.0);
  const double srr = 0.5 * pi * (8.0 * R5 / 15.0 - R2 * R2 * d + 2.0 * R2 * d3 / 3.0 - d5 / 5.0);
  const Mat3 aa = a * a.transpose();
  const Mat3 s_local = szz * aa + 0.5 * srr * (Mat3::Identity() - aa);
  const Vec3 m1_local = mz * a;
  Moments m;
  m.v = v;
  m.m1 = v * c + m1_local;
  m.s = s_local + c * m1_local.transpose() + m1_local * c.transpose() + v * c * c.transpose();
  return m;
}

Moments sphere(const Vec3& c, double R) { return cap(c, R, Vec3::UnitZ(), -R); }

// The lens (intersection) of two spheres; empty when they do not overlap.
Moments lens(const ClumpSphere& p, const ClumpSphere& q) {
  const Vec3 dc = q.offset - p.offset;
  const double D = dc.norm();
  if (D >= p.radius + q.radius) return {};
  if (D <= std::abs(p.radius - q.radius)) return p.radius < q.radius ? sphere(p.offset, p.radius) : sphere(q.offset, q.radius);
  const Vec3 a = dc / D;
  // Radical plane: points equidistant in power from both centres.
  const double dp = (D * D + p.radius * p.radius - q.radius * q.radius) / (2.0 * D);
  Moments m = cap(p.offset, p.radius, a, dp);
  m += cap(q.offset, q.radius, -a, D - dp);
  return m;
}

bool overlap(const ClumpSphere& p, const ClumpSphere& q) {
  return (q.offset - p.offset).norm() < p.radius + q.radius;
}

VolumeProperties from_moments(const Moments& m, bool exact) {
  VolumeProperties out;
  out.volume = m.v;
  out.centroid = m.m1 / m.v;
  const Mat3 s_c = m.s - m.v * out.centroid * out.centroid.transpose();  // about the centroid
  out.inertia = s_c.trace() * Mat3::Identity() - s_c;
  out.exact = exact;
  return out;
}

void check_spheres(const std::vector<ClumpSphere>& spheres) {
  if (spheres.empty()) throw InputError("", 0, "clump", "a clump needs at least one sphere");
  for (const auto& s : spheres)
    if (!(s.radius > 0.0) || !std::isfinite(s.radius) || !s.offset.allFinite())
      throw InputError("", 0, "clump", fmt::format("sphere radius must be > 0 m and offsets finite, got r = {}", s.radius));
}

}  // namespace

VolumeProperties union_of_spheres_quadrature(const std::vector<ClumpSphere>& spheres, int cells) {
  check_spheres(spheres);
  Vec3 lo = Vec3::Constant(1e300), hi = Vec3::Constant(-1e300);
  for (const auto& s : spheres) {
    lo = lo.cwiseMin(s.offset - Vec3::Constant(s.radius));
    hi = hi.cwiseMax(s.offset + Vec3::Constant(s.radius));
  }
  const double h = (hi - lo).maxCoeff() / std::max(cells, 4);
  const Eigen::Vector3i n = ((hi - lo) / h).array().ceil().cast<int>();
  const double dv = h * h * h;
  Moments m;
  for (int k = 0; k < n.z(); ++k)
    for (int j = 0; j < n.y(); ++j)
      for (int i = 0; i < n.x(); ++i) {
        const Vec3 p = lo + h * Vec3(i + 0.5, j + 0.5, k + 0.5);
        bool in = false;
        for (const auto& s : spheres)
          if ((p - s.offset).squaredNorm() <= s.radius * s.radius) {
            in = true;
            break;
          }
        if (!in) continue;
        m.v += dv;
        m.m1 += dv * p;
        m.s += dv * p * p.transpose();
      }
  return from_moments(m, false);
}

VolumeProperties union_of_spheres(const std::vector<ClumpSphere>& spheres, int cells) {
  check_spheres(spheres);
  const std::size_t n = spheres.size();
  // Inclusion-exclusion stops at pairs: exact unless some point lies in three spheres. Three mutually
  // overlapping spheres (a necessary condition) send the shape to the quadrature.
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 1; j < n; ++j) {
      if (!overlap(spheres[i], spheres[j])) continue;
      for (std::size_t k = j + 1; k < n; ++k)
        if (overlap(spheres[i], spheres[k]) && overlap(spheres[j], spheres[k]))
          return union_of_spheres_quadrature(spheres, cells);
    }
  Moments m;
  for (const auto& s : spheres) m += sphere(s.offset, s.radius);
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 1; j < n; ++j) m -= lens(spheres[i], spheres[j]);
  return from_moments(m, true);
}

ClumpShape ClumpShape::from_spheres(std::vector<ClumpSphere> spheres, std::string name) {
  const VolumeProperties vp = union_of_spheres(spheres);
  Eigen::SelfAdjointEigenSolver<Mat3> eig(vp.inertia);
  Mat3 axes = eig.eigenvectors();  // columns: principal axes, eigenvalues ascending
  if (axes.determinant() < 0.0) axes.col(2) = -axes.col(2);
  ClumpShape c;
  c.name = std::move(name);
  c.volume = vp.volume;
  c.principal_inertia = eig.eigenvalues();
  for (auto& s : spheres) {
    s.offset = axes.transpose() * (s.offset - vp.centroid);
    // Round-off of the eigen-decomposition leaves ~1e-19 m components; clean them for readable output.
    for (int d = 0; d < 3; ++d)
      if (std::abs(s.offset[d]) < 1e-12 * s.radius) s.offset[d] = 0.0;
    c.bounding_radius = std::max(c.bounding_radius, s.offset.norm() + s.radius);
  }
  c.spheres = std::move(spheres);
  return c;
}

ClumpShape ClumpShape::two_sphere(double sphere_diameter, double spacing, std::string name) {
  if (!(sphere_diameter > 0.0) || !(spacing >= 0.0))
    throw InputError("", 0, "clump", fmt::format("need sphere diameter > 0 and spacing >= 0, got {} and {}", sphere_diameter, spacing));
  const double r = 0.5 * sphere_diameter;
  return from_spheres({{Vec3(-0.5 * spacing, 0, 0), r}, {Vec3(0.5 * spacing, 0, 0), r}}, std::move(name));
}

ClumpShape ClumpShape::reference_pellet() { return two_sphere(4.4e-3, 3.0 * 4.55e-3 - 3.0 * 4.4e-3, "reference-pellet"); }

ClumpShape ClumpShape::scaled(double f) const {
  ClumpShape c = *this;
  for (auto& s : c.spheres) {
    s.offset *= f;
    s.radius *= f;
  }
  c.volume *= f * f * f;
  c.principal_inertia *= f * f * f * f * f;
  c.bounding_radius *= f;
  return c;
}

double ClumpShape::largest_sphere_radius() const {
  double r = 0.0;
  for (const auto& s : spheres) r = std::max(r, s.radius);
  return r;
}

double ClumpShape::equivalent_diameter() const { return std::cbrt(6.0 * volume / pi); }

}  // namespace chutelab::dem
