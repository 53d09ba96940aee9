#pragma once
// Progress of a DEM run (core/progress.h): on a terminal a bar with percentage and an estimate of
// the time left on the status line, rewritten in place; one line when the run ends (left to the
// campaign when the run is one of its jobs); nothing with --quiet. The time left is an upper
// bound: the run stops earlier once the plate force is steady.
#include <string>

#include "dem/station/run.h"

namespace chutelab::dem::station {

class ProgressPrinter {
 public:
  explicit ProgressPrinter(std::string label);
  void operator()(const Progress& p);

 private:
  std::string label_;
};

}  // namespace chutelab::dem::station
