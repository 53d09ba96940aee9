#include "python/bind_common.h"

#include <cmath>
#include <fmt/format.h>

#include "api/effect_library.h"
#include "api/files.h"
#include "core/input_error.h"

namespace chutelab::bindings {

namespace {
// Whether `key` is a [dem] setting validate and diagnose take here as a keyword: only the quality.
bool dem_keyword(std::string_view key) { return key == api::key(api::DemSetting::quality); }
}  // namespace

std::string python_keyword(std::string_view key) {
  static const std::pair<std::string_view, std::string_view> renamed[] = {
      {"effect", "effects"}, {"input", "inputs"}, {"dem.threads", "dem_threads"},
      {"dem.cache", "dem_cache"}, {"dem.no_cache", "no_dem_cache"}, {"shape", "shapes"}, {"sizes", "sizes_mm"},
      {"sphere_diameter", "sphere_diameter_mm"}, {"clump_diameter", "clump_diameter_mm"},
      {"target_pile_height", "target_pile_height_mm"}};
  for (const auto& [k, word] : renamed)
    if (k == key) return std::string(word);
  // The [dem] settings validate and diagnose take (api/dem_options.h): "dem.quality" is dem_quality.
  if (dem_keyword(key)) return "dem_" + std::string(key.substr(4));
  return std::string(key);
}

std::string python_mention(std::string_view key) {
  static const std::string_view keywords[] = {"dataset", "setup", "condition", "effect", "models", "tolerances",
                                              "seed", "noise_scale", "out", "alpha", "dem.threads",
                                              "dem.cache", "dem.no_cache", "self_check", "belt_speed", "mass_flow",
                                              "plate_distance", "plate_top", "stream_thickness", "pulley_diameter",
                                              "belt_width", "bulk_density", "diagnose", "input",
                                              "accept_with_effects", "sweep", "rolling", "density", "shape",
                                              "quality", "only", "sizes", "limit", "threads", "jobs", "sphere_diameter",
                                              "clump_diameter", "target_bulk_density", "target_pile_height"};
  for (const auto k : keywords)
    if (k == key) return python_keyword(key) + "=";
  if (dem_keyword(key)) return python_keyword(key) + "=";
  return std::string(key);
}

double whole_number(const py::object& v, const options::NumberRule& rule) {
  if (py::isinstance<py::bool_>(v) || !(py::isinstance<py::int_>(v) || py::isinstance<py::float_>(v) ||
                                         py::hasattr(v, "__index__")))
    throw InputError("", 0, std::string(rule.key),
                     fmt::format("must be {}, got {}", rule.describe(), std::string(py::str(py::repr(v)))));
  if (py::isinstance<py::float_>(v)) return rule.check(v.cast<double>());
  // An int of any size, checked exactly by its digits (as the command line checks what is typed), so a
  // huge one is refused, not wrapped.
  const py::int_ i = py::reinterpret_steal<py::int_>(PyNumber_Index(v.ptr()));
  if (!i) throw py::error_already_set();
  return rule.check(std::string(py::repr(i)));
}

std::uint64_t seed_value(const py::object& seed_arg) {
  const double checked = whole_number(seed_arg, options::rules::seed);
  return py::isinstance<py::float_>(seed_arg)
             ? static_cast<std::uint64_t>(checked)
             : py::reinterpret_steal<py::int_>(PyNumber_Index(seed_arg.ptr())).cast<std::uint64_t>();
}

std::optional<py::error_already_set>& pending_signal() {
  static std::optional<py::error_already_set> e;
  return e;
}

bool python_signalled() {
  py::gil_scoped_acquire gil;
  if (PyErr_CheckSignals() == 0) return false;
  pending_signal().emplace();  // takes (and clears) the handler's exception
  return true;
}

api::DemOptions dem_options(const std::string& quality, std::optional<int> threads, const std::string& cache,
                            bool no_cache) {
  api::DemOptions d;
  d.quality = quality;
  d.threads = threads;
  d.cache = cache;
  d.no_cache = no_cache;
  return d;
}

double as_written(double v) { return std::isfinite(v) ? std::stod(fmt::format("{:.15g}", v)) : v; }

py::dict strength(const std::string& effect, const std::string& parameter, double value,
                  std::optional<double> sd, bool fitted) {
  py::dict d;
  d["effect"] = effect, d["parameter"] = parameter, d["value"] = value;
  d["sd"] = sd ? py::object(py::float_(*sd)) : py::object(py::none());
  std::string unit;
  for (const auto& e : api::effect_library())
    if (e.name == effect) unit = e.unit;
  d["unit"] = unit;
  d["fitted"] = fitted;
  return d;
}

void write_files(const std::vector<api::OutputFile>& files, const std::vector<std::filesystem::path>& inputs,
                 const std::filesystem::path& out, const char* command) {
  if (out.empty()) throw InputError("", 0, "out", "is empty; give a folder");
  py::gil_scoped_release free;
  api::write_files(out, files, inputs, command);
}

}  // namespace chutelab::bindings
