#include "analytical/korzen.h"

#include <cmath>
#include <fmt/format.h>

#include "core/input_error.h"

namespace chutelab::analytical {

std::string_view name(ShearEquation e) { return e == ShearEquation::eq6 ? "Eq 6" : "Eq 7"; }

KorzenResult korzen_impact(const KorzenInput& in) {
  KorzenResult r;
  const double incidence = in.impact_angle + in.plate_angle;  // alpha_p + beta
  r.normal_speed = in.impact_speed * std::cos(incidence);
  r.tangential_speed = in.impact_speed * std::sin(incidence);
  r.stationary_flow = incidence > std::atan(in.friction);  // Eq 3
  r.inflow_area = in.mass_flow / (in.bulk_density * in.impact_speed);

  const double drive = std::sin(incidence) - in.friction * std::cos(incidence);
  if (drive > 0.0) {
    // Eq 4 with continuity: each pass V_a <- V_p sqrt((A_p/A_a) drive), A_a <- A_p V_p / V_a.
    // The map halves the log-distance to its fixed point V_p * drive every pass.
    double area = r.inflow_area;
    double va = 0.0;
    for (r.iterations = 1; r.iterations <= 200; ++r.iterations) {
      const double next = in.impact_speed * std::sqrt(r.inflow_area / area * drive);
      const bool converged = std::abs(next - va) <= 1e-13 * next;
      va = next;
      area = r.inflow_area * in.impact_speed / va;
      if (converged) break;
    }
    // Finite inputs converge in a few dozen passes; only an impact speed or flow out of range (an
    // extreme measured value driving a fit, a unit slip) gets here. It is the input's fault.
    if (r.iterations > 200)
      throw InputError("", 0, "",
                       fmt::format("Korzen Eq 4 has no finite solution for an impact speed of {:g} m/s and a mass "
                                   "flow of {:g} kg/s",
                                   in.impact_speed, in.mass_flow));
    r.exit_speed = va;
    r.outflow_area = area;
  }

  // Eq 5. Rebounding particles return part of the normal momentum (0 in the reference study's model); they
  // leave the plate rather than slide on it, so the shear below sees only the arriving flux.
  const double arriving_normal_force = in.mass_flow * r.normal_speed;
  r.normal_force = arriving_normal_force * (1.0 + in.rebound);
  if (r.exit_speed) {
    r.shear_force = in.mass_flow * r.tangential_speed -
                    in.bulk_density * *r.outflow_area * *r.exit_speed * *r.exit_speed;  // Eq 6
    r.shear_equation = ShearEquation::eq6;
  } else {
    r.shear_force = in.friction * arriving_normal_force;  // Eq 7
    r.shear_equation = ShearEquation::eq7;
  }
  r.resultant_force = std::hypot(r.normal_force, r.shear_force);
  return r;
}

}  // namespace chutelab::analytical
