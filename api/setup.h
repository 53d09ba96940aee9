#pragma once
// A rig as the dataset reader reads it, for the front ends that start from one file or one row
// rather than a whole dataset (the designer's page, `chutelab design`): the same checks and
// messages as a dataset's. Only core/ types cross here, so the page's WebAssembly build and the
// command line share it without the dataset's readers in their headers.
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "core/rig.h"

namespace chutelab::api {

// setup.toml, checked as a dataset's. Throws InputError naming the file, line and key.
Setup read_setup(const std::filesystem::path& file);

// The row `condition` of the dataset folder `dir`'s conditions.csv, read against `setup`. None:
// InputError naming the file and `field` (the caller's word for what chose the row).
Station read_condition(const std::filesystem::path& dir, const Setup& setup, std::string_view condition,
                       std::string_view field);

// The bounds no conveyor reaches, one row an operating input (conditions.csv's column and unit):
// beyond them a number is a unit slip. The designer's page sets its sliders by them.
struct OperatingLimit {
  std::string column;
  double min = 0.0;     // exclusive when min_open
  bool min_open = false;
  double max = 0.0;     // inclusive
};
std::vector<OperatingLimit> operating_limits();

}  // namespace chutelab::api
