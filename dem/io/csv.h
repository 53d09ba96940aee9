#pragma once
// CSV time series of a run: one row per call to record(), with particle count, energies, the fastest
// particle, and force and torque of every wall (load cells).
#include <fstream>
#include <string>

#include "dem/world.h"

namespace chutelab::dem {

class TimeSeriesCsv {
 public:
  // Writes the header for the world's current walls.
  TimeSeriesCsv(const std::string& path, const World& world);
  void record(const World& world);

 private:
  std::ofstream out_;
  std::string path_;
  std::size_t walls_;
};

}  // namespace chutelab::dem
