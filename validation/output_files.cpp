#include "validation/output_files.h"

#include <cmath>
#include <fmt/format.h>
#include <fstream>

#include "core/campaign.h"
#include "core/input_error.h"

namespace chutelab::validation {

std::string csv_number(double v) { return std::isfinite(v) ? fmt::format("{:.6g}", v) : ""; }
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
      o += fmt::format("{},{},{},{},{},\n", p.condition, p.model, name(q), csv_number(*v * s),
                       u ? csv_number(*u * s) : "");
    }
  }
  // Trajectory predictions, at the points the dataset measured.
  for (const auto& c : r.comparisons)
    if (c.boundary && c.predicted)
      o += fmt::format("{},{},{},{},{},{}\n", c.condition, c.model, c.quantity,
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
    const std::string tol = !c.verdict.checked ? "" : c.verdict.passed ? "pass" : "fail: " + c.verdict.limit;
    // The parts of u_val only beside a prediction: without one nothing was propagated.
    auto part = [&](const std::optional<double>& v) { return c.predicted ? scaled(v) : std::string(); };
    o += fmt::format("{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{}\n", c.condition, c.model, c.quantity,
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
    o += fmt::format("{},{},{},{},{},{},{}\n", s.model, s.quantity, s.n, csv_number(s.rms_error),
                     csv_number(s.rms_normalised_error), csv_number(s.max_abs_relative_error),
                     s.within_tolerance ? (*s.within_tolerance ? "yes" : "no") : "");
  return o;
}

void write_outputs(const std::filesystem::path& dir, const std::vector<OutputFile>& files) {
  namespace fs = std::filesystem;
  // Under mpirun every rank reaches here with the same files; rank 0 alone writes them. (The
  // designer's page compiles this file to WebAssembly, where there are no ranks.)
#ifndef __EMSCRIPTEN__
  if (!campaign::output_rank()) return;
#endif
  std::error_code ec;
  if (fs::exists(dir) && !fs::is_directory(dir))
    throw InputError(dir.string(), 0, "--out", "exists and is not a folder");
  fs::create_directories(dir, ec);
  if (ec) throw InputError(dir.string(), 0, "--out", "cannot create the folder: " + ec.message());
  std::vector<fs::path> staged;
  try {
    for (const auto& [name, content] : files) {
      const fs::path tmp = dir / ("." + name + ".partial");
      std::ofstream out(tmp, std::ios::binary);
      out << content;
      out.close();
      if (!out) throw InputError(tmp.string(), 0, "--out", "cannot write the file");
      staged.push_back(tmp);
    }
  } catch (...) {
    for (const auto& p : staged) fs::remove(p, ec);
    throw;
  }
  for (std::size_t i = 0; i < files.size(); ++i) fs::rename(staged[i], dir / files[i].first);
}

}  // namespace chutelab::validation
