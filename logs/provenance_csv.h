#pragma once
// The files an import of logs writes beside measurements.csv: its rows with their provenance
// (measurements_rows: file, window, method; the reader takes the extra columns as comments) and
// log_provenance.csv, every number behind each mean: the window, the zeros and their drift, the
// creep, the autocorrelation time and effective sample count, the batches, and each part of the
// uncertainty; then the belt's own channels against the record. Values and uncertainty parts are in
// the quantity's unit (the suffix of its name, as in measurements.csv).
#include <string>

#include "logs/dataset_logs.h"

namespace chutelab::logs {

// measurements.csv: `rows` (the dataset's own measurements.csv rows, written as they were) and the
// logs' rows with the columns source_file,window_start_s,window_end_s,method.
std::string measurements_csv(const validation::Dataset& d, const LogImport& logs);

std::string log_provenance_csv(const LogImport& logs);

// log_checks.csv: the belt's own channels (tachometer, belt scale) against the recorded operating
// point: condition,channel,check (belt_speed_mps or mass_flow_tph: the unit of the next three
// columns),recorded,logged,logged_uncertainty,difference_percent,off (beyond 3 u).
std::string log_checks_csv(const LogImport& logs);

// One line of words for a quantity's method, e.g. "mean of 1490 samples at 50 Hz; u: 9 batch means
// of 3.0 s (tau 0.50 s, 30 independent samples), tare before and after, calibration, resolution".
std::string method_words(const ConditionReading& c, const QuantityReading& q);

}  // namespace chutelab::logs
