#include "dem/material.h"

#include <cmath>
#include <numbers>

#include <fmt/format.h>

#include "core/input_error.h"
#include "dem/contact/mixing.h"

namespace chutelab::dem {

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
  ++revision_;
  return static_cast<int>(n_old);
}

const Interaction& MaterialTable::interaction(int a, int b) const {
  return interactions_.at(static_cast<std::size_t>(a) * materials_.size() + static_cast<std::size_t>(b));
}

double MaterialTable::shear_modulus(int i) const { return dem::shear_modulus(material(i)); }

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
  for (const auto& [key, value] : in.law.values())
    if (!std::isfinite(value)) throw InputError("", 0, field, fmt::format("law parameter {} must be finite", key));
  if (!(in.cohesion_energy_density >= 0.0))
    throw InputError("", 0, field, "cohesion energy density must be >= 0 J/m^3");
  if (!(in.rolling_damping_ratio >= 0.0))
    throw InputError("", 0, field, "rolling damping ratio must be >= 0");
  const std::size_t n = materials_.size();
  interactions_[static_cast<std::size_t>(a) * n + static_cast<std::size_t>(b)] = in;
  interactions_[static_cast<std::size_t>(b) * n + static_cast<std::size_t>(a)] = in;
  ++revision_;
}

}  // namespace chutelab::dem
