#pragma once
// Progress of a DEM run on stderr: a bar with percentage and an estimate of the time left when
// stderr is a terminal; otherwise a quiet line every quarter (logs stay short). The time left is an
// upper bound: the run stops earlier once the plate force is steady.
#include <string>

#include "dem/station/run.h"

namespace chutelab::dem::station {

class ProgressPrinter {
 public:
  explicit ProgressPrinter(std::string label);
  void operator()(const Progress& p);

 private:
  std::string label_;
  bool tty_;
  int last_quarter_ = -1;
};

}  // namespace chutelab::dem::station
