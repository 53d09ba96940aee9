#include "core/quantity.h"

#include <stdexcept>

namespace chutelab {
namespace {
constexpr std::array<QuantityInfo, kQuantityCount> kInfo = {{
    {Quantity::normal_force, "normal_force_N", "R_n", "plate normal force", "N", 1.0, false},
    {Quantity::shear_force, "shear_force_N", "R_s", "plate shear force", "N", 1.0, false},
    {Quantity::resultant_force, "resultant_force_N", "R", "plate resultant force", "N", 1.0, true},
    {Quantity::impact_velocity, "impact_velocity_mps", "V_p", "impact velocity", "m/s", 1.0, true},
    {Quantity::exit_velocity, "exit_velocity_mps", "V_a", "exit velocity", "m/s", 1.0, true},
    {Quantity::impact_point_y, "impact_point_y_mm", "y_R", "impact point height", "mm", 1e3, false},
    {Quantity::belt_layer_velocity, "belt_layer_velocity_mps", "V_l", "layer speed before the pulley", "m/s", 1.0,
     true, true},
    {Quantity::stream_mass_flow, "stream_mass_flow_tph", "m_st", "free-stream mass flow", "t/h", 3.6, true, true},
}};
}  // namespace

const QuantityInfo& info(Quantity q) { return kInfo.at(static_cast<std::size_t>(q)); }

std::optional<Quantity> parse_quantity(std::string_view name) {
  for (const auto& i : kInfo)
    if (i.name == name) return i.quantity;
  return std::nullopt;
}

std::string_view name(Boundary b) {
  switch (b) {
    case Boundary::upper: return "upper";
    case Boundary::lower: return "lower";
    case Boundary::centre: return "centre";
  }
  throw std::logic_error("unknown boundary");
}

std::optional<Boundary> parse_boundary(std::string_view n) {
  for (Boundary b : kAllBoundaries)
    if (name(b) == n) return b;
  return std::nullopt;
}

std::string trajectory_quantity(Boundary b) {
  return "trajectory_" + std::string(name(b)) + "_y_mm";
}

}  // namespace chutelab
