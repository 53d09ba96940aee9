#include "core/rig.h"

#include <algorithm>

#include "core/units.h"

namespace chutelab {
namespace {
using units::deg;
using units::mm;

std::vector<RigField> make_fields() {
  // Ranges are the physically possible ones, not the typical ones: a 0.5 m pulley or a 3 m/s^2
  // gravity (a centrifuge model) is odd but legal; a negative density is not.
  return {
      {"belt", "pulley_diameter_mm", "pulley_diameter_mm", mm, 1.0, 1e4, true, {},
       [](Setup& s) -> double& { return s.belt.pulley_diameter; }},
      {"belt", "belt_thickness_mm", "belt_thickness_mm", mm, 0.0, 200.0, true, {},
       [](Setup& s) -> double& { return s.belt.belt_thickness; }},
      {"belt", "belt_width_mm", "belt_width_mm", mm, 1.0, 1e4, true, {},
       [](Setup& s) -> double& { return s.belt.belt_width; }},
      {"belt", "loaded_width_mm", "loaded_width_mm", mm, 1.0, 1e4, true, {},
       [](Setup& s) -> double& { return s.belt.loaded_width; }},
      {"belt", "incline_deg", "belt_incline_deg", deg, -45.0, 45.0, true, {},
       [](Setup& s) -> double& { return s.belt.incline; }},
      {"belt", "trough_angle_deg", "trough_angle_deg", deg, 0.0, 60.0, false, 0.0,
       [](Setup& s) -> double& { return s.belt.trough.idler_angle; }},
      {"belt", "centre_roll_mm", "centre_roll_mm", mm, 0.0, 1e4, false, 0.0,
       [](Setup& s) -> double& { return s.belt.trough.centre_roll; }},
      {"belt", "surcharge_angle_deg", "surcharge_angle_deg", deg, 0.0, 45.0, false, 20.0,
       [](Setup& s) -> double& { return s.belt.trough.surcharge_angle; }},
      {"plate", "width_mm", "plate_width_mm", mm, 1.0, 1e4, true, {},
       [](Setup& s) -> double& { return s.plate.width; }},
      {"plate", "height_mm", "plate_height_mm", mm, 1.0, 1e4, true, {},
       [](Setup& s) -> double& { return s.plate.height; }},
      {"plate", "angle_deg", "plate_angle_deg", deg, -60.0, 60.0, true, {},
       [](Setup& s) -> double& { return s.plate.angle; }},
      {"material", "particle_diameter_mm", "particle_diameter_mm", mm, 1e-3, 1e3, true, {},
       [](Setup& s) -> double& { return s.material.particle_diameter; }},
      {"material", "solid_density_kgm3", "solid_density_kgm3", 1.0, 1.0, 3e4, true, {},
       [](Setup& s) -> double& { return s.material.solid_density; }},
      {"material", "bulk_density_kgm3", "bulk_density_kgm3", 1.0, 1.0, 3e4, true, {},
       [](Setup& s) -> double& { return s.material.bulk_density; }},
      {"material", "youngs_modulus_Pa", "youngs_modulus_Pa", 1.0, 1e3, 1e13, true, {},
       [](Setup& s) -> double& { return s.material.youngs_modulus; }},
      {"material", "poisson_ratio", "poisson_ratio", 1.0, -0.99, 0.5, true, {},
       [](Setup& s) -> double& { return s.material.poisson_ratio; }},
      {"material", "friction_particle", "friction_particle", 1.0, 0.0, 10.0, true, {},
       [](Setup& s) -> double& { return s.material.friction_particle; }},
      {"material", "friction_plate", "friction_plate", 1.0, 0.0, 10.0, true, {},
       [](Setup& s) -> double& { return s.material.friction_plate; }},
      {"material", "friction_belt", "friction_belt", 1.0, 0.0, 10.0, true, {},
       [](Setup& s) -> double& { return s.material.friction_belt; }},
      {"material", "friction_side", "friction_side", 1.0, 0.0, 10.0, false, {},
       [](Setup& s) -> double& { return s.material.friction_side; }},
      {"material", "rolling_friction_particle", "rolling_friction_particle", 1.0, 0.0, 10.0, true,
       {}, [](Setup& s) -> double& { return s.material.rolling_friction_particle; }},
      {"material", "rolling_friction_wall", "rolling_friction_wall", 1.0, 0.0, 10.0, false, {},
       [](Setup& s) -> double& { return s.material.rolling_friction_wall; }},
      {"material", "restitution_particle", "restitution_particle", 1.0, 0.0, 1.0, true, {},
       [](Setup& s) -> double& { return s.material.restitution_particle; }},
      {"material", "restitution_plate", "restitution_plate", 1.0, 0.0, 1.0, true, {},
       [](Setup& s) -> double& { return s.material.restitution_plate; }},
      {"material", "restitution_belt", "restitution_belt", 1.0, 0.0, 1.0, false, 0.4,
       [](Setup& s) -> double& { return s.material.restitution_belt; }},
      {"", "gravity_mps2", "", 1.0, 0.01, 1e4, false, units::standard_gravity,
       [](Setup& s) -> double& { return s.gravity; }},
  };
}
}  // namespace

const std::vector<RigField>& rig_fields() {
  static const std::vector<RigField> fields = make_fields();
  return fields;
}

const RigField* find_override_column(std::string_view column) {
  for (const auto& f : rig_fields())
    if (!f.column.empty() && f.column == column) return &f;
  return nullptr;
}

void complete_defaults(Setup& setup, const std::vector<std::string_view>& present) {
  auto has = [&](std::string_view key) {
    return std::find(present.begin(), present.end(), key) != present.end();
  };
  // Without a separate measurement, the walls get the particle-particle rolling resistance and
  // the side panels the plate friction: the reference study calibrated one rolling coefficient for both.
  if (!has("rolling_friction_wall"))
    setup.material.rolling_friction_wall = setup.material.rolling_friction_particle;
  if (!has("friction_side")) setup.material.friction_side = setup.material.friction_plate;
}

}  // namespace chutelab
