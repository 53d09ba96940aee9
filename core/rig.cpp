#include "core/rig.h"
#include "core/rig_needs.h"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>

#include "core/input_error.h"
#include "core/message.h"
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
       [](Setup& s) -> double& { return s.belt.pulley_diameter; }, "head pulley diameter (mm)"},
      {"belt", "belt_thickness_mm", "belt_thickness_mm", mm, 0.0, 200.0, true, {},
       [](Setup& s) -> double& { return s.belt.belt_thickness; }, "belt thickness (mm)"},
      {"belt", "belt_width_mm", "belt_width_mm", mm, 1.0, 1e4, true, {},
       [](Setup& s) -> double& { return s.belt.belt_width; }, "belt width (mm)"},
      {"belt", "loaded_width_mm", "loaded_width_mm", mm, 1.0, 1e4, true, {},
       [](Setup& s) -> double& { return s.belt.loaded_width; }, "loaded width of the belt (mm)"},
      {"belt", "incline_deg", "belt_incline_deg", deg, -45.0, 45.0, true, {},
       [](Setup& s) -> double& { return s.belt.incline; }, "belt incline at the pulley (°)"},
      {"belt", "trough_angle_deg", "trough_angle_deg", deg, 0.0, 60.0, false, 0.0,
       [](Setup& s) -> double& { return s.belt.trough.idler_angle; }, "trough idler angle (°; 0 = flat belt)"},
      {"belt", "centre_roll_mm", "centre_roll_mm", mm, 0.0, 1e4, false, 0.0,
       [](Setup& s) -> double& { return s.belt.trough.centre_roll; }, "trough centre roll length (mm)"},
      {"belt", "surcharge_angle_deg", "surcharge_angle_deg", deg, 0.0, 45.0, false, 20.0,
       [](Setup& s) -> double& { return s.belt.trough.surcharge_angle; }, "surcharge angle of the load (°)"},
      {"plate", "width_mm", "plate_width_mm", mm, 1.0, 1e4, true, {},
       [](Setup& s) -> double& { return s.plate.width; }, "plate width (mm)"},
      {"plate", "height_mm", "plate_height_mm", mm, 1.0, 1e4, true, {},
       [](Setup& s) -> double& { return s.plate.height; }, "plate height (mm)"},
      {"plate", "angle_deg", "plate_angle_deg", deg, -60.0, 60.0, true, {},
       [](Setup& s) -> double& { return s.plate.angle; }, "plate angle from vertical (°)"},
      {"material", "particle_diameter_mm", "particle_diameter_mm", mm, 1e-3, 1e3, false, {},
       [](Setup& s) -> double& { return s.material.particle_diameter; }, "particle diameter (mm)"},
      {"material", "solid_density_kgm3", "solid_density_kgm3", 1.0, 1.0, 3e4, false, {},
       [](Setup& s) -> double& { return s.material.solid_density; }, "solid density (kg/m³)"},
      {"material", "bulk_density_kgm3", "bulk_density_kgm3", 1.0, 1.0, 3e4, true, {},
       [](Setup& s) -> double& { return s.material.bulk_density; }, "bulk density (kg/m³)"},
      {"material", "youngs_modulus_Pa", "youngs_modulus_Pa", 1.0, 1e3, 1e13, false, {},
       [](Setup& s) -> double& { return s.material.youngs_modulus; }, "Young's modulus (Pa)"},
      {"material", "poisson_ratio", "poisson_ratio", 1.0, -0.99, 0.5, false, {},
       [](Setup& s) -> double& { return s.material.poisson_ratio; }, "Poisson's ratio"},
      {"material", "friction_particle", "friction_particle", 1.0, 0.0, 10.0, false, {},
       [](Setup& s) -> double& { return s.material.friction_particle; }, "friction, particle–particle"},
      {"material", "friction_plate", "friction_plate", 1.0, 0.0, 10.0, true, {},
       [](Setup& s) -> double& { return s.material.friction_plate; }, "friction, particle–plate"},
      {"material", "friction_belt", "friction_belt", 1.0, 0.0, 10.0, false, {},
       [](Setup& s) -> double& { return s.material.friction_belt; }, "friction, particle–belt"},
      {"material", "friction_side", "friction_side", 1.0, 0.0, 10.0, false, {},
       [](Setup& s) -> double& { return s.material.friction_side; }, "friction, particle–side wall",
       "friction_plate"},
      {"material", "rolling_friction_particle", "rolling_friction_particle", 1.0, 0.0, 10.0, false,
       {}, [](Setup& s) -> double& { return s.material.rolling_friction_particle; }, "rolling friction, particle–particle"},
      {"material", "rolling_friction_wall", "rolling_friction_wall", 1.0, 0.0, 10.0, false, {},
       [](Setup& s) -> double& { return s.material.rolling_friction_wall; }, "rolling friction, particle–wall",
       "rolling_friction_particle"},
      {"material", "restitution_particle", "restitution_particle", 1.0, 0.0, 1.0, false, {},
       [](Setup& s) -> double& { return s.material.restitution_particle; }, "restitution, particle–particle"},
      {"material", "restitution_plate", "restitution_plate", 1.0, 0.0, 1.0, false, {},
       [](Setup& s) -> double& { return s.material.restitution_plate; }, "restitution, particle–plate"},
      {"material", "restitution_belt", "restitution_belt", 1.0, 0.0, 1.0, false, 0.4,
       [](Setup& s) -> double& { return s.material.restitution_belt; }, "restitution, particle–belt"},
      {"", "gravity_mps2", "", 1.0, 0.01, 1e4, false, units::standard_gravity,
       [](Setup& s) -> double& { return s.gravity; }, "gravity (m/s²)"},
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
  for (const auto& f : rig_fields()) {
    if (f.default_from.empty() || has(f.key)) continue;
    for (const auto& from : rig_fields())
      if (from.section == f.section && from.key == f.default_from) f.ref(setup) = from.ref(setup);
  }
}

