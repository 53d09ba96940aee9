#pragma once
// The numbers a normal contact law reads for a material pair beyond the moduli, restitution and
// friction every law shares: each law declares its own (name, unit, meaning, default), and an
// Interaction carries the values by name (Interaction::law). A law reads only what it declared,
// and World::initialise rejects a name the scene's law does not declare.
#include <cmath>
#include <initializer_list>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace chutelab::dem {

// One number a law declares.
struct LawParameter {
  std::string_view key;      // its name in Interaction::law
  std::string_view unit;     // SI; "" if dimensionless
  std::string_view meaning;
  double fallback;           // used when the interaction does not give it (kRequired, kOwnRule: see below)
  // The interaction must give it (value() is NaN otherwise, which the law's check refuses).
  static constexpr double kRequired = std::numeric_limits<double>::quiet_NaN();
  // The law derives it from its other parameters when the interaction does not give it (its meaning
  // says how; the law reads it with get(), not value()).
  static constexpr double kOwnRule = -std::numeric_limits<double>::infinity();
};

// The values an interaction gives, by name.
class LawParameters {
 public:
  LawParameters() = default;
  LawParameters(std::initializer_list<std::pair<std::string_view, double>> values) {
    for (const auto& [k, v] : values) set(k, v);
  }
  LawParameters& set(std::string_view key, double value) {
    for (auto& [k, v] : values_)
      if (k == key) {
        v = value;
        return *this;
      }
    values_.emplace_back(std::string(key), value);
    return *this;
  }
  std::optional<double> get(std::string_view key) const {
    for (const auto& [k, v] : values_)
      if (k == key) return v;
    return std::nullopt;
  }
  // The value of a declared parameter: the interaction's, else its fallback (NaN if required).
  double value(const LawParameter& p) const { return get(p.key).value_or(p.fallback); }
  const std::vector<std::pair<std::string, double>>& values() const { return values_; }
  bool empty() const { return values_.empty(); }

 private:
  std::vector<std::pair<std::string, double>> values_;
};

}  // namespace chutelab::dem
