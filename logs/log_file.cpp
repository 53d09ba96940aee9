#include "logs/log_file.h"

#include <cmath>
#include <fmt/format.h>

#include "core/input_error.h"
#include "validation/csv_table.h"

namespace chutelab::logs {

Log read_log(const std::filesystem::path& file, const Layout& layout) {
  const validation::CsvTable tab = validation::CsvTable::read(file);
  Log log;
  log.file = file;
  const std::size_t ct = tab.require(layout.time_column);
  std::vector<std::size_t> cols;
  for (const auto& c : layout.channels) cols.push_back(tab.require(c.column));
  if (tab.rows().size() < 8)
    throw InputError(tab.file(), 0, "", fmt::format("{} samples: a log needs at least 8", tab.rows().size()));
  log.raw.assign(cols.size(), {});
  for (auto& r : log.raw) r.reserve(tab.rows().size());
  log.t.reserve(tab.rows().size());
  for (const auto& row : tab.rows()) {
    log.t.push_back(tab.number(row, ct));
    for (std::size_t i = 0; i < cols.size(); ++i) log.raw[i].push_back(tab.number(row, cols[i]));
  }
  const double dt = (log.t.back() - log.t.front()) / static_cast<double>(log.t.size() - 1);
  if (!(dt > 0.0))
    throw InputError(tab.file(), tab.rows().back().line, layout.time_column, "time does not advance");
  for (std::size_t k = 1; k < log.t.size(); ++k) {
    const double step = log.t[k] - log.t[k - 1];
    if (std::abs(step - dt) > kMaxJitter * dt)
      throw InputError(tab.file(), tab.rows()[k].line, layout.time_column,
                       fmt::format("time steps by {:g} s here, the log's interval is {:g} s: the samples must be "
                                   "equally spaced (a gap is a lost stretch of the log)",
                                   step, dt));
  }
  log.dt = dt;
  return log;
}

}  // namespace chutelab::logs
