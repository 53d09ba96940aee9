#include "analytical/flight.h"

#include <cmath>

namespace chutelab::analytical {

Eigen::Vector2d PlateLine::normal() const { return {std::cos(angle), std::sin(angle)}; }
Eigen::Vector2d PlateLine::down() const { return {std::sin(angle), -std::cos(angle)}; }
double PlateLine::signed_distance(const Eigen::Vector2d& p) const { return (p - top).dot(normal()); }
double PlateLine::along(const Eigen::Vector2d& p) const { return (p - top).dot(down()); }

Trajectory::Trajectory(FlightPoint start, double gravity, AccelerationFn extra, double dt)
    : start_(std::move(start)), g_(gravity), extra_(std::move(extra)), dt_(dt) {}

Eigen::Vector2d Trajectory::accel(const Eigen::Vector2d& v) const {
  Eigen::Vector2d a(0.0, -g_);
  if (extra_) a += extra_(v);
  return a;
}

FlightPoint Trajectory::step(const FlightPoint& s, double h) const {
  // Classical RK4 on (x, v); the acceleration depends on velocity only (gravity, drag).
  const Eigen::Vector2d k1v = accel(s.velocity);
  const Eigen::Vector2d k1x = s.velocity;
  const Eigen::Vector2d k2v = accel(s.velocity + 0.5 * h * k1v);
  const Eigen::Vector2d k2x = s.velocity + 0.5 * h * k1v;
  const Eigen::Vector2d k3v = accel(s.velocity + 0.5 * h * k2v);
  const Eigen::Vector2d k3x = s.velocity + 0.5 * h * k2v;
  const Eigen::Vector2d k4v = accel(s.velocity + h * k3v);
  const Eigen::Vector2d k4x = s.velocity + h * k3v;
  FlightPoint out;
  out.t = s.t + h;
  out.position = s.position + h / 6.0 * (k1x + 2.0 * k2x + 2.0 * k3x + k4x);
  out.velocity = s.velocity + h / 6.0 * (k1v + 2.0 * k2v + 2.0 * k3v + k4v);
  return out;
}

FlightPoint Trajectory::at_time(double t) const {
  if (!extra_) {
    FlightPoint p;
    p.t = start_.t + t;
    p.position = start_.position + start_.velocity * t + Eigen::Vector2d(0.0, -0.5 * g_ * t * t);
    p.velocity = start_.velocity + Eigen::Vector2d(0.0, -g_ * t);
    return p;
  }
  FlightPoint s = start_;
  double left = t;
  while (left > 0.0) {
    const double h = std::min(dt_, left);
    s = step(s, h);
    left -= h;
  }
  s.t = start_.t + t;
  return s;
}

std::optional<FlightPoint> Trajectory::first_root(
    const std::function<double(const FlightPoint&)>& event, double t_max) const {
  // March until the event turns non-negative, then refine the time inside the bracketing step by
  // bisection on the exact (closed-form or single RK4 part-step) state: a part-step of RK4 from the
  // bracket start is as accurate as a full step, so the root carries the integrator's accuracy.
  const double h = extra_ ? dt_ : std::min(dt_, 1e-2);
  FlightPoint a = start_;
  if (event(a) >= 0.0) return std::nullopt;
  auto advance = [&](const FlightPoint& from, double dt) {
    return extra_ ? step(from, dt) : at_time(from.t - start_.t + dt);
  };
  while (a.t - start_.t < t_max) {
    const FlightPoint b = advance(a, h);
    if (event(b) >= 0.0) {
      double lo = 0.0, hi = h;
      for (int i = 0; i < 80 && hi - lo > 1e-15; ++i) {
        const double mid = 0.5 * (lo + hi);
        (event(advance(a, mid)) < 0.0 ? lo : hi) = mid;
      }
      return advance(a, 0.5 * (lo + hi));
    }
    a = b;
  }
  return std::nullopt;
}

std::optional<FlightPoint> Trajectory::at_x(double x, double t_max) const {
  if (!extra_ && start_.velocity.x() > 0.0) {
    const double t = (x - start_.position.x()) / start_.velocity.x();
    if (t < 0.0) return std::nullopt;
    return at_time(t);
  }
  return first_root([x](const FlightPoint& p) { return p.position.x() - x; }, t_max);
}

std::optional<PlateHit> Trajectory::hit(const PlateLine& plate, double t_max) const {
  std::optional<FlightPoint> p;
  if (!extra_) {
    // Solve n.(p0 + v t - g t^2/2 ey - top) = 0 exactly: c2 t^2 + c1 t + c0 = 0.
    const Eigen::Vector2d n = plate.normal();
    const double c2 = -0.5 * g_ * n.y();
    const double c1 = start_.velocity.dot(n);
    const double c0 = plate.signed_distance(start_.position);
    double t = -1.0;
    if (c0 >= 0.0) return std::nullopt;  // released on or beyond the plate face
    if (std::abs(c2) < 1e-14 * std::abs(c1)) {
      if (c1 > 0.0) t = -c0 / c1;
    } else {
      const double disc = c1 * c1 - 4.0 * c2 * c0;
      if (disc >= 0.0) {
        const double sq = std::sqrt(disc);
        // Numerically stable pair of roots; take the smallest positive one.
        const double q = -0.5 * (c1 + std::copysign(sq, c1));
        const double r1 = q / c2, r2 = (q != 0.0) ? c0 / q : -1.0;
        for (double r : {r1, r2})
          if (r > 0.0 && (t < 0.0 || r < t)) t = r;
      }
    }
    if (t < 0.0 || t > t_max) return std::nullopt;
    p = at_time(t);
  } else {
    p = first_root([&plate](const FlightPoint& s) { return plate.signed_distance(s.position); },
                   t_max);
  }
  if (!p) return std::nullopt;
  PlateHit h;
  h.point = *p;
  h.speed = p->velocity.norm();
  h.alpha = std::atan2(-p->velocity.y(), p->velocity.x());
  h.along = plate.along(p->position);
  h.on_plate = h.along >= 0.0 && h.along <= plate.height;
  return h;
}

std::vector<FlightPoint> Trajectory::sample(double t_end, int n) const {
  std::vector<FlightPoint> out;
  out.reserve(static_cast<std::size_t>(n) + 1);
  if (!extra_) {
    for (int i = 0; i <= n; ++i) out.push_back(at_time(t_end * i / n));
    return out;
  }
  FlightPoint s = start_;
  out.push_back(s);
  for (int i = 1; i <= n; ++i) {
    const double target = t_end * i / n;
    while (s.t - start_.t < target - 1e-15) s = step(s, std::min(dt_, target - (s.t - start_.t)));
    out.push_back(s);
  }
  return out;
}

}  // namespace chutelab::analytical
