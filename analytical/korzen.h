#pragma once
// Korzen (1988) impact-plate model as used by the reference study (Grima & Wypych 2010, Eqs 1-7).
//
// How we read the reference study's garbled equations (its PDF text lost the symbols; see DESIGN.md §1):
//  - Eqs 1-2 give the speed at impact, V_p^2 = V_d^2 + 2 g s for a drop s (energy, no air drag);
//    here V_p and its angle alpha_p come from the Booth trajectory at the plate instead, which is
//    the same thing without drag and stays right when an effect adds forces in flight.
//  - With beta the plate angle from the vertical: V_pn = V_p cos(alpha_p + beta) normal to the
//    plate, V_pt = V_p sin(alpha_p + beta) along it.
//  - Eq 3: stationary (build-up) flow forms iff alpha_p + beta > atan(mu_pw).
//  - Eq 4: V_a = V_p sqrt((A_p / A_a)(sin(alpha_p + beta) - mu_pw cos(alpha_p + beta))), iterated
//    with continuity A_a = A_p V_p / V_a from A_a = A_p. A negative radicand (the "negative root")
//    means Eq 4 has no solution: no stationary flow.
//  - Eq 5: R_n = m_s V_pn. Eq 6: R_s = m_s V_pt - rho_bl A_a V_a^2. Eq 7: R_s = mu_pw R_n, used
//    when Eq 4 has no solution.
// With continuity rho_bl A_a V_a = m_s, so Eq 6 reduces to m_s (V_pt - V_a) = mu_pw R_n as well:
// in this reading R_s / R_n = mu_pw at every condition, which is the reference study's stated finding 2.
#include <optional>
#include <string_view>

namespace chutelab::analytical {

struct KorzenInput {
  double mass_flow = 0.0;      // m_s, kg/s
  double bulk_density = 0.0;   // rho_bl, kg/m^3
  double impact_speed = 0.0;   // V_p, m/s
  double impact_angle = 0.0;   // alpha_p, rad below the horizontal
  double plate_angle = 0.0;    // beta, rad from the vertical
  double friction = 0.0;       // mu_pw
  double rebound = 0.0;        // fraction of normal momentum returned (0 = the reference study's model)
};

enum class ShearEquation { eq6, eq7 };
std::string_view name(ShearEquation e);

struct KorzenResult {
  double normal_speed = 0.0;      // V_pn
  double tangential_speed = 0.0;  // V_pt
  bool stationary_flow = false;   // Eq 3
  std::optional<double> exit_speed;  // V_a (Eq 4); absent when Eq 4 has no solution
  int iterations = 0;             // Eq 4 fixed-point iterations used
  double inflow_area = 0.0;       // A_p = m_s / (rho_bl V_p), m^2
  std::optional<double> outflow_area;  // A_a, m^2
  double normal_force = 0.0;      // R_n
  double shear_force = 0.0;       // R_s
  double resultant_force = 0.0;   // R
  ShearEquation shear_equation = ShearEquation::eq6;
};

KorzenResult korzen_impact(const KorzenInput& in);

}  // namespace chutelab::analytical
