#include "validation/quantity_misfit.h"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <gsl/gsl_cdf.h>
#include <map>

#include "validation/model.h"

namespace chutelab::validation {
namespace {

// Quantities whose zero is physical: their error reads best as a share of the value.
bool relative_quantity(const Comparison& c) {
  if (!c.q) return false;
  return c.q != Quantity::impact_point_y;
}

std::string words_of(const Comparison& c, std::string* symbol) {
  if (c.q) {
    *symbol = std::string(info(*c.q).symbol);
    return std::string(info(*c.q).label);
  }
  if (c.boundary) {
    *symbol = fmt::format("y_{}", name(*c.boundary));
    return fmt::format("{} stream boundary", name(*c.boundary));
  }
  *symbol = c.quantity;
  return "plate map " + c.quantity;
}

}  // namespace

std::vector<QuantityMisfit> quantity_misfits(const ValidationResult& r) {
  // The judging model per value, as the combined figure picks it.
  const auto order = model_names();
  auto rank = [&](const std::string& m) {
    return static_cast<std::size_t>(std::find(order.begin(), order.end(), m) - order.begin());
  };
  std::map<std::tuple<std::string, std::string, double, double, double>, const Comparison*> chosen;
  for (const auto& c : r.comparisons) {
    if (!c.normalised_error()) continue;
    auto& slot = chosen[{c.condition, c.quantity, c.x, c.plate_y.value_or(0.0), c.plate_z.value_or(0.0)}];
    if (!slot || rank(c.model) < rank(slot->model)) slot = &c;
  }
  // Per quantity, the model that judges most of its values (one model in practice).
  std::map<std::string, std::map<std::string, std::vector<const Comparison*>>> by_quantity;
  for (const auto& [key, c] : chosen) by_quantity[c->quantity][c->model].push_back(c);

  std::vector<std::string> quantities;
  for (Quantity q : kAllQuantities) quantities.emplace_back(name(q));
  for (Boundary b : kAllBoundaries) quantities.push_back(trajectory_quantity(b));
  for (const auto& [q, models] : by_quantity)
    if (std::find(quantities.begin(), quantities.end(), q) == quantities.end()) quantities.push_back(q);

  std::vector<QuantityMisfit> out;
  for (const auto& qn : quantities) {
    const auto it = by_quantity.find(qn);
    if (it == by_quantity.end()) continue;
    const auto best = std::max_element(it->second.begin(), it->second.end(),
                                       [](const auto& a, const auto& b) { return a.second.size() < b.second.size(); });
    const auto& values = best->second;
    QuantityMisfit m;
    m.quantity = qn;
    m.model = best->first;
    m.label = words_of(*values.front(), &m.symbol);
    m.unit = values.front()->unit();
    m.in_percent = relative_quantity(*values.front()) &&
                   std::all_of(values.begin(), values.end(), [](const Comparison* c) { return c->relative_error(); });
    double sum_e = 0.0, sum_z = 0.0, sum_z2 = 0.0;
    for (const Comparison* c : values) {
      const double z = *c->normalised_error();
      const double e = m.in_percent ? *c->relative_error() : c->error() * c->scale;
      sum_e += e;
      sum_z += z;
      sum_z2 += z * z;
      // The largest error in the quantity's own terms: what an engineer designs against.
      if (m.worst_condition.empty() || std::abs(e) > std::abs(m.worst_error)) {
        m.worst_condition = c->condition;
        m.worst_error = e;
        m.worst_normalised = z;
      }
    }
    m.n = static_cast<int>(values.size());
    m.mean_error = sum_e / m.n;
    m.mean_normalised = sum_z / m.n;
    m.rms_normalised = std::sqrt(sum_z2 / m.n);
    m.beyond_noise = gsl_cdf_chisq_Q(sum_z2, m.n) < 0.01 || std::abs(m.worst_normalised) > 4.0;
    out.push_back(std::move(m));
  }
  return out;
}

std::optional<QuantityMisfit> find_misfit(const std::vector<QuantityMisfit>& all, const std::string& quantity) {
  for (const auto& m : all)
    if (m.quantity == quantity) return m;
  return std::nullopt;
}

std::string signed_amount(const QuantityMisfit& m, double value) {
  if (m.in_percent) return fmt::format("{:+.1f} %", 100.0 * value);
  return fmt::format("{:+.{}f} {}", value, m.unit == "mm" ? 1 : 3, m.unit);
}

std::string amount_words(const QuantityMisfit& m, double value) {
  const double shown = m.in_percent ? 100.0 * value : value;
  const int decimals = m.in_percent || m.unit == "mm" ? 1 : 3;
  const std::string unit = m.in_percent ? "%" : m.unit;
  if (std::abs(shown) < 0.5 * std::pow(10.0, -decimals)) return fmt::format("within 0.{}1 {}", std::string(decimals - 1, '0'), unit);
  return fmt::format("{:.{}f} {} {}", std::abs(shown), decimals, unit, shown > 0 ? "high" : "low");
}

}  // namespace chutelab::validation
