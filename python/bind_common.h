#pragma once
// What every binding file of _chutelab shares: the package's keywords for the library's neutral
// keys, Python numbers checked as the command line checks them, calls that hear Ctrl-C, the Table
// the Python layer makes DataFrames of, and the results that keep what their run read.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <cstdint>
#include <filesystem>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "api/dem_options.h"
#include "api/output_plan.h"
#include "core/interrupt.h"
#include "core/option_check.h"

namespace chutelab::bindings {
namespace py = pybind11;

// The library names an input by a neutral key ("dem.threads", core/input_error.h); here it is the
// keyword of the package's function (dem_threads). Keys that are no keyword here (a column, a TOML
// key, an option the package does not have) are shown as they are.
std::string python_keyword(std::string_view key);
// Inside a message another input is named as it is typed here: "use dataset=".
std::string python_mention(std::string_view key);

// A whole number from Python: an int (not a bool), or a float that is whole; checked by `rule`, the
// command line's (core/option_check.h). seed=1.5 is refused, not truncated to 1.
double whole_number(const py::object& v, const options::NumberRule& rule);
// A seed from Python, checked as the command line's --seed; a huge int exactly, not wrapped.
std::uint64_t seed_value(const py::object& seed_arg);

// Ctrl-C during a long call. The library asks this at its interruption points (core/interrupt.h),
// on the calling thread; Python's handler runs there (KeyboardInterrupt, or the user's own), and
// the exception it raises is kept until the call has unwound.
std::optional<py::error_already_set>& pending_signal();
bool python_signalled();

// `f` without the GIL, hearing Ctrl-C: an interrupted call raises the signal handler's exception.
template <class F>
auto interruptible(F&& f) -> decltype(f()) {
  const interrupt::Scope scope(python_signalled);
  try {
    py::gil_scoped_release free;
    return f();
  } catch (const interrupt::Interrupted&) {
    if (auto& e = pending_signal()) {
      py::error_already_set raised = std::move(*e);
      e.reset();
      throw raised;
    }
    PyErr_SetNone(PyExc_KeyboardInterrupt);
    throw py::error_already_set();
  }
}

api::DemOptions dem_options(const std::string& quality, std::optional<int> threads, const std::string& cache,
                            bool no_cache);

// A table for the Python layer: {column: values} in column order, numbers as NumPy arrays of the
// C++ doubles themselves (no text in between), flags as bool arrays, names as lists of str.
class Table {
 public:
  void text(const char* name, std::vector<std::string> v) { d_[name] = py::cast(std::move(v)); }
  void real(const std::string& name, const std::vector<double>& v) { d_[py::str(name)] = py::array_t<double>(v.size(), v.data()); }
  void real(const char* name, const std::vector<double>& v) { d_[name] = py::array_t<double>(v.size(), v.data()); }
  void whole(const char* name, const std::vector<long long>& v) {
    d_[name] = py::array_t<long long>(v.size(), v.data());
  }
  void flag(const char* name, const std::vector<bool>& v) {
    py::array_t<bool> a(v.size());
    auto m = a.mutable_unchecked<1>();
    for (std::size_t i = 0; i < v.size(); ++i) m(static_cast<py::ssize_t>(i)) = v[i];
    d_[name] = a;
  }
  py::dict dict() const { return d_; }

 private:
  py::dict d_;
};

constexpr double kNan = std::numeric_limits<double>::quiet_NaN();
inline double or_nan(const std::optional<double>& v, double scale = 1.0) { return v ? *v * scale : kNan; }

// A file's value went to SI and back; 15 significant digits drop the conversion's last-bit noise,
// so a table shows the number the file holds (41.9, not 41.900000000000006).
double as_written(double v);
inline double written_or_nan(const std::optional<double>& v, double scale) { return v ? as_written(*v * scale) : kNan; }

// A strength as the Python layer's Strength wants it.
py::dict strength(const std::string& effect, const std::string& parameter, double value,
                  std::optional<double> sd, bool fitted);

// A result that writes files (validate's, diagnose's, calibrate's, sensitivity's) with what its run
// read: write() never puts a file onto one of them.
template <class R>
struct Kept {
  R result;
  std::vector<std::filesystem::path> inputs;
};

// Runs `call(o)` without the GIL, hearing Ctrl-C, and keeps the inputs its plan names.
template <class R, class Options, class Call>
std::unique_ptr<Kept<R>> run_kept(Options& o, Call&& call) {
  std::vector<std::filesystem::path> inputs;
  o.prepare_output = [&](const api::OutputPlan& plan) -> std::filesystem::path {
    inputs = plan.inputs;
    return {};
  };
  return interruptible([&] { return std::make_unique<Kept<R>>(Kept<R>{call(o), std::move(inputs)}); });
}

// Writes a result's files into `out` as the command line's --out does: all or nothing, never onto
// a file the run read.
void write_files(const std::vector<api::OutputFile>& files, const std::vector<std::filesystem::path>& inputs,
                 const std::filesystem::path& out, const char* command);

// The Python class of a kept result, with its write(out) as `command`'s; numbers() is the caller's.
template <class R>
py::class_<Kept<R>> kept_class(py::module_& m, const char* name, const char* command) {
  py::class_<Kept<R>> c(m, name);
  c.def("write", [command](const Kept<R>& k, const std::filesystem::path& out) {
    write_files(k.result.files(), k.inputs, out, command);
  });
  return c;
}

// The module's parts, by area; PYBIND11_MODULE calls each once.
void bind_estimate(py::module_& m);
void bind_dataset(py::module_& m);
void bind_validate(py::module_& m);
void bind_studies(py::module_& m);

}  // namespace chutelab::bindings
