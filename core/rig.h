#pragma once
// The rig (belt, plate, material) and one test condition on it, in SI units. A Station is what a
// model needs to predict one condition: the setup with the condition's overrides applied.
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace chutelab {

struct Trough {
  double idler_angle = 0.0;      // rad; 0 = flat belt
  double centre_roll = 0.0;      // m, length of the centre roll
  double surcharge_angle = 0.0;  // rad, CEMA surcharge angle of the load's top surface
  bool troughed() const { return idler_angle > 0.0; }
};

struct Belt {
  double pulley_diameter = 0.0;  // m
  double belt_thickness = 0.0;   // m
  double belt_width = 0.0;       // m
  double loaded_width = 0.0;     // m, chord W of the load cross-section
  double incline = 0.0;          // rad, > 0 when the belt climbs towards the pulley
  Trough trough;
  double belt_radius() const { return 0.5 * pulley_diameter + belt_thickness; }  // R_b
};

struct Plate {
  double width = 0.0;   // m
  double height = 0.0;  // m
  double angle = 0.0;   // rad from vertical (the reference study's beta); > 0 leans the top towards the pulley
};

struct Material {
  double particle_diameter = 0.0;          // m
  double solid_density = 0.0;              // kg/m^3
  double bulk_density = 0.0;               // kg/m^3, rho_bl
  double youngs_modulus = 0.0;             // Pa
  double poisson_ratio = 0.0;
  double friction_particle = 0.0;          // particle-particle sliding
  double friction_plate = 0.0;             // particle-plate sliding, mu_pw
  double friction_belt = 0.0;              // particle-belt sliding
  double rolling_friction_particle = 0.0;  // reference study Eq 10, particle-particle
  double rolling_friction_wall = 0.0;      // reference study Eq 10, particle-boundary (defaults to particle value)
  double restitution_particle = 0.0;
  double restitution_plate = 0.0;
  double restitution_belt = 0.0;           // conveyor belt, reference study Table 2 (secondary source): 0.4
  double friction_side = 0.0;              // side panels (acrylic in the reference study's rig)
};

struct Setup {
  std::string name;
  std::string source;
  Belt belt;
  Plate plate;
  Material material;
  double gravity = 9.80665;  // m/s^2
};

// One test condition resolved against its setup. Everything in SI.
struct Station {
  std::string condition;
  Belt belt;
  Plate plate;
  Material material;
  double gravity = 9.80665;
  double belt_speed = 0.0;      // V_b, m/s
  double mass_flow = 0.0;       // m_s, kg/s
  double plate_distance = 0.0;  // Z, m: x of the plate face at its top edge
  double plate_top = 0.0;       // m: y of the plate's top edge
  std::optional<double> stream_thickness;  // h_b, m; from continuity when absent
};

// The table of named rig parameters: one place that says how each boundary name maps to SI, what
// range is physical, and which conditions.csv column may override it per condition.
struct RigField {
  std::string_view section;     // TOML table: "belt", "plate", "material", or "" for top level
  std::string_view key;         // TOML key, with unit suffix
  std::string_view column;      // conditions.csv override column ("" = not overridable)
  double to_si;                 // boundary value * to_si = SI value
  double min, max;              // physical range at the boundary (inclusive)
  bool required;
  std::optional<double> fallback;  // boundary value used when absent and not required
  std::function<double&(Setup&)> ref;
  std::string_view label = {};  // plain words with the unit, for people (the designer's page)
  std::string_view default_from = {};  // when absent: the value of this key of the same table
};
const std::vector<RigField>& rig_fields();
const RigField* find_override_column(std::string_view column);

// Fill the defaults that depend on other fields (RigField::default_from: e.g. wall rolling friction =
// particle value).
void complete_defaults(Setup& setup, const std::vector<std::string_view>& present_keys);

}  // namespace chutelab
