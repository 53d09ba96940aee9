#pragma once
// A particle time series ParaView opens as one: a .pvd collection (VTK XML) listing one VTK XML
// PolyData file (.vtp) per frame with its simulated time (s). Each .vtp carries the particles as
// vertices in mm, as every other chutelab file (the engine is SI inside), with their id, clump,
// radius_mm, velocity_mps, speed_mps and contact_force_N (a comment in each file says so); its arrays are
// raw binary in an appended block (little-endian, UInt64 block headers), so a frame costs what its
// numbers weigh and reads back exactly. The .pvd is rewritten after every frame, so a run stopped
// early still leaves a series that opens.
#include <cstddef>
#include <string>
#include <vector>

#include "dem/world.h"

namespace chutelab::dem {

class VtkSeries {
 public:
  // Files go to `dir` (created): NAME.pvd and NAME_00000.vtp, NAME_00001.vtp, ...
  VtkSeries(std::string dir, std::string name);
  // One frame at simulated time t; contact_force[i] is particle i's contact-force magnitude, N.
  void write(double t, const Particles& p, const std::vector<double>& contact_force);
  std::size_t frames() const { return times_.size(); }
  double last_time() const { return times_.empty() ? -1.0 : times_.back(); }

 private:
  std::string dir_, name_;
  std::vector<double> times_;
  std::vector<std::string> files_;
};

// One frame's .vtp on its own (what VtkSeries writes per frame).
void write_vtp_particles(const std::string& path, const Particles& p, const std::vector<double>& contact_force);

}  // namespace chutelab::dem
