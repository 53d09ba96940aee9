#pragma once
// One condition's log: time and one column a channel of the layout (layout.h), read strictly: every
// problem is one InputError naming the file, line and column.
#include <filesystem>
#include <vector>

#include "logs/layout.h"

namespace chutelab::logs {

struct Log {
  std::filesystem::path file;
  std::vector<double> t;                  // s, equally spaced
  std::vector<std::vector<double>> raw;   // per layout channel, in the channel's unit
  double dt = 0.0;                        // s
};

// The sampling may jitter by at most this fraction of its interval; a longer gap is a lost stretch
// of the log, which would bias every mean across it.
inline constexpr double kMaxJitter = 0.05;

Log read_log(const std::filesystem::path& file, const Layout& layout);

}  // namespace chutelab::logs
