// Rigid multi-sphere particles: mass properties of the union of overlapping spheres against an
// independent numerical integral, and the torque-free rotation of a clump (angular momentum, energy,
// and the tumbling motion against Euler's equations).
#define BOOST_TEST_MODULE dem_clump
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <numbers>

#include "dem/clump.h"
#include "dem/clump_bodies.h"
#include "dem/rigid_rotation.h"

using namespace chutelab::dem;

namespace {

constexpr double pi = std::numbers::pi;

// Independent reference: integrate the indicator of the union in spherical shells around each point of
// a Cartesian lattice... kept simple on purpose: a midpoint rule on an n^3 lattice over the bounding
// box, written without the library's code, with moments about the box centre.
struct Ref {
  double volume;
  Vec3 centroid;
  Mat3 inertia;  // about the centroid, per unit density
};
Ref lattice_integral(const std::vector<ClumpSphere>& s, int n) {
  Vec3 lo = s[0].offset, hi = s[0].offset;
  for (const auto& e : s) {
    for (int d = 0; d < 3; ++d) {
      lo[d] = std::min(lo[d], e.offset[d] - e.radius);
      hi[d] = std::max(hi[d], e.offset[d] + e.radius);
    }
  }
  const Vec3 h = (hi - lo) / n;
  const double dv = h.x() * h.y() * h.z();
  double v = 0;
  Vec3 m1 = Vec3::Zero();
  Mat3 m2 = Mat3::Zero();
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (int k = 0; k < n; ++k) {
        const Vec3 p(lo.x() + (i + 0.5) * h.x(), lo.y() + (j + 0.5) * h.y(), lo.z() + (k + 0.5) * h.z());
        bool in = false;
        for (const auto& e : s) in = in || (p - e.offset).norm() <= e.radius;
        if (!in) continue;
        v += dv;
        m1 += dv * p;
        m2 += dv * p * p.transpose();
      }
  Ref r;
  r.volume = v;
  r.centroid = m1 / v;
  const Mat3 c = m2 - v * r.centroid * r.centroid.transpose();
  r.inertia = c.trace() * Mat3::Identity() - c;
  return r;
}

double sphere_volume(double r) { return 4.0 / 3.0 * pi * r * r * r; }

}  // namespace

// Closed form (sphere minus lenses, lenses as two caps) against a 240^3 lattice midpoint integral.
// Tolerance 0.3 % of the volume and of the largest principal moment: the lattice's error at the curved
// boundary, ~ (cell / size) for moments of a union this small, measured at 0.05-0.15 % here.
BOOST_AUTO_TEST_CASE(union_mass_properties_match_numerical_integral) {
  const std::vector<std::vector<ClumpSphere>> shapes = {
      {{Vec3(-0.225e-3, 0, 0), 2.2e-3}, {Vec3(0.225e-3, 0, 0), 2.2e-3}},            // reference pellet
      {{Vec3(0, 0, 0), 3e-3}, {Vec3(2e-3, 1e-3, -1e-3), 1.5e-3}},                    // unequal, oblique
      {{Vec3(0, 0, 0), 2e-3}, {Vec3(3e-3, 0, 0), 2e-3}, {Vec3(6e-3, 1e-3, 0), 2e-3}},  // chain, pairs only
      {{Vec3(0, 0, 0), 2e-3}, {Vec3(0.5e-3, 0, 0), 1e-3}},                            // one inside the other
      {{Vec3(0, 0, 0), 2e-3}, {Vec3(2e-3, 0, 0), 2e-3}, {Vec3(1e-3, 1.7e-3, 0), 2e-3}},  // triple overlap
  };
  for (std::size_t k = 0; k < shapes.size(); ++k) {
    const VolumeProperties vp = union_of_spheres(shapes[k]);
    const Ref ref = lattice_integral(shapes[k], 240);
    const double scale = ref.inertia.norm();
    BOOST_TEST_MESSAGE("shape " << k << (vp.exact ? " (closed form)" : " (quadrature)") << ": V " << vp.volume
                                << " (lattice " << ref.volume << "), |J - J_ref| / |J| "
                                << (vp.inertia - ref.inertia).norm() / scale);
    BOOST_TEST(std::abs(vp.volume / ref.volume - 1) < 3e-3);
    BOOST_TEST((vp.centroid - ref.centroid).norm() < 3e-3 * std::cbrt(ref.volume));
    BOOST_TEST((vp.inertia - ref.inertia).norm() / scale < 3e-3);
    BOOST_TEST(vp.exact == (k != 4));
  }
  // Non-overlapping spheres: exactly the sum (parallel axes); a contained sphere adds nothing.
  const VolumeProperties apart = union_of_spheres({{Vec3(-5e-3, 0, 0), 1e-3}, {Vec3(5e-3, 0, 0), 1e-3}});
  const double vs = sphere_volume(1e-3);
  BOOST_TEST(std::abs(apart.volume / (2 * vs) - 1) < 1e-12);
  BOOST_TEST(std::abs(apart.inertia(1, 1) / (2 * (0.4 * vs * 1e-6 + vs * 25e-6)) - 1) < 1e-12);
  const VolumeProperties inside = union_of_spheres(shapes[3]);
  BOOST_TEST(std::abs(inside.volume / sphere_volume(2e-3) - 1) < 1e-12);
}

