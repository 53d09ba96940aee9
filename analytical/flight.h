#pragma once
// Flight of a streamline from its release point to the plate. Without added forces the path is the
// closed-form parabola; with them (air drag, ...) it is integrated with classical RK4, whose steps
// are exact for constant acceleration, so both paths agree to rounding when no force is added.
#include <Eigen/Core>
#include <functional>
#include <optional>
#include <vector>

namespace chutelab::analytical {

// The plate face as a line: hinged at its top edge (x = Z, y = plate_top), tilted by beta from the
// vertical with the top leaning towards the pulley for beta > 0. Its inward normal (the direction
// in which the stream pushes it) is (cos beta, sin beta), so a stream arriving at alpha_p below the
// horizontal meets it at alpha_p + beta from the normal, as in reference study Eqs 1-7.
struct PlateLine {
  Eigen::Vector2d top = Eigen::Vector2d::Zero();
  double angle = 0.0;
  double height = 0.0;
  Eigen::Vector2d normal() const;
  Eigen::Vector2d down() const;  // unit vector along the face, from the top edge downward
  double signed_distance(const Eigen::Vector2d& p) const;  // < 0 on the pulley side
  double along(const Eigen::Vector2d& p) const;             // distance below the top edge
};

struct FlightPoint {
  double t = 0.0;
  Eigen::Vector2d position = Eigen::Vector2d::Zero();
  Eigen::Vector2d velocity = Eigen::Vector2d::Zero();
};

struct PlateHit {
  FlightPoint point;
  double speed = 0.0;        // V_p
  double alpha = 0.0;        // alpha_p: angle of the velocity below the horizontal, rad
  double along = 0.0;        // m below the plate's top edge
  bool on_plate = false;     // within the plate's height
};

using AccelerationFn = std::function<Eigen::Vector2d(const Eigen::Vector2d& velocity)>;

class Trajectory {
 public:
  // extra == nullptr: closed form. Otherwise RK4 with step dt (s), marched once and stored; states
  // between steps come from the cubic Hermite interpolant of the stored positions and velocities
  // (error O(dt^4), and exact for constant acceleration like the steps themselves).
  Trajectory(FlightPoint start, double gravity, AccelerationFn extra = nullptr, double dt = 2e-3);

  FlightPoint at_time(double t) const;
  // First crossing of the vertical x = const after the start; nullopt if never within t_max.
  std::optional<FlightPoint> at_x(double x, double t_max = 10.0) const;
  // First crossing of the plate line after the start (the plate may be missed: see on_plate).
  std::optional<PlateHit> hit(const PlateLine& plate, double t_max = 10.0) const;
  // Points from the start to time t_end, for drawing.
  std::vector<FlightPoint> sample(double t_end, int n) const;
  bool closed_form() const { return !extra_; }

 private:
  FlightPoint step(const FlightPoint& s, double h) const;
  Eigen::Vector2d accel(const Eigen::Vector2d& v) const;
  // Integrated path: stored state i (at t = i dt), marching further on demand.
  const FlightPoint& stored(std::size_t i) const;
  FlightPoint interpolate(std::size_t i, double tau) const;  // tau in [0, 1] within step i
  Eigen::Vector2d interpolate_position(std::size_t i, double tau) const;
  // First time at which event(state) changes sign from negative. Events look at the position only.
  std::optional<FlightPoint> first_root(const std::function<double(const FlightPoint&)>& event,
                                        double t_max) const;

  FlightPoint start_;
  double g_;
  AccelerationFn extra_;
  double dt_;
  mutable std::vector<FlightPoint> path_;  // integrated states, grown on demand
};

}  // namespace chutelab::analytical
