#include "validation/output_files.h"
#include "core/csv_field.h"

#include <cmath>
#include <fmt/format.h>
#include <fstream>

#include "core/input_error.h"

namespace chutelab::validation {

std::string csv_number(double v) { return chutelab::csv_number(v); }
std::string csv_number(const std::optional<double>& v) { return v ? csv_number(*v) : ""; }

namespace {
std::string x_mm(const Comparison& c) { return c.boundary ? csv_number(c.x * 1e3) : ""; }
std::string yz_mm(const Comparison& c) {
  return c.plate_y ? fmt::format("{},{}", csv_number(*c.plate_y * 1e3), csv_number(*c.plate_z * 1e3)) : ",";
}
}  // namespace

std::string predictions_csv(const ValidationResult& r) {
  std::string o = "condition,model,quantity,value,uncertainty,x_mm\n";
  for (const auto& p : r.predictions) {
    for (Quantity q : kAllQuantities) {
      const auto& v = p.prediction.values[q];
      if (!v) continue;
      const double s = info(q).to_boundary;
      const auto& u = p.prediction.uncertainty[q];
      o += fmt::format("{},{},{},{},{},\n", csv_field(p.condition), csv_field(p.model), name(q), csv_number(*v * s),
                       u ? csv_number(*u * s) : "");
    }
  }
  // Trajectory predictions, at the points the dataset measured.
  for (const auto& c : r.comparisons)
    if (c.boundary && c.predicted)
      o += fmt::format("{},{},{},{},{},{}\n", csv_field(c.condition), csv_field(c.model), c.quantity,
                       csv_number(*c.predicted * c.scale),
                       c.u_num_stat() ? csv_number(*c.u_num_stat() * c.scale) : "", x_mm(c));
  return o;
}

std::string errors_csv(const ValidationResult& r) {
  std::string o =
      "condition,model,quantity,measured,uncertainty,predicted,error,relative_error,"
      "normalised_error,x_mm,validation_uncertainty,vv20_ratio,tolerance,u_num_stat,u_num_disc,u_input,y_mm,z_mm\n";
  for (const auto& c : r.comparisons) {
    const double s = c.scale;
    auto scaled = [s](const std::optional<double>& v) {
      return v ? csv_number(*v * s) : std::string();
    };
    const std::string tol = !c.verdict.checked ? "" : c.verdict.passed ? "pass" : csv_field("fail: " + c.verdict.limit);
    // The parts of u_val only beside a prediction: without one nothing was propagated.
    auto part = [&](const std::optional<double>& v) { return c.predicted ? scaled(v) : std::string(); };
    o += fmt::format("{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{}\n", csv_field(c.condition), csv_field(c.model), c.quantity,
                     csv_number(c.measured * s), scaled(c.uncertainty), scaled(c.predicted),
                     c.predicted ? csv_number(c.error() * s) : "", csv_number(c.relative_error()),
                     csv_number(c.normalised_error()), x_mm(c), scaled(c.validation_uncertainty()),
                     csv_number(c.vv20_ratio()), tol, part(c.u_num_stat()), part(c.u_num_disc),
                     part(c.u_input), yz_mm(c));
  }
  return o;
}

std::string summary_csv(const ValidationResult& r) {
  std::string o =
      "model,quantity,n,rms_error,rms_normalised_error,max_abs_relative_error,within_tolerance\n";
  for (const auto& s : r.summary)
    o += fmt::format("{},{},{},{},{},{},{}\n", csv_field(s.model), s.quantity, s.n, csv_number(s.rms_error),
                     csv_number(s.rms_normalised_error), csv_number(s.max_abs_relative_error),
                     s.within_tolerance ? (*s.within_tolerance ? "yes" : "no") : "");
  return o;
}


}  // namespace chutelab::validation
