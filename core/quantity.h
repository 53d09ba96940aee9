#pragma once
// The measurement vocabulary of DESIGN.md section 2: every stage (dataset, models, comparison,
// diagnosis, report) talks about these quantities and nothing model-specific.
#include <array>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace chutelab {

enum class Quantity {
  normal_force,       // R_n, N
  shear_force,        // R_s, N
  resultant_force,    // R, N
  impact_velocity,    // V_p, m/s
  exit_velocity,      // V_a, m/s
  impact_point_y,     // y of the point of application of R_n, m inside, mm at the boundary
  // Optional measurements that separate candidate explanations (DESIGN.md §6):
  belt_layer_velocity,  // mean speed along the belt of the layer 20-100 mm before the pulley, m/s
  stream_mass_flow,     // mass flux of the free stream between pulley and plate, kg/s inside, t/h at the boundary
};
inline constexpr std::size_t kQuantityCount = 8;
inline constexpr std::array<Quantity, kQuantityCount> kAllQuantities = {
    Quantity::normal_force,    Quantity::shear_force,   Quantity::resultant_force,
    Quantity::impact_velocity, Quantity::exit_velocity, Quantity::impact_point_y,
    Quantity::belt_layer_velocity, Quantity::stream_mass_flow};

struct QuantityInfo {
  Quantity quantity;
  std::string_view name;     // file name with unit, e.g. "normal_force_N"
  std::string_view symbol;   // the reference study's symbol, e.g. "R_n"
  std::string_view label;    // words for reports
  std::string_view unit;     // boundary unit
  double to_boundary;        // SI value * to_boundary = boundary value
  // A magnitude (a speed, the resultant) cannot be negative: the dataset reader refuses it and the
  // synthesizer's noise must respect it. R_n and R_s are signed components, y_R a coordinate.
  bool magnitude;
  // Measured only by rigs instrumented for it (DESIGN.md §6): a synthesized dataset carries it only
  // where its source dataset did.
  bool optional = false;
};

const QuantityInfo& info(Quantity q);
std::optional<Quantity> parse_quantity(std::string_view name);
inline std::string_view name(Quantity q) { return info(q).name; }

// Stream boundaries that trajectory.csv can hold.
enum class Boundary { upper, lower, centre };
inline constexpr std::array<Boundary, 3> kAllBoundaries = {Boundary::upper, Boundary::lower,
                                                           Boundary::centre};
std::string_view name(Boundary b);
std::optional<Boundary> parse_boundary(std::string_view name);
// Compared stream points travel under "trajectory_<boundary>_y_mm" (predictions.csv, errors.csv,
// tolerances.toml), so that they sit in one long table with the quantities above.
std::string trajectory_quantity(Boundary b);

// A model's (or a measurement set's) values for one condition, SI. Absent = not predicted.
struct QuantityValues {
  std::array<std::optional<double>, kQuantityCount> value{};
  std::optional<double>& operator[](Quantity q) { return value[static_cast<std::size_t>(q)]; }
  const std::optional<double>& operator[](Quantity q) const {
    return value[static_cast<std::size_t>(q)];
  }
};

}  // namespace chutelab