bool read_by_dem_only(const RigField& f) {
  // The contact model's inputs; the particle's size and density also feed air drag's force in flight.
  static constexpr std::string_view kKeys[] = {
      "particle_diameter_mm", "solid_density_kgm3",        "youngs_modulus_Pa",    "poisson_ratio",
      "friction_particle",    "friction_belt",             "rolling_friction_particle",
      "restitution_particle", "restitution_plate"};
  if (f.section != "material") return false;
  for (auto k : kKeys)
    if (f.key == k) return true;
  return false;
}

std::vector<std::string> missing_dem_keys(const Station& st) {
  Setup s;
  s.belt = st.belt;
  s.plate = st.plate;
  s.material = st.material;
  s.gravity = st.gravity;
  std::vector<std::string> out;
  for (const auto& f : rig_fields())
    if (read_by_dem_only(f) && !std::isfinite(f.ref(s))) out.push_back(fmt::format("{}.{}", f.section, f.key));
  return out;
}

void require_dem_keys(const Station& st, std::string_view file, std::string_view who) {
  const auto missing = missing_dem_keys(st);
  if (missing.empty()) return;
  throw InputError(std::string(file), 0, missing.front(),
                   fmt::format("{} needs {} more material value{} the analytical models do without: {} (give them in "
                               "[material]; each key and its unit: docs/dataset-reference.md)",
                               who, missing.size(), missing.size() == 1 ? "" : "s", fmt::join(missing, ", ")));
}

std::string air_drag_unavailable(const std::vector<Station>& stations) {
  for (const auto& st : stations)
    if (!std::isfinite(st.material.particle_diameter) || !std::isfinite(st.material.solid_density))
      return fmt::format(
          "air drag cannot be tried on this rig: it needs material.particle_diameter_mm and "
          "material.solid_density_kgm3 in setup.toml (condition {} has none); the diagnosis ranks the other "
          "candidates without it",
          shown(st.condition));
  return {};
}

}  // namespace chutelab
