#pragma once
// Materials and what the user states for each pair of them (reference study §3, Table 1). The contact laws
// derive their per-pair coefficients from these (dem/contact/pair_coeffs.h).
#include <cstdint>
#include <string>
#include <vector>

#include "dem/contact/law_parameters.h"

namespace chutelab::dem {

struct Material {
  std::string name;
  double youngs_modulus = 0.0;  // Pa
  double poisson_ratio = 0.0;
  double density = 0.0;         // kg/m^3 (solid density of the particles; ignored for walls)
};

// What the user states for one pair of materials.
struct Interaction {
  double friction = 0.0;          // Coulomb sliding coefficient mu
  double rolling_friction = 0.0;  // mu_r of reference study Eq 10 (dimensionless)
  double restitution = 1.0;       // normal coefficient of restitution e, 0 < e <= 1
  // Optional cohesion (simplified JKR): attractive force = energy density * contact area.
  double cohesion_energy_density = 0.0;  // J/m^3
  // Elastic-plastic spring-dashpot rolling model (Ai et al. 2011) viscous damping ratio.
  double rolling_damping_ratio = 0.3;
  // The normal contact law's own numbers, by the names the law declares (its `parameters`, e.g. the
  // linear spring-dashpot's normal_stiffness); checked against the scene's law by World::initialise.
  LawParameters law;
};

class MaterialTable {
 public:
  // Returns the material index. Throws InputError for impossible values.
  int add(const Material& m);
  // Sets the interaction of materials a and b (symmetric). Unset pairs are frictionless, elastic.
  void set_interaction(int a, int b, const Interaction& in);
  int size() const { return static_cast<int>(materials_.size()); }
  const Material& material(int i) const { return materials_.at(static_cast<std::size_t>(i)); }
  const Interaction& interaction(int a, int b) const;
  double shear_modulus(int i) const;
  // Counts the changes, so that what is derived from the table (the contact laws' pair
  // coefficients) knows when to derive again.
  std::uint64_t revision() const { return revision_; }

 private:
  std::vector<Material> materials_;
  std::vector<Interaction> interactions_;  // n x n, symmetric
  std::uint64_t revision_ = 0;
};

}  // namespace chutelab::dem
