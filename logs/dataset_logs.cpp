#include "logs/dataset_logs.h"

#include <fmt/format.h>
#include <map>

#include "core/input_error.h"
#include "core/message.h"

namespace chutelab::logs {

namespace fs = std::filesystem;

std::vector<std::string> LogImport::warnings() const {
  std::vector<std::string> out;
  for (const auto& c : conditions)
    for (const auto& w : c.warnings) out.push_back(fmt::format("{}: {}", c.file.filename().string(), w));
  return out;
}

bool has_logs(const fs::path& dir) {
  std::error_code ec;
  return fs::exists(fs::symlink_status(dir / "logs" / "layout.toml", ec));
}

LogImport import_logs(const validation::Dataset& d) {
  LogImport out;
  const fs::path folder = d.dir / "logs";
  out.layout = read_layout(folder / "layout.toml");
  for (const auto& st : d.stations) {
    const fs::path file = folder / (st.condition + ".csv");
    std::error_code ec;
    if (!fs::exists(fs::symlink_status(file, ec))) {
      const auto* where = d.station_line(st.condition);
      throw InputError(where ? where->file : (d.dir / "conditions.csv").string(), where ? where->line : 0,
                       "condition",
                       fmt::format("condition '{}' has no log: {} not found (every condition needs one when the "
                                   "dataset has logs/layout.toml)",
                                   st.condition, file.string()));
    }
    const Log log = read_log(file, out.layout);
    out.conditions.push_back(read_condition(log, out.layout, st.condition, st.belt_speed, st.mass_flow));
  }
  return out;
}

void add_measurements(validation::Dataset& d, const LogImport& logs) {
  std::map<std::pair<std::string, Quantity>, const validation::Measurement*> have;
  for (const auto& m : d.measurements) have[{m.condition, m.quantity}] = &m;
  std::vector<validation::Measurement> add;
  for (const auto& c : logs.conditions)
    for (const auto& q : c.quantities) {
      if (const auto it = have.find({c.condition, q.quantity}); it != have.end())
        throw InputError(it->second->where.file, it->second->where.line, "quantity",
                         fmt::format("{} of condition '{}' is also read from its log {}: give it once", name(q.quantity),
                                     c.condition, c.file.string()));
      validation::Measurement m;
      m.condition = c.condition;
      m.quantity = q.quantity;
      m.value = q.value;
      m.uncertainty = q.budget.u;
      m.where = {c.file.string(), 0};
      add.push_back(std::move(m));
    }
  d.measurements.insert(d.measurements.end(), add.begin(), add.end());
}

validation::Dataset read_dataset(const fs::path& dir, validation::MeasurementsRequired need,
                                 std::optional<LogImport>* logs) {
  if (!has_logs(dir)) {
    if (logs) logs->reset();
    return validation::read_dataset(dir, need);
  }
  validation::Dataset d = validation::read_dataset(dir, validation::MeasurementsRequired::no);
  LogImport li = import_logs(d);
  add_measurements(d, li);
  for (const auto& w : li.warnings()) warn(w);
  if (need == validation::MeasurementsRequired::yes && d.measurements.empty())
    throw InputError((dir / "logs" / "layout.toml").string(), 0, "", "the logs give no measurement");
  if (logs) *logs = std::move(li);
  return d;
}

}  // namespace chutelab::logs
