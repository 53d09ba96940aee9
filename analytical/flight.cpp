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

const FlightPoint& Trajectory::stored(std::size_t i) const {
  if (path_.empty()) path_.push_back(start_);
  while (path_.size() <= i) {
    FlightPoint next = step(path_.back(), dt_);
    next.t = start_.t + dt_ * static_cast<double>(path_.size());  // no drift from summing dt
    path_.push_back(next);
  }
  return path_[i];
}

Eigen::Vector2d Trajectory::interpolate_position(std::size_t i, double tau) const {
  const FlightPoint& a = stored(i);
  const FlightPoint& b = stored(i + 1);
  const double t2 = tau * tau, t3 = t2 * tau;
  return (2 * t3 - 3 * t2 + 1) * a.position + (t3 - 2 * t2 + tau) * dt_ * a.velocity +
         (-2 * t3 + 3 * t2) * b.position + (t3 - t2) * dt_ * b.velocity;
}

FlightPoint Trajectory::interpolate(std::size_t i, double tau) const {
  const FlightPoint& a = stored(i);
  const FlightPoint& b = stored(i + 1);
  const double h = dt_;
  const double t2 = tau * tau, t3 = t2 * tau;
  // Cubic Hermite on positions (slopes = velocities) and on velocities (slopes = accelerations).
  const double h00 = 2 * t3 - 3 * t2 + 1, h10 = t3 - 2 * t2 + tau, h01 = -2 * t3 + 3 * t2,
               h11 = t3 - t2;
  FlightPoint p;
  p.t = a.t + tau * h;
  p.position = h00 * a.position + h10 * h * a.velocity + h01 * b.position + h11 * h * b.velocity;
  p.velocity = h00 * a.velocity + h10 * h * accel(a.velocity) + h01 * b.velocity +
               h11 * h * accel(b.velocity);
  return p;
}

FlightPoint Trajectory::at_time(double t) const {
  if (!extra_) {
    FlightPoint p;
    p.t = start_.t + t;
    p.position = start_.position + start_.velocity * t + Eigen::Vector2d(0.0, -0.5 * g_ * t * t);
    p.velocity = start_.velocity + Eigen::Vector2d(0.0, -g_ * t);
    return p;
  }
  const double steps = std::max(0.0, t / dt_);
  const auto i = static_cast<std::size_t>(steps);
  return interpolate(i, steps - static_cast<double>(i));
}

std::optional<FlightPoint> Trajectory::first_root(
    const std::function<double(const FlightPoint&)>& event, double t_max) const {
  // March until the event turns non-negative, then bisect the time inside the bracketing interval
  // on the exact state (closed form) or the step's Hermite interpolant (integrated).
  if (event(start_) >= 0.0) return std::nullopt;
  if (extra_) {
    for (std::size_t i = 0; dt_ * static_cast<double>(i) < t_max; ++i) {
      if (event(stored(i + 1)) < 0.0) continue;
      // Events depend on position only: bisect on the cheap position interpolant.
      double lo = 0.0, hi = 1.0;
      FlightPoint probe;
      for (int k = 0; k < 52; ++k) {
        const double mid = 0.5 * (lo + hi);
        probe.position = interpolate_position(i, mid);
        (event(probe) < 0.0 ? lo : hi) = mid;
      }
      return interpolate(i, 0.5 * (lo + hi));
    }
    return std::nullopt;
  }
  const double h = 1e-2;
  for (double t = 0.0; t < t_max; t += h) {
    if (event(at_time(t + h)) < 0.0) continue;
    double lo = t, hi = t + h;
    for (int k = 0; k < 80 && hi - lo > 1e-15; ++k) {
      const double mid = 0.5 * (lo + hi);
      (event(at_time(mid)) < 0.0 ? lo : hi) = mid;
    }
    return at_time(0.5 * (lo + hi));
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
    // signed_distance() with the plate's normal taken once: computed at each of the search's
    // events, its sine and cosine were a tenth of a diagnosis's time (same arithmetic, same bits).
    const Eigen::Vector2d n = plate.normal(), top = plate.top;
    p = first_root([&n, &top](const FlightPoint& s) { return (s.position - top).dot(n); }, t_max);
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
  for (int i = 0; i <= n; ++i) out.push_back(at_time(t_end * i / n));
  return out;
}

}  // namespace chutelab::analytical
