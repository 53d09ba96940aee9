#pragma once
// Materials and per-pair interaction coefficients (seed §3, Table 1). A MaterialTable owns both and
// derives the effective moduli and damping factors once, so the contact loop only reads numbers.
#include <string>
#include <vector>

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
  double rolling_friction = 0.0;  // mu_r of seed Eq 10 (dimensionless)
  double restitution = 1.0;       // normal coefficient of restitution e, 0 < e <= 1
  // Linear spring-dashpot (seed Eq 8) only: normal stiffness k_n in N/m and k_t / k_n.
  double linear_stiffness = 0.0;
  double linear_tangential_ratio = 2.0 / 7.0;  // 2/7 gives equal normal and tangential periods
  // Optional cohesion (simplified JKR): attractive force = energy density * contact area.
  double cohesion_energy_density = 0.0;  // J/m^3
  // Elastic-plastic spring-dashpot rolling model (Ai et al. 2011) viscous damping ratio.
  double rolling_damping_ratio = 0.3;
};

// Derived numbers used by the contact laws.
struct PairCoeffs {
  double e_star = 0.0;      // effective Young's modulus E*, 1/E* = (1-nu_i^2)/E_i + (1-nu_j^2)/E_j
  double g_star = 0.0;      // effective shear modulus G*, 1/G* = (2-nu_i)/G_i + (2-nu_j)/G_j
  double friction = 0.0;
  double rolling_friction = 0.0;
  double restitution = 1.0;
  double hertz_damping = 0.0;  // 2 sqrt(5/6) beta, beta = -ln e / sqrt(ln^2 e + pi^2) (seed §3)
  double hertz_tangential_ratio = 0.0;  // sqrt(S_t / S_n) = sqrt(4 G* / E*)
  double linear_kn = 0.0;      // N/m
  double linear_kt = 0.0;      // N/m
  double linear_damping = 0.0; // 2 zeta, zeta = -ln e / sqrt(ln^2 e + pi^2) (exact for Eq 8)
  double cohesion = 0.0;       // J/m^3
  double rolling_damping_ratio = 0.0;
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
  const PairCoeffs& pair(int a, int b) const {
    return coeffs_[static_cast<std::size_t>(a) * materials_.size() + static_cast<std::size_t>(b)];
  }
  double shear_modulus(int i) const;
  // Row-major n x n table for the contact loop: pair(a, b) == coeff_table()[a * size() + b].
  const PairCoeffs* coeff_table() const { return coeffs_.data(); }

 private:
  void derive(int a, int b);
  std::vector<Material> materials_;
  std::vector<Interaction> interactions_;  // n x n, symmetric
  std::vector<PairCoeffs> coeffs_;         // n x n, symmetric
};

// beta of the seed's damping formula for restitution e: -ln e / sqrt(ln^2 e + pi^2).
double damping_ratio_from_restitution(double e);

}  // namespace chutelab::dem
