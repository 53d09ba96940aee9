#include "dem/station/progress.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "core/message.h"
#include "core/progress.h"

namespace chutelab::dem::station {
namespace {

std::string clock(double s) {
  const long t = std::lround(std::max(0.0, s));
  return fmt::format("{}:{:02d}", t / 60, t % 60);
}

}  // namespace

// The label holds names from the data (a condition): shown through the one formatter, so a name
// with a line end or a terminal escape cannot rewrite the terminal.
ProgressPrinter::ProgressPrinter(std::string label) : label_(one_line(label, 120)) {}

void ProgressPrinter::operator()(const Progress& p) {
  const double f = std::clamp(p.max_time > 0 ? p.time / p.max_time : 1.0, 0.0, 1.0);
  if (!p.done) {
    const int width = 20;
    const int fill = static_cast<int>(f * width);
    progress::status(fmt::format("{} [{}{}] {:3.0f}%  eta <= {}", label_, std::string(static_cast<std::size_t>(fill), '#'),
                                 std::string(static_cast<std::size_t>(width - fill), '.'), 100.0 * f,
                                 clock(f > 0 ? p.wall / f * (1 - f) : 0)));
    return;
  }
  progress::status("");
  // Inside a campaign the campaign prints the run's line (core/campaign.h).
  if (!progress::in_campaign_job())
    progress::line(fmt::format("{}: done, {:.2f} s simulated in {} ({} particles)", label_, p.time, clock(p.wall),
                               p.particles));
}

}  // namespace chutelab::dem::station
