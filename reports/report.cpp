// Interim renderer: the summary table only, until the full report (tables, charts) lands.
#include "reports/report.h"

#include <fmt/format.h>

#include "validation/output_files.h"

namespace chutelab::reports {

std::string report_markdown(const ReportInput& in) {
  std::string o = fmt::format("# chutelab validation: {}\n\n", in.baseline->dataset_name);
  o += "| model | quantity | n | RMS error | RMS normalised error | max abs relative error |\n";
  o += "|---|---|---|---|---|---|\n";
  for (const auto& s : in.baseline->summary)
    o += fmt::format("| {} | {} | {} | {} | {} | {} |\n", s.model, s.quantity, s.n,
                     validation::csv_number(s.rms_error), validation::csv_number(s.rms_normalised_error),
                     validation::csv_number(s.max_abs_relative_error));
  return o;
}

std::string report_html(const ReportInput& in) {
  return "<!DOCTYPE html><html><head><meta charset=\"utf-8\"><title>chutelab report</title></head>"
         "<body><pre>" + report_markdown(in) + "</pre></body></html>\n";
}

}  // namespace chutelab::reports
