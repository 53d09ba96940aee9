#pragma once
// What `validate` prints on stdout: the result in a few lines a reader can act on. The counts and
// RMS E/u_val first (one line, before and after an added effect), the quantities the models miss in
// per cent or mm, the diagnosis's verdict, the values outside tolerance as a table, then two or
// three sentences in plain words and where the report is.
#include <string>

#include "reports/report.h"

namespace chutelab::app {

// `added_missing`: the effects were chosen by --add-missing (then "nothing added" is said when the
// diagnosis found nothing to add).
std::string validate_console(const reports::ReportInput& in, bool added_missing, const std::string& report_path);

}  // namespace chutelab::app
