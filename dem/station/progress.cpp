#include "dem/station/progress.h"

#include "core/message.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <fmt/format.h>

namespace chutelab::dem::station {
namespace {

std::string clock(double s) {
  const long t = std::lround(std::max(0.0, s));
  return fmt::format("{}:{:02d}", t / 60, t % 60);
}

}  // namespace

// The label holds names from the data (a condition): shown through the one formatter, so a name
// with a line end or a terminal escape cannot rewrite the terminal.
ProgressPrinter::ProgressPrinter(std::string label) : label_(one_line(label, 120)), tty_(isatty(2) != 0) {}

void ProgressPrinter::operator()(const Progress& p) {
  const double f = std::clamp(p.max_time > 0 ? p.time / p.max_time : 1.0, 0.0, 1.0);
  if (tty_) {
    const int width = 30;
    const int fill = p.done ? width : static_cast<int>(f * width);
    const std::string bar = std::string(static_cast<std::size_t>(fill), '#') + std::string(static_cast<std::size_t>(width - fill), '.');
    const std::string tail = p.done ? fmt::format("done in {}", clock(p.wall))
                                    : fmt::format("eta <= {}", clock(f > 0 ? p.wall / f * (1 - f) : 0));
    std::fprintf(stderr, "\r%s [%s] %3.0f%%  t = %.2f s  %zu particles  %s   ", label_.c_str(), bar.c_str(),
                 p.done ? 100.0 : 100.0 * f, p.time, p.particles, tail.c_str());
    if (p.done) std::fprintf(stderr, "\n");
    std::fflush(stderr);
    return;
  }
  const int quarter = static_cast<int>(std::floor(f * 4.0));
  if (p.done) {
    std::fprintf(stderr, "%s: done, %.2f s simulated in %s\n", label_.c_str(), p.time, clock(p.wall).c_str());
  } else if (quarter > last_quarter_ && quarter > 0) {
    std::fprintf(stderr, "%s: %d%% (t = %.2f s, %zu particles, %s)\n", label_.c_str(), 25 * quarter, p.time,
                 p.particles, clock(p.wall).c_str());
  }
  last_quarter_ = std::max(last_quarter_, quarter);
}

}  // namespace chutelab::dem::station
