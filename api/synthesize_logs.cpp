#include "api/synthesize_logs.h"

#include <cmath>
#include <fmt/format.h>
#include <fstream>
#include <map>
#include <sstream>

#include "core/csv_field.h"
#include "core/input_error.h"
#include "core/utf8.h"
#include "logs/layout.h"
#include "validation/dataset_output.h"

namespace chutelab::api {
namespace {

std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return to_utf8(ss.str());
}

bool from_logs(Quantity q) {
  return q == Quantity::normal_force || q == Quantity::shear_force || q == Quantity::resultant_force ||
         q == Quantity::impact_point_y;
}

std::filesystem::path series_file(const std::filesystem::path& dir, const std::string& condition) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::path a = dir / condition / "timeseries.csv";
  if (fs::exists(fs::symlink_status(a, ec))) return a;
  const fs::path b = dir / (condition + ".csv");
  if (fs::exists(fs::symlink_status(b, ec))) return b;
  throw InputError(a.string(), 0, "dem_series",
                   fmt::format("no DEM series for condition '{}' (nor {})", condition, b.string()));
}

}  // namespace

void check(const SynthesizeLogsOptions& o) {
  if (o.dataset.empty()) throw InputError("", 0, "dataset", "give the dataset whose rig and conditions to log");
  if (o.truth.empty())
    throw InputError("", 0, "truth", "give the truth: a CSV of condition,quantity,value (a model's prediction)");
}

SynthesizeLogsResult synthesize_logs(const SynthesizeLogsOptions& o) {
  check(o);
  SynthesizeLogsResult r;
  r.source = validation::read_dataset(o.dataset, validation::MeasurementsRequired::no);
  const std::vector<validation::Measurement> truth = validation::read_measurements(o.truth, &r.source);
  if (!o.sensor.empty()) r.sensor = logs::read_sensor_model(o.sensor);
  std::vector<std::optional<logs::Fluctuation>> fluct(r.source.stations.size());
  if (!o.dem_series.empty())
    for (std::size_t i = 0; i < r.source.stations.size(); ++i)
      fluct[i] = logs::read_dem_series(series_file(o.dem_series, r.source.stations[i].condition));
  if (o.prepare_output) {
    OutputPlan plan;
    plan.inputs = validation::dataset_files(o.dataset);
    plan.inputs.push_back(o.truth);
    if (!o.sensor.empty()) plan.inputs.push_back(o.sensor);
    if (!o.dem_series.empty()) plan.inputs.push_back(o.dem_series);
    o.prepare_output(plan);
  }

  std::map<std::pair<std::string, Quantity>, const validation::Measurement*> by;
  for (const auto& m : truth) by[{m.condition, m.quantity}] = &m;
  // The cells sit at the plate's top and bottom edges.
  const validation::Dataset& d = r.source;
  std::vector<validation::OutputFile> logs_files;
  std::optional<logs::Layout> layout;
  for (std::size_t i = 0; i < d.stations.size(); ++i) {
    const Station& st = d.stations[i];
    auto need = [&](Quantity q) {
      const auto it = by.find({st.condition, q});
      if (it == by.end())
        throw InputError(o.truth.string(), 0, "quantity",
                         fmt::format("the truth has no {} for condition '{}': the virtual rig needs R_n, R_s and y_R",
                                     name(q), st.condition));
      return it->second->value;
    };
    logs::TrueCondition t;
    t.condition = st.condition;
    t.normal = need(Quantity::normal_force);
    t.shear = need(Quantity::shear_force);
    t.impact_y = need(Quantity::impact_point_y);
    t.belt_speed = st.belt_speed;
    t.mass_flow = st.mass_flow;
    const double y_upper = st.plate_top, y_lower = st.plate_top - st.plate.height * std::cos(st.plate.angle);
    if (!layout) layout = logs::virtual_layout(r.sensor, y_upper, y_lower);
    // The DEM's fluctuation about its own mean rides on the truth's mean.
    const logs::Fluctuation* f = fluct[i] ? &*fluct[i] : nullptr;
    logs_files.emplace_back("logs/" + st.condition + ".csv",
                            logs::virtual_log(t, r.sensor, *layout, o.seed + 7919 * i, f));
    r.truth.push_back(t);
  }
  if (d.stations.empty()) throw InputError((o.dataset / "conditions.csv").string(), 0, "", "no condition");

  std::ostringstream meas;
  meas << "condition,quantity,value,uncertainty\n";
  for (const auto& m : d.measurements) {
    if (from_logs(m.quantity)) continue;
    const double k = info(m.quantity).to_boundary;
    meas << csv_field(m.condition) << ',' << name(m.quantity) << ',' << csv_number(m.value * k) << ','
         << (m.uncertainty ? csv_number(*m.uncertainty * k) : std::string()) << '\n';
  }
  std::string readme = fmt::format(
      "# {} as logged by a virtual rig\n\n"
      "The plate's quantities of this dataset are logs, one logs/<condition>.csv a condition with their layout in "
      "logs/layout.toml: two normal load cells at the plate's top and bottom edges, one shear cell, a tachometer "
      "and a belt scale. They were written by `chutelab synthesize-logs` (seed {}) from the true means in {}, "
      "through a sensor model: sampled at {:g} Hz after a {:g} Hz low-pass, white noise of {:g} N, noise "
      "correlated over {:g} s of {:g} % of each cell's load, a logger step of {:g} N, calibration errors of {:g} % "
      "(stated in the layout), a zero drift of {:g} N and a creep of {:g} %/s, a start-up surge of {:g} %.{}\n\n"
      "The other quantities (measurements.csv) and the stream's limits are the source dataset's.\n",
      d.setup.name, o.seed, o.truth.filename().string(), r.sensor.rate_hz, r.sensor.lowpass_hz, r.sensor.white_N,
      r.sensor.corr_s, 100.0 * r.sensor.corr_fraction, r.sensor.resolution_N, 100.0 * r.sensor.gain_u,
      r.sensor.drift_N, 100.0 * r.sensor.creep_per_s, 100.0 * r.sensor.surge,
      o.dem_series.empty() ? "" : " The stream's own fluctuation is that of the DEM's plate loads, looped.");
  r.files = {{"setup.toml", slurp(d.dir / "setup.toml")},
             {"conditions.csv", slurp(d.dir / "conditions.csv")},
             {"measurements.csv", meas.str()},
             {"logs/layout.toml", logs::layout_toml(*layout)}};
  for (const char* f : {"trajectory.csv", "plate_map.csv"}) {
    std::error_code ec;
    if (std::filesystem::exists(std::filesystem::symlink_status(d.dir / f, ec))) r.files.emplace_back(f, slurp(d.dir / f));
  }
  for (auto& f : logs_files) r.files.push_back(std::move(f));
  r.files.emplace_back("README.md", readme);
  return r;
}

}  // namespace chutelab::api
