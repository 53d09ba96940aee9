#include "validation/failed_values.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <fmt/format.h>

namespace chutelab::validation {
namespace {

// Columns line up by characters, not bytes ("±", "≤").
std::size_t utf8_width(const std::string& s) {
  return static_cast<std::size_t>(std::count_if(s.begin(), s.end(), [](char c) { return (c & 0xC0) != 0x80; }));
}

// Four significant digits, fixed notation in the usual range of the vocabulary's units.
std::string num(double v) {
  if (v == 0.0) return "0";
  const int mag = static_cast<int>(std::floor(std::log10(std::abs(v))));
  if (mag < -4 || mag > 6) return fmt::format("{:.3e}", v);
  return fmt::format("{:.{}f}", v, std::clamp(3 - mag, 0, 6));
}

std::string what(const Comparison& c) {
  if (c.q) return fmt::format("{} {}", info(*c.q).symbol, info(*c.q).label);
  if (c.boundary)
    return fmt::format("y_{} {} stream boundary at x = {:.0f} mm", name(*c.boundary), name(*c.boundary), c.x * 1e3);
  if (c.plate_y && c.plate_z)
    return fmt::format("{} at y = {:.0f} mm, z = {:.0f} mm", c.quantity, *c.plate_y * 1e3, *c.plate_z * 1e3);
  return c.quantity;
}

// The broken limit as the largest allowed |E| in the quantity's unit, and what it was set as.
std::string limit_text(const Comparison& c) {
  const std::string u = c.unit();
  const double scale = c.scale;
  const double measured = std::abs(c.measured * scale);
  const auto& v = c.verdict;
  if (v.kind == "relative")
    return fmt::format("±{} {} (relative {:.3g} %)", num(v.allowed * measured), u, 100.0 * v.allowed);
  if (v.kind == "absolute") {
    const bool percent = c.q && c.q != Quantity::impact_point_y && measured > 0.0;
    return percent ? fmt::format("±{} {} (absolute; {:.1f} % of measured)", num(v.allowed), u, 100.0 * v.allowed / measured)
                   : fmt::format("±{} {} (absolute)", num(v.allowed), u);
  }
  if (v.kind == "normalised") {
    const auto uval = c.validation_uncertainty();
    if (!uval || !(*uval > 0.0)) return fmt::format("|E|/u_val ≤ {:.3g} (no uncertainty stated)", v.allowed);
    return fmt::format("±{} {} ({:.3g} u_val)", num(v.allowed * *uval * scale), u, v.allowed);
  }
  return v.limit;
}

}  // namespace

std::vector<FailedValue> failed_values(const ValidationResult& r) {
  std::vector<FailedValue> out;
  for (const auto& c : r.comparisons) {
    if (!c.verdict.checked || c.verdict.passed || !c.predicted) continue;
    const std::string u = c.unit();
    FailedValue f;
    f.condition = c.condition;
    f.model = c.model;
    f.quantity = what(c);
    f.measured = c.uncertainty ? fmt::format("{} ± {:.2g} {}", num(c.measured * c.scale), *c.uncertainty * c.scale, u)
                               : fmt::format("{} {}", num(c.measured * c.scale), u);
    f.predicted = fmt::format("{} {}", num(*c.predicted * c.scale), u);
    f.error = fmt::format("{}{} {}", c.error() >= 0 ? "+" : "", num(c.error() * c.scale), u);
    // Per cent of a height means nothing (its zero is the pulley's centre): forces and speeds only.
    if (const auto rel = c.relative_error(); rel && c.q && c.q != Quantity::impact_point_y)
      f.error += fmt::format(" ({:+.1f} %)", 100.0 * *rel);
    f.limit = limit_text(c);
    out.push_back(std::move(f));
  }
  return out;
}

std::string failure_table_text(const ValidationResult& r, std::size_t max_rows, const std::string& rest_in) {
  const auto failed = failed_values(r);
  if (failed.empty()) return {};
  std::vector<std::array<std::string, 7>> rows = {
      {"condition", "model", "quantity", "measured", "predicted", "error", "limit"}};
  for (std::size_t k = 0; k < failed.size() && k < max_rows; ++k) {
    const auto& f = failed[k];
    rows.push_back({f.condition, f.model, f.quantity, f.measured, f.predicted, f.error, f.limit});
  }
  std::array<std::size_t, 7> width{};
  for (const auto& row : rows)
    for (std::size_t j = 0; j < row.size(); ++j) width[j] = std::max(width[j], utf8_width(row[j]));
  std::string o = fmt::format("{} of {} checked values outside tolerance ({}):\n", failed.size(), r.checked_count(),
                              r.models.size() == 1 ? r.models.front() : fmt::format("{}", fmt::join(r.models, ", ")));
  for (const auto& row : rows) {
    std::string line = " ";
    for (std::size_t j = 0; j < row.size(); ++j) {
      line += " " + row[j];
      if (j + 1 < row.size()) line += std::string(width[j] - utf8_width(row[j]) + 1, ' ');
    }
    o += line + "\n";
  }
  if (failed.size() > max_rows)
    o += fmt::format("  ... and {} more (every one in {})\n", failed.size() - max_rows, rest_in);
  return o;
}

}  // namespace chutelab::validation
