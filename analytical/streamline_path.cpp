#include "analytical/streamline_path.h"

#include <cmath>

namespace chutelab::analytical {

std::vector<Eigen::Vector2d> streamline_path(const TransferAnalysis& a, Streamline which) {
  using Pt = Eigen::Vector2d;
  const StreamlineFlight& l = a.line(which);
  const double gamma = a.station.belt.incline;
  const double r = a.station.belt.belt_radius() + l.height_above_belt;
  std::vector<Pt> p = {r * Pt(-std::sin(gamma), std::cos(gamma))};
  // Round the pulley in 24 steps when the stream rides on it (low-speed discharge).
  const double theta = l.release.theta;
  if (theta > -gamma + 1e-9)
    for (int k = 1; k <= 24; ++k) {
      const double phi = -gamma + (theta + gamma) * k / 24.0;
      p.push_back(r * Pt(std::sin(phi), std::cos(phi)));
    }
  const double t_end = l.hit ? l.hit->point.t : 1.0;
  for (const auto& f : l.trajectory.sample(t_end, 64)) p.push_back(f.position);
  return p;
}

}  // namespace chutelab::analytical