// The clump template sits in its principal frame: centre of mass at the origin, inertia diagonal
// (ascending), the reference pellet's long axis along body x; scaling by f scales V by f^3 and I by f^5.
BOOST_AUTO_TEST_CASE(clump_shape_is_in_its_principal_frame) {
  const ClumpShape c = ClumpShape::from_spheres(
      {{Vec3(1e-3, 2e-3, 0), 2e-3}, {Vec3(3e-3, 2.5e-3, 1e-3), 1.5e-3}, {Vec3(0, 4e-3, -1e-3), 1.8e-3}});
  std::vector<ClumpSphere> s = c.spheres;
  const Ref ref = lattice_integral(s, 200);
  BOOST_TEST(ref.centroid.norm() < 5e-3 * std::cbrt(ref.volume));
  const double scale = c.principal_inertia.maxCoeff();
  BOOST_TEST(std::abs(ref.inertia(0, 1)) < 3e-3 * scale);
  BOOST_TEST(std::abs(ref.inertia(0, 2)) < 3e-3 * scale);
  BOOST_TEST(std::abs(ref.inertia(1, 2)) < 3e-3 * scale);
  for (int d = 0; d < 3; ++d) BOOST_TEST(std::abs(ref.inertia(d, d) - c.principal_inertia[d]) < 3e-3 * scale);
  BOOST_TEST(c.principal_inertia[0] <= c.principal_inertia[1]);
  BOOST_TEST(c.principal_inertia[1] <= c.principal_inertia[2]);

  const ClumpShape p = ClumpShape::reference_pellet();
  BOOST_TEST(std::abs(p.spheres[0].offset.x()) > 0.0);
  BOOST_TEST(p.spheres[0].offset.tail<2>().norm() < 1e-15);
  BOOST_TEST(std::abs(p.bounding_radius - (2.2e-3 + 0.225e-3)) < 1e-12);
  const ClumpShape big = p.scaled(5.6 / 4.4);
  BOOST_TEST(std::abs(big.volume / p.volume - std::pow(5.6 / 4.4, 3)) < 1e-12);
  BOOST_TEST(std::abs(big.principal_inertia[2] / p.principal_inertia[2] - std::pow(5.6 / 4.4, 5)) < 1e-12);
  BOOST_TEST_MESSAGE("reference pellet: V = " << p.volume * 1e9 << " mm^3, d_eq = " << p.equivalent_diameter() * 1e3
                                         << " mm, I/rho = " << p.principal_inertia.transpose() * 1e15 << " mm^5");
}

