#pragma once
// What a dataset's logs add to the validation report (reports/log_chart.h): a chart and a line of
// words a condition.
#include <string>
#include <vector>

#include "logs/dataset_logs.h"
#include "reports/log_chart.h"

namespace chutelab::api {

std::vector<reports::LogChart> log_charts(const logs::LogImport& logs);
// One line a condition: its log file, its window, its means with their u and what its log said.
std::vector<std::string> log_lines(const logs::LogImport& logs);

}  // namespace chutelab::api
