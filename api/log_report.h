#pragma once
// What a dataset's logs add to the validation report (reports/log_chart.h): a chart and a line of
// words a condition.
#include <string>
#include <vector>

#include "logs/dataset_logs.h"
#include "reports/log_chart.h"

namespace chutelab::api {

std::vector<reports::LogChart> log_charts(const logs::LogImport& logs);
// "V2-26 (logs/V2-26.csv): window 6.3-34.1 s; R_n 14.93 ± 0.08 N, ...; zero drift ...; creep ..."
std::vector<std::string> log_lines(const logs::LogImport& logs);

}  // namespace chutelab::api
