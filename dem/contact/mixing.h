#pragma once
// Mixing rules: a material pair's effective elastic moduli from its two materials, shared by the laws
// that need them (as LAMMPS' granular sub-models share mix_stiffnessE and mix_stiffnessG).
#include "dem/material.h"

namespace chutelab::dem {

inline double shear_modulus(const Material& m) { return m.youngs_modulus / (2.0 * (1.0 + m.poisson_ratio)); }

// E*, 1/E* = (1 - nu_a^2)/E_a + (1 - nu_b^2)/E_b (Hertz).
inline double effective_youngs_modulus(const Material& a, const Material& b) {
  return 1.0 / ((1.0 - a.poisson_ratio * a.poisson_ratio) / a.youngs_modulus +
                (1.0 - b.poisson_ratio * b.poisson_ratio) / b.youngs_modulus);
}

// G*, 1/G* = (2 - nu_a)/G_a + (2 - nu_b)/G_b (Mindlin).
inline double effective_shear_modulus(const Material& a, const Material& b) {
  return 1.0 / ((2.0 - a.poisson_ratio) / shear_modulus(a) + (2.0 - b.poisson_ratio) / shear_modulus(b));
}

}  // namespace chutelab::dem
