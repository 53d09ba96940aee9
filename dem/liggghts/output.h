#pragma once
// Readers of what a LIGGGHTS deck (deck.h) writes: the plate's `fix ave/time` file, the `dump
// custom` particle frames and the log (particle counts, inserted mass). Malformed files throw
// InputError naming the file, the line and what is wrong.
#include <cstdint>
#include <fstream>
#include <string>
#include <vector>

#include "dem/types.h"

namespace chutelab::dem::liggghts {

// One line of the plate file: the force and torque on the stress mesh, averaged over the steps
// ending at `step`.
struct PlateSample {
  long long step = 0;
  Vec3 force = Vec3::Zero();   // N
  Vec3 torque = Vec3::Zero();  // N m, about the mesh's reference point
};
std::vector<PlateSample> read_plate_file(const std::string& path);

struct Frame {
  long long step = 0;
  std::vector<std::int64_t> id;
  std::vector<Vec3> x, v;       // m, m/s
  std::vector<double> mass;     // kg
};

// Reads a dump custom file frame by frame (needs the columns id x y z vx vy vz mass, any order).
class DumpReader {
 public:
  explicit DumpReader(std::string path);
  bool next(Frame& f);  // false at the end of the file

 private:
  [[noreturn]] void fail(const std::string& what) const;
  std::string path_;
  std::ifstream in_;
  long line_ = 0;
};

struct LogSummary {
  std::size_t peak_atoms = 0, final_atoms = 0;
  double inserted_mass = 0.0;  // kg, the last "inserted so far" report
  std::string error;           // the first "ERROR" line, if any
  std::string version;         // the first line, "LIGGGHTS (Version ...)"
};
LogSummary read_log(const std::string& path);

}  // namespace chutelab::dem::liggghts
