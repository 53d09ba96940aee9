#include "dem/material.h"

#include <cmath>
#include <numbers>

#include <fmt/format.h>

#include "core/input_error.h"

namespace chutelab::dem {

double damping_ratio_from_restitution(double e) {
  if (e >= 1.0) return 0.0;
  const double l = std::log(e);
  return -l / std::sqrt(l * l + std::numbers::pi * std::numbers::pi);
}

int MaterialTable::add(const Material& m) {
  const std::string field = fmt::format("material '{}'", m.name);
  if (!(m.youngs_modulus > 0.0) || !std::isfinite(m.youngs_modulus))
    throw InputError("", 0, field, fmt::format("Young's modulus must be > 0 Pa, got {}", m.youngs_modulus));
  if (!(m.poisson_ratio > -1.0 && m.poisson_ratio < 0.5))
    throw InputError("", 0, field, fmt::format("Poisson ratio must be in (-1, 0.5), got {}", m.poisson_ratio));
  if (!(m.density >= 0.0) || !std::isfinite(m.density))
    throw InputError("", 0, field, fmt::format("density must be >= 0 kg/m^3, got {}", m.density));
  const std::size_t n_old = materials_.size();
  const std::size_t n = n_old + 1;
  std::vector<Interaction> in(n * n);
  for (std::size_t a = 0; a < n_old; ++a)
    for (std::size_t b = 0; b < n_old; ++b) in[a * n + b] = interactions_[a * n_old + b];
  materials_.push_back(m);
  interactions_ = std::move(in);
  coeffs_.assign(n * n, PairCoeffs{});
  for (std::size_t a = 0; a < n; ++a)
    for (std::size_t b = 0; b < n; ++b) derive(static_cast<int>(a), static_cast<int>(b));
  return static_cast<int>(n_old);
}

const Interaction& MaterialTable::interaction(int a, int b) const {
  return interactions_.at(static_cast<std::size_t>(a) * materials_.size() + static_cast<std::size_t>(b));
}

double MaterialTable::shear_modulus(int i) const {
  const Material& m = material(i);
  return m.youngs_modulus / (2.0 * (1.0 + m.poisson_ratio));
}

void MaterialTable::set_interaction(int a, int b, const Interaction& in) {
  if (a < 0 || b < 0 || a >= size() || b >= size())
    throw InputError("", 0, "interaction", fmt::format("unknown material index {} or {}", a, b));
  const std::string field =
      fmt::format("interaction '{}'-'{}'", materials_[static_cast<std::size_t>(a)].name,
                  materials_[static_cast<std::size_t>(b)].name);
  if (!(in.friction >= 0.0)) throw InputError("", 0, field, fmt::format("friction must be >= 0, got {}", in.friction));
  if (!(in.rolling_friction >= 0.0))
    throw InputError("", 0, field, fmt::format("rolling friction must be >= 0, got {}", in.rolling_friction));
  if (!(in.restitution > 0.0 && in.restitution <= 1.0))
    throw InputError("", 0, field, fmt::format("restitution must be in (0, 1], got {}", in.restitution));
  if (!(in.linear_stiffness >= 0.0))
    throw InputError("", 0, field, fmt::format("linear stiffness must be >= 0 N/m, got {}", in.linear_stiffness));
  if (!(in.linear_tangential_ratio >= 0.0))
    throw InputError("", 0, field, "linear tangential stiffness ratio must be >= 0");
  if (!(in.cohesion_energy_density >= 0.0))
    throw InputError("", 0, field, "cohesion energy density must be >= 0 J/m^3");
  if (!(in.rolling_damping_ratio >= 0.0))
    throw InputError("", 0, field, "rolling damping ratio must be >= 0");
  const std::size_t n = materials_.size();
  interactions_[static_cast<std::size_t>(a) * n + static_cast<std::size_t>(b)] = in;
  interactions_[static_cast<std::size_t>(b) * n + static_cast<std::size_t>(a)] = in;
  derive(a, b);
  derive(b, a);
}

void MaterialTable::derive(int a, int b) {
  const std::size_t n = materials_.size();
  const Material& ma = materials_[static_cast<std::size_t>(a)];
  const Material& mb = materials_[static_cast<std::size_t>(b)];
  const Interaction& in = interactions_[static_cast<std::size_t>(a) * n + static_cast<std::size_t>(b)];
  PairCoeffs c;
  c.e_star = 1.0 / ((1.0 - ma.poisson_ratio * ma.poisson_ratio) / ma.youngs_modulus +
                    (1.0 - mb.poisson_ratio * mb.poisson_ratio) / mb.youngs_modulus);
  c.g_star = 1.0 / ((2.0 - ma.poisson_ratio) / shear_modulus(a) + (2.0 - mb.poisson_ratio) / shear_modulus(b));
  c.friction = in.friction;
  c.rolling_friction = in.rolling_friction;
  c.restitution = in.restitution;
  const double beta = damping_ratio_from_restitution(in.restitution);
  // Seed §3 (Tsuji-type damping of Hertz): F_d = 2 sqrt(5/6) beta sqrt(S_n m*) v_n. With the tensile
  // tail of the force allowed this reproduces e exactly for any impact speed (checked by the tests).
  c.hertz_damping = 2.0 * std::sqrt(5.0 / 6.0) * beta;
  c.hertz_tangential_ratio = std::sqrt(4.0 * c.g_star / c.e_star);
  c.linear_kn = in.linear_stiffness;
  c.linear_kt = in.linear_stiffness * in.linear_tangential_ratio;
  c.linear_damping = 2.0 * beta;
  c.cohesion = in.cohesion_energy_density;
  c.rolling_damping_ratio = in.rolling_damping_ratio;
  coeffs_[static_cast<std::size_t>(a) * n + static_cast<std::size_t>(b)] = c;
}

}  // namespace chutelab::dem
