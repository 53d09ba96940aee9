// _chutelab: the compiled half of the Python package. It binds the library's functions (api/:
// estimate, validate, diagnose, synthesize, calibrate, sensitivity), the ones the command line
// calls, keeps their result structs, and hands their doubles to Python as NumPy arrays (no text in
// between), with the columns of the files the command line writes; chutelab/__init__.py makes
// DataFrames and typed values of them. No physics here, and nothing of the command line's (app/ is
// not included); only api/ and core/ headers, as for the command line. One file an area
// (bind_*.cpp); this one holds what the whole module shares.
#include <string>

#include "api/effect_library.h"
#include "api/validate.h"
#include "core/input_error.h"
#include "core/message.h"
#include "core/progress.h"
#include "core/quantity.h"
#include "python/bind_common.h"

namespace py = pybind11;
using namespace chutelab;
using namespace chutelab::bindings;

PYBIND11_MODULE(_chutelab, m) {
  m.doc() = "chutelab's C++ core (use the chutelab package, not this module)";
  // Progress lines name other inputs as they are typed here, as errors do (set once, before any thread).
  progress::set_mention_names(python_mention);

  // InputError(ValueError) carrying file, line (0 = none) and field, as the command line's
  // one-line message names them.
  static py::exception<InputError> input_error(m, "InputError", PyExc_ValueError);
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const InputError& e) {
      py::object err = py::reinterpret_borrow<py::object>(input_error)(py::str(e.said(python_keyword, python_mention)));
      err.attr("file") = e.file();
      err.attr("line") = e.line();
      err.attr("field") = one_line(python_keyword(e.field()));
      err.attr("problem") = one_line(e.problem_said(python_mention));
      PyErr_SetObject(input_error.ptr(), err.ptr());
    }
  });

  m.attr("source_datasets") = std::string(CHUTELAB_DATASETS_DIR);

  // The dataset first: the other areas take and return its class.
  bind_dataset(m);
  bind_estimate(m);
  bind_validate(m);
  bind_studies(m);

  // The quantity vocabulary (core/quantity.h) and the stream boundaries trajectory.csv compares, for
  // axis labels: name (as in the tables), symbol, label, unit.
  m.def("quantities", [] {
    py::list out;
    for (Quantity q : kAllQuantities) {
      const auto& i = info(q);
      out.append(py::make_tuple(std::string(i.name), std::string(i.symbol), std::string(i.label), std::string(i.unit)));
    }
    for (Boundary b : kAllBoundaries) {
      const std::string n(name(b));
      out.append(py::make_tuple(trajectory_quantity(b), "y_" + n, "height of the stream's " + n + " line at x", "mm"));
    }
    return out;
  });

  m.def("model_names", &api::model_names);
  m.def("effect_library", [] {
    py::list out;
    for (const auto& e : api::effect_library()) {
      py::dict d;
      d["effect"] = e.name;
      d["parameter"] = e.parameter;
      d["unit"] = e.unit;
      d["stage"] = e.stage;
      d["kind"] = e.record ? "record" : "physics";
      d["neutral"] = e.neutral;
      d["lower"] = e.lower;
      d["upper"] = e.upper;
      d["typical"] = e.typical;
      d["physics"] = e.physics;
      d["source"] = e.source;
      out.append(d);
    }
    return out;
  });
}