namespace {

// Torque-free rigid body by Euler's equations in the body frame, I dW/dt = (I W) x W, and
// dq/dt = q (0, W) / 2, with RK4 at a small step: the reference for the splitting integrator.
void euler_reference(Quat& q, Vec3& wb, const Vec3& I, double t, int steps) {
  const double h = t / steps;
  auto deriv = [&](const Quat& qq, const Vec3& ww, Quat& dq, Vec3& dw) {
    dw = (I.cwiseProduct(ww)).cross(ww).cwiseQuotient(I);
    const Quat p = qq * Quat(0, ww.x(), ww.y(), ww.z());
    dq = Quat(0.5 * p.w(), 0.5 * p.x(), 0.5 * p.y(), 0.5 * p.z());
  };
  auto add = [](const Quat& a, const Quat& b, double s) {
    return Quat(a.w() + s * b.w(), a.x() + s * b.x(), a.y() + s * b.y(), a.z() + s * b.z());
  };
  for (int k = 0; k < steps; ++k) {
    Quat k1q, k2q, k3q, k4q;
    Vec3 k1w, k2w, k3w, k4w;
    deriv(q, wb, k1q, k1w);
    deriv(add(q, k1q, h / 2), wb + h / 2 * k1w, k2q, k2w);
    deriv(add(q, k2q, h / 2), wb + h / 2 * k2w, k3q, k3w);
    deriv(add(q, k3q, h), wb + h * k3w, k4q, k4w);
    q = Quat(q.w() + h / 6 * (k1q.w() + 2 * k2q.w() + 2 * k3q.w() + k4q.w()),
             q.x() + h / 6 * (k1q.x() + 2 * k2q.x() + 2 * k3q.x() + k4q.x()),
             q.y() + h / 6 * (k1q.y() + 2 * k2q.y() + 2 * k3q.y() + k4q.y()),
             q.z() + h / 6 * (k1q.z() + 2 * k2q.z() + 2 * k3q.z() + k4q.z()));
    q.normalize();
    wb += h / 6 * (k1w + 2 * k2w + 2 * k3w + k4w);
  }
}

}  // namespace

// A free asymmetric clump tumbling (spin near the unstable middle axis, the "tennis racket"):
// world angular momentum conserved to round-off (1e-12 relative: the splitting rotates L exactly),
// rotational energy to 1e-4 over 20 000 steps (bounded O(h^2) error of a symplectic scheme), and the
// world angular velocity after 0.2 s within 1 % of |w| of the RK4 solution of Euler's equations.
BOOST_AUTO_TEST_CASE(free_clump_conserves_angular_momentum_and_tumbles_like_euler) {
  ClumpBodies b;
  const int shape = b.add_shape(ClumpShape::from_spheres(
      {{Vec3(-2e-3, 0, 0), 2e-3}, {Vec3(2e-3, 0, 0), 1.6e-3}, {Vec3(0, 2.5e-3, 0), 1.2e-3}}));
  const double rho = 1000;
  const Quat q0(Eigen::AngleAxisd(0.3, Vec3(1, 2, 3).normalized()));
  const Vec3 wb0(20.0, 200.0, 30.0);  // rad/s in the body frame, mostly about the middle axis
  const Vec3 w0 = q0 * wb0;
  b.add(shape, Vec3::Zero(), q0, Vec3(0.1, 0, 0), w0, rho, 0);
  const Vec3 L0 = b.L[0];
  const double e0 = b.rotational_energy();
  const double dt = 1e-5;
  const int n = 20000;
  double worst_e = 0, tumble = 0;
  for (int k = 0; k < n; ++k) {
    b.kick(0.5 * dt);
    b.drift(dt);
    b.kick(0.5 * dt);
    worst_e = std::max(worst_e, std::abs(b.rotational_energy() / e0 - 1));
    tumble = std::max(tumble, (b.q[0].conjugate() * b.w[0] - wb0).norm());
  }
  BOOST_TEST((b.L[0] - L0).norm() / L0.norm() < 1e-12);
  BOOST_TEST_MESSAGE("worst relative energy error " << worst_e);
  BOOST_TEST(worst_e < 1e-4);
  BOOST_TEST((b.x[0] - Vec3(0.1 * n * dt, 0, 0)).norm() < 1e-12);

  Quat q = q0;
  Vec3 wb = wb0;
  euler_reference(q, wb, rho * b.shapes[0].principal_inertia, n * dt, 200000);
  const Vec3 w_ref = q * wb;
  BOOST_TEST_MESSAGE("w after 0.2 s: " << b.w[0].transpose() << " (Euler RK4 " << w_ref.transpose() << ")");
  BOOST_TEST((b.w[0] - w_ref).norm() < 0.01 * w0.norm());
  // The body really tumbled (the middle axis is unstable): its body-frame spin moved far from the start.
  BOOST_TEST_MESSAGE("largest change of the body-frame spin " << tumble << " rad/s");
  BOOST_TEST(tumble > 0.5 * wb0.norm());
}
