// estimate() and sweep(): the analytical chain of `chutelab estimate`, its values, each model's
// reading, the streamlines and their flights as numbers, and the sweep's rows.
#include <algorithm>
#include <fmt/format.h>

#include "api/estimate.h"
#include "api/files.h"
#include "api/sweep.h"
#include "core/message.h"
#include "python/bind_common.h"

namespace chutelab::bindings {
namespace {

// estimate(): the library's result, kept for its views.
struct Estimated {
  api::EstimateResult result;
};

py::dict estimate_values(const Estimated& e) {
  py::dict r;
  for (const auto& [n, v] : api::estimate_scalars(e.result.analysis)) r[py::str(n)] = v;
  return r;
}

py::dict estimate_models(const Estimated& e) {
  std::vector<std::string> model, quantity;
  std::vector<double> value;
  for (const auto& [m, vals] : e.result.models)
    for (Quantity q : kAllQuantities)
      if (vals[q]) {
        model.push_back(m), quantity.emplace_back(name(q));
        value.push_back(*vals[q] * info(q).to_boundary);
      }
  Table t;
  t.text("model", model), t.text("quantity", quantity), t.real("value", value);
  return t.dict();
}

// The streamlines as drawn (the same points as estimate's JSON, CSV and DXF), mm.
py::dict estimate_paths(const Estimated& e) {
  py::dict r;
  for (api::Streamline s : api::kAllStreamlines) {
    const auto pts = e.result.path(s);
    py::array_t<double> a({static_cast<py::ssize_t>(pts.size()), py::ssize_t{2}});
    auto m = a.mutable_unchecked<2>();
    for (std::size_t k = 0; k < pts.size(); ++k) {
      m(static_cast<py::ssize_t>(k), 0) = pts[k].x() * 1e3;
      m(static_cast<py::ssize_t>(k), 1) = pts[k].y() * 1e3;
    }
    r[py::str(std::string(name(s)))] = a;
  }
  return r;
}

// Each streamline's flight from its release to the plate line (1 s when it never gets there) at
// `points` equal time steps: the model's own trajectory (closed form, or RK4 with a flight force).
py::dict estimate_flight(const Estimated& e, int points) {
  std::vector<std::string> line;
  std::vector<double> t, x, y, vx, vy;
  for (api::Streamline s : api::kAllStreamlines) {
    const auto& l = e.result.analysis.line(s);
    const double t_end = l.hit ? l.hit->point.t : 1.0;
    for (const auto& f : l.trajectory.sample(t_end, points - 1)) {
      line.emplace_back(name(s));
      t.push_back(f.t), x.push_back(f.position.x() * 1e3), y.push_back(f.position.y() * 1e3);
      vx.push_back(f.velocity.x()), vy.push_back(f.velocity.y());
    }
  }
  Table tb;
  tb.text("streamline", line), tb.real("t_s", t), tb.real("x_mm", x), tb.real("y_mm", y);
  tb.real("vx_mps", vx), tb.real("vy_mps", vy);
  return tb.dict();
}

struct Swept {
  api::SweepResult result;
};

// estimate's sweep: one row a value, the columns of its CSV as numbers (NaN where a point has no
// answer), the note as text.
py::dict sweep_rows(const Swept& w) {
  const api::SweepResult& res = w.result;
  std::vector<std::string> scalar_cols;
  std::vector<std::pair<std::string, Quantity>> model_cols;
  for (const auto& r : res.rows) {
    if (!r.point) continue;
    for (const auto& [n, v] : api::estimate_scalars(r.point->analysis))
      if (n != res.spec.column && std::find(scalar_cols.begin(), scalar_cols.end(), n) == scalar_cols.end())
        scalar_cols.push_back(n);
    for (const auto& [m, vals] : r.point->models)
      for (Quantity q : kAllQuantities)
        if (vals[q] && std::find(model_cols.begin(), model_cols.end(), std::pair{m, q}) == model_cols.end())
          model_cols.emplace_back(m, q);
  }
  std::vector<double> value;
  std::vector<std::vector<double>> scalars(scalar_cols.size()), models(model_cols.size());
  std::vector<std::string> note;
  for (const auto& r : res.rows) {
    value.push_back(r.value);
    note.push_back(said_text(r.note, python_mention));
    const std::vector<std::pair<std::string, double>> sc =
        r.point ? api::estimate_scalars(r.point->analysis) : std::vector<std::pair<std::string, double>>{};
    for (std::size_t c = 0; c < scalar_cols.size(); ++c) {
      double v = kNan;
      for (const auto& [n, x] : sc)
        if (n == scalar_cols[c]) v = x;
      scalars[c].push_back(v);
    }
    for (std::size_t c = 0; c < model_cols.size(); ++c) {
      double v = kNan;
      if (r.point)
        for (const auto& [m, vals] : r.point->models)
          if (m == model_cols[c].first && vals[model_cols[c].second])
            v = *vals[model_cols[c].second] * info(model_cols[c].second).to_boundary;
      models[c].push_back(v);
    }
  }
  Table t;
  t.real(res.spec.column, value);
  for (std::size_t c = 0; c < scalar_cols.size(); ++c) t.real(scalar_cols[c], scalars[c]);
  for (std::size_t c = 0; c < model_cols.size(); ++c)
    t.real(fmt::format("{}_{}", model_cols[c].first, name(model_cols[c].second)), models[c]);
  t.text("note", note);
  return t.dict();
}

}  // namespace

void bind_estimate(py::module_& m) {
  // The options as the library takes them, set by keyword from the Python layer: one field a line
  // here, no argument list to keep in step with it. SweepOptions is an EstimateOptions with the
  // swept input.
  py::class_<api::EstimateOptions>(m, "EstimateOptions")
      .def(py::init<>())
      .def_readwrite("dataset", &api::EstimateOptions::dataset)
      .def_readwrite("setup", &api::EstimateOptions::setup)
      .def_property(
          "dataset_read", [](const api::EstimateOptions& o) { return o.dataset_read; },
          [](api::EstimateOptions& o, const api::Dataset* d) { o.dataset_read = d; }, py::keep_alive<1, 2>())
      .def_readwrite("condition", &api::EstimateOptions::condition)
      .def_readwrite("default_dataset", &api::EstimateOptions::default_dataset)
      .def_readwrite("belt_speed", &api::EstimateOptions::belt_speed)
      .def_readwrite("mass_flow", &api::EstimateOptions::mass_flow)
      .def_readwrite("plate_distance", &api::EstimateOptions::plate_distance)
      .def_readwrite("plate_top", &api::EstimateOptions::plate_top)
      .def_readwrite("stream_thickness", &api::EstimateOptions::stream_thickness)
      .def_readwrite("pulley_diameter", &api::EstimateOptions::pulley_diameter)
      .def_readwrite("belt_width", &api::EstimateOptions::belt_width)
      .def_readwrite("bulk_density", &api::EstimateOptions::bulk_density)
      .def_readwrite("effects", &api::EstimateOptions::effects);
  py::class_<api::SweepOptions, api::EstimateOptions>(m, "SweepOptions")
      .def(py::init<>())
      .def_readwrite("sweep", &api::SweepOptions::sweep);

  py::class_<Estimated>(m, "Estimated")
      .def("json", [](const Estimated& e) { return e.result.json(); })
      .def("values", &estimate_values)
      .def("models", &estimate_models)
      .def("effects",
           [](const Estimated& e) {
             py::dict d;
             for (const auto& s : e.result.settings)
               if (s.value) d[py::str(s.info->name)] = *s.value;
             return d;
           })
      .def("paths", &estimate_paths)
      .def("flight", &estimate_flight, py::arg("points"));
  m.def(
      "estimate", [](const api::EstimateOptions& o) { return std::make_unique<Estimated>(Estimated{api::estimate(o)}); },
      py::arg("options"));

  py::class_<Swept>(m, "Swept")
      .def("rows", &sweep_rows)
      .def("column", [](const Swept& w) { return w.result.spec.column; })
      .def("table", [](const Swept& w) { return w.result.table(python_mention); })
      .def("csv", [](const Swept& w) { return w.result.csv(python_mention); })
      .def("json", [](const Swept& w) { return w.result.json(python_mention); })
      .def("svg", [](const Swept& w) { return w.result.svg(python_mention); });
  m.def(
      "sweep", [](const api::SweepOptions& o) { return std::make_unique<Swept>(Swept{api::sweep(o)}); },
      py::arg("options"));
}

}  // namespace chutelab::bindings
