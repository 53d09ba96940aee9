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

// Lines for the console (the results a command prints): each line escaped as messages are
// (core/message.h one_line: controls, bytes that are not UTF-8, invisible and direction-changing
// code points), so that a name from the data cannot reorder or hide what is printed around it (a
// right-to-left override in a condition name). Line ends are kept.
std::string console_text(const std::string& text);

}  // namespace chutelab::app
