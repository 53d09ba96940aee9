#include "analytical/booth.h"

#include <cmath>
#include <fmt/format.h>

#include "core/input_error.h"

namespace chutelab::analytical {

Release booth_release(const DischargeInput& in) {
  // The belt wraps the pulley from theta0 = -incline (a belt climbing towards the pulley meets it
  // behind the top). On the pulley the radial balance is g cos(theta) + a_hold = V^2 / r: the
  // material stays while the pull towards the axis can still bend its path.
  Release out;
  const double r = in.radius;
  const double centripetal = in.speed * in.speed / r;
  out.ratio = centripetal / in.gravity;
  const double theta0 = 0.0 - in.incline;  // 0 - x, not -x: a level belt reports +0, not -0
  const double k = (centripetal - in.holding_accel) / in.gravity;
  if (k >= std::cos(theta0)) {
    out.high_speed = true;
    out.theta = theta0;
  } else {
    if (k <= -1.0)
      throw InputError("", 0, "belt_speed_mps",
                       fmt::format("at {:.3f} m/s the material never leaves the pulley (holding "
                                   "acceleration {:.1f} m/s^2 exceeds V^2/r + g)",
                                   in.speed, in.holding_accel));
    out.high_speed = false;
    out.theta = std::acos(k);  // Booth low-speed release angle, acos(K) without holding force
  }
  out.position = r * Eigen::Vector2d(std::sin(out.theta), std::cos(out.theta));
  out.velocity = in.speed * Eigen::Vector2d(std::cos(out.theta), -std::sin(out.theta));
  return out;
}

}  // namespace chutelab::analytical
