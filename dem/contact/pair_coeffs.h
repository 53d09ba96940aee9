#pragma once
// What the contact loop reads per material pair: the normal law's own coefficients (its mixing rule,
// Law::mix) and those every other contact part reads, derived once from the MaterialTable.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "dem/material.h"

namespace chutelab::dem {

// The coefficients of the tangential, rolling and cohesion parts.
struct SharedCoeffs {
  double friction = 0.0;          // Coulomb sliding coefficient
  double rolling_friction = 0.0;  // mu_r (reference study Eq 10)
  double rolling_damping_ratio = 0.0;
  double cohesion = 0.0;          // J/m^3 (sJKR)
};

template <class Law>
struct PairCoeffs : SharedCoeffs {
  typename Law::Coeffs normal;
};

template <class Law>
PairCoeffs<Law> pair_coeffs(const Material& a, const Material& b, const Interaction& in) {
  PairCoeffs<Law> c;
  c.friction = in.friction;
  c.rolling_friction = in.rolling_friction;
  c.rolling_damping_ratio = in.rolling_damping_ratio;
  c.cohesion = in.cohesion_energy_density;
  c.normal = Law::mix(a, b, in);
  return c;
}

// Every material pair's coefficients for one law, row-major: table[a * materials + b].
template <class Law>
std::vector<PairCoeffs<Law>> pair_table(const MaterialTable& mt) {
  const auto n = static_cast<std::size_t>(mt.size());
  std::vector<PairCoeffs<Law>> t(n * n);
  for (int a = 0; a < mt.size(); ++a)
    for (int b = 0; b < mt.size(); ++b)
      t[static_cast<std::size_t>(a) * n + static_cast<std::size_t>(b)] =
          pair_coeffs<Law>(mt.material(a), mt.material(b), mt.interaction(a, b));
  return t;
}

}  // namespace chutelab::dem
