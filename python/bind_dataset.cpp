// The dataset as the Python layer holds it (its tables as numbers, its files as texts), the CSV
// cells of a table edited in Python, and the commands that make a dataset folder: synthesize,
// import-logs, synthesize-logs.
#include <fmt/format.h>

#include "api/files.h"
#include "api/import_logs.h"
#include "api/synthesize.h"
#include "api/synthesize_logs.h"
#include "core/csv_field.h"
#include "core/input_error.h"
#include "core/output_folder.h"
#include "core/rig.h"
#include "core/units.h"
#include "python/bind_common.h"

namespace chutelab::bindings {
namespace {

py::dict conditions_table(const api::Dataset& d) {
  std::vector<std::string> condition;
  std::vector<double> speed, flow, distance, top, thickness, angle, incline;
  for (const auto& s : d.stations) {
    condition.push_back(s.condition);
    speed.push_back(as_written(s.belt_speed)), flow.push_back(as_written(s.mass_flow / units::tph));
    distance.push_back(as_written(s.plate_distance / units::mm)), top.push_back(as_written(s.plate_top / units::mm));
    thickness.push_back(written_or_nan(s.stream_thickness, 1.0 / units::mm));
    angle.push_back(as_written(s.plate.angle * units::deg_per_rad)), incline.push_back(as_written(s.belt.incline * units::deg_per_rad));
  }
  Table t;
  t.text("condition", condition), t.real("belt_speed_mps", speed), t.real("mass_flow_tph", flow);
  t.real("plate_distance_mm", distance), t.real("plate_top_mm", top), t.real("stream_thickness_mm", thickness);
  t.real("plate_angle_deg", angle), t.real("belt_incline_deg", incline);
  return t.dict();
}

py::dict measurements_table(const api::Dataset& d) {
  std::vector<std::string> condition, quantity;
  std::vector<double> value, uncertainty;
  for (const auto& m : d.measurements) {
    const double s = info(m.quantity).to_boundary;
    condition.push_back(m.condition), quantity.emplace_back(name(m.quantity));
    value.push_back(as_written(m.value * s)), uncertainty.push_back(written_or_nan(m.uncertainty, s));
  }
  Table t;
  t.text("condition", condition), t.text("quantity", quantity), t.real("value", value);
  t.real("uncertainty", uncertainty);
  return t.dict();
}

py::dict trajectory_table(const api::Dataset& d) {
  std::vector<std::string> condition, boundary;
  std::vector<double> x, y, u;
  for (const auto& p : d.trajectory) {
    condition.push_back(p.condition), boundary.emplace_back(name(p.boundary));
    x.push_back(as_written(p.x / units::mm)), y.push_back(as_written(p.y / units::mm));
    u.push_back(written_or_nan(p.uncertainty, 1.0 / units::mm));
  }
  Table t;
  t.text("condition", condition), t.text("boundary", boundary), t.real("x_mm", x), t.real("y_mm", y);
  t.real("uncertainty_mm", u);
  return t.dict();
}

// setup.toml as "section.key" -> value in the file's units (the rig-field table says which).
py::dict setup_dict(const Setup& setup) {
  py::dict d;
  d["name"] = setup.name;
  d["source"] = setup.source;
  Setup copy = setup;
  for (const auto& f : rig_fields()) {
    const std::string key = f.section.empty() ? std::string(f.key) : fmt::format("{}.{}", f.section, f.key);
    d[py::str(key)] = as_written(f.ref(copy) / f.to_si);
  }
  return d;
}

// The synthetic dataset: written to `out` and read back from there, or without `out` made in memory
// from its files (it has no folder).
api::Dataset synthesize(const api::Dataset& source, const std::vector<std::string>& effect_args,
                        const py::object& seed_arg, double noise_scale, const std::filesystem::path& out) {
  api::SynthesizeOptions o;
  o.seed = seed_value(seed_arg);
  o.noise_scale = noise_scale;
  o.effects = effect_args;
  api::check(o);
  // The same refusal as the command line's before any work: out may not be the source.
  if (!out.empty())
    o.prepare_output = [&](const api::OutputPlan& plan) -> std::filesystem::path {
      OutputFolder check(out, plan.inputs, "synthesize");
      return {};
    };
  const api::SynthesizeResult r = interruptible([&] { return api::synthesize(source, o); });
  py::gil_scoped_release free;
  return api::synthesized_dataset(r, out);
}

// A dataset's files as Python keeps them: {name: (shown, text, unread)}.
py::dict dataset_sources(const api::Dataset& d) {
  py::dict out;
  if (d.sources)
    for (const auto& [name, f] : *d.sources) out[py::str(name)] = py::make_tuple(f.shown, py::bytes(f.text), f.unread);
  return out;
}

api::Dataset dataset_from_sources(const py::dict& files, const std::string& dir, bool measurements_required) {
  api::DatasetTexts texts;
  for (const auto& [name, entry] : files) {
    const auto t = entry.cast<py::tuple>();
    texts[name.cast<std::string>()] = {t[0].cast<std::string>(), t[1].cast<std::string>(), t[2].cast<bool>()};
  }
  py::gil_scoped_release free;
  return api::read_dataset(texts, dir, measurements_required);
}

// A CSV text's header and rows of cells, as chutelab's reader splits them (quotes, the writer's
// apostrophe before a formula character, trimmed edges).
py::tuple csv_cells(const std::string& text, const std::string& file) {
  const api::CsvCells t = api::csv_cells(text, file);
  py::list rows;
  for (const auto& r : t.rows) rows.append(py::cast(r));
  return py::make_tuple(py::cast(t.header), rows);
}

// A CSV text from a header and rows of cells: a str as a text cell, a number as the shortest
// decimal that reads back as the same double (NaN or None: an empty cell), as chutelab writes CSV.
std::string csv_text(const std::vector<std::string>& header, const py::list& rows) {
  auto line = [](const auto& cells, auto cell) {
    std::string o;
    bool first = true;
    for (const auto& c : cells) {
      if (!first) o += ',';
      first = false;
      o += cell(c);
    }
    return o + "\n";
  };
  std::string out = line(header, [](const std::string& h) { return csv_field(h); });
  for (const auto& row : rows)
    out += line(row.cast<py::list>(), [](const py::handle& c) -> std::string {
      if (c.is_none()) return {};
      if (py::isinstance<py::str>(c)) return csv_field(c.cast<std::string>());
      if (py::isinstance<py::bool_>(c)) return c.cast<bool>() ? "1" : "0";
      return csv_number(c.cast<double>());
    });
  return out;
}

void import_logs(const std::filesystem::path& dataset, const std::filesystem::path& out) {
  api::ImportLogsOptions o;
  o.dataset = dataset;
  api::check(o);
  if (out.empty()) throw InputError("", 0, "out", "is empty; give a folder");
  o.prepare_output = [&](const api::OutputPlan& plan) -> std::filesystem::path {
    OutputFolder check(out, plan.inputs, "import-logs");
    return {};
  };
  py::gil_scoped_release free;
  const api::ImportLogsResult r = api::import_logs(o);
  api::write_dataset(out, r.files(), r.dataset.dir, "import-logs");
}

void synthesize_logs(const std::filesystem::path& dataset, const std::filesystem::path& truth,
                     const std::filesystem::path& sensor, const std::filesystem::path& dem_series,
                     const py::object& seed_arg, const std::filesystem::path& out) {
  api::SynthesizeLogsOptions o;
  o.seed = seed_value(seed_arg);
  o.dataset = dataset;
  o.truth = truth;
  o.sensor = sensor;
  o.dem_series = dem_series;
  api::check(o);
  if (out.empty()) throw InputError("", 0, "out", "is empty; give a folder");
  o.prepare_output = [&](const api::OutputPlan& plan) -> std::filesystem::path {
    OutputFolder check(out, plan.inputs, "synthesize-logs");
    return {};
  };
  py::gil_scoped_release free;
  const api::SynthesizeLogsResult r = api::synthesize_logs(o);
  api::write_dataset(out, r.files, r.source.dir, "synthesize-logs");
}

}  // namespace

void bind_dataset(py::module_& m) {
  py::class_<api::Dataset>(m, "Dataset")
      .def_property_readonly("dir", [](const api::Dataset& d) { return d.dir.string(); })
      .def_property_readonly("name", [](const api::Dataset& d) { return d.setup.name; })
      .def_property_readonly("setup", [](const api::Dataset& d) { return setup_dict(d.setup); })
      .def("sources", &dataset_sources)
      .def("conditions", &conditions_table)
      .def("measurements", &measurements_table)
      .def("trajectory", &trajectory_table);
  m.def(
      "read_dataset",
      [](const std::filesystem::path& dir, bool measurements_required) {
        // A dataset of logs reads its logs into means (logs/dataset_logs.h).
        return api::read_dataset(dir, measurements_required);
      },
      py::arg("dir"), py::arg("measurements_required"));
  m.def("dataset_from_sources", &dataset_from_sources, py::arg("files"), py::arg("dir"),
        py::arg("measurements_required"));
  m.def("csv_cells", &csv_cells, py::arg("text"), py::arg("file"));
  m.def("csv_text", &csv_text, py::arg("header"), py::arg("rows"));

  m.def("synthesize", &synthesize, py::arg("source"), py::arg("effects"), py::arg("seed"),
        py::arg("noise_scale"), py::arg("out"));
  m.def("import_logs", &import_logs, py::arg("dataset"), py::arg("out"));
  m.def("synthesize_logs", &synthesize_logs, py::arg("dataset"), py::arg("truth"), py::arg("sensor"),
        py::arg("dem_series"), py::arg("seed"), py::arg("out"));
}

}  // namespace chutelab::bindings
