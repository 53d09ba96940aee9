// calibrate() and sensitivity(): the DEM studies of the reference paper (Table 3, Table 6), their
// rows as numbers and their verdicts as text.
#include "api/calibrate.h"
#include "api/sensitivity.h"
#include "python/bind_common.h"

namespace chutelab::bindings {
namespace {

// calibrate(): the library's result and what it read (the folder written to may not be among them).
using Calibrated = Kept<api::CalibrateResult>;

// Table 3 a row (calibration.csv's columns, the doubles themselves) and the incline's onsets.
py::dict calibrated_numbers(const Calibrated& c) {
  const api::CalibrationStudy& s = c.result.study;
  std::vector<std::string> shape, grain;
  std::vector<double> rolling, density, bulk, pile, repose, distance, seconds;
  std::vector<long long> particles;
  std::vector<bool> settled, closest;
  for (std::size_t k = 0; k < s.rows.size(); ++k) {
    const auto& r = s.rows[k];
    shape.emplace_back(name(r.shape)), grain.push_back(api::grain_label(s, r.shape));
    rolling.push_back(r.rolling_friction), density.push_back(r.solid_density);
    bulk.push_back(r.slump.bulk_density), pile.push_back(r.slump.pile_height * 1e3);
    repose.push_back(r.slump.repose_angle_deg), distance.push_back(r.distance), seconds.push_back(r.slump.wall_seconds);
    particles.push_back(static_cast<long long>(r.slump.particles)), settled.push_back(r.slump.settled);
    closest.push_back(static_cast<int>(k) == s.closest);
  }
  Table rows;
  rows.text("shape", shape), rows.text("grain", grain), rows.real("rolling_friction", rolling);
  rows.real("solid_density_kgm3", density), rows.real("bulk_density_kgm3", bulk), rows.real("pile_height_mm", pile);
  rows.real("repose_angle_deg", repose), rows.whole("particles", particles), rows.flag("settled", settled);
  rows.real("run_seconds", seconds), rows.real("target_distance", distance), rows.flag("closest", closest);
  std::vector<double> i_rolling, wall, onset, eq10;
  std::vector<std::string> motion, eq10_motion;
  for (const auto& r : s.incline) {
    i_rolling.push_back(r.rolling_friction), wall.push_back(r.wall_friction);
    onset.push_back(r.result.onset_deg), eq10.push_back(r.result.predicted.onset_deg);
    motion.emplace_back(name(r.result.motion)), eq10_motion.emplace_back(name(r.result.predicted.motion));
  }
  Table incline;
  incline.real("rolling_friction", i_rolling), incline.real("wall_friction", wall), incline.real("onset_deg", onset);
  incline.text("motion", motion), incline.real("eq10_onset_deg", eq10), incline.text("eq10_motion", eq10_motion);
  py::dict r;
  r["rows"] = rows.dict();
  r["incline"] = incline.dict();
  r["closest"] = s.closest >= 0 ? py::cast(s.closest) : py::none();
  r["findings"] = api::calibration_findings(s);
  r["table3"] = c.result.table3();
  for (const auto& [name, text] : c.result.files())
    if (name == "material.toml") r["material_toml"] = text;
  return r;
}

// sensitivity(): the library's result and what it read.
using Sensitized = Kept<api::SensitivityResult>;

// Table 6 a row (sensitivity.csv's numbers, SI at the boundary: N, %, s, mm) and the verdict.
py::dict sensitivity_numbers(const Sensitized& s) {
  const api::SensitivityStudy& st = s.result.study;
  std::vector<std::string> key, label, group;
  std::vector<double> d, rn, rn_se, rs, rs_se, r, r_se, sd_r, change, change_se, dt, seconds;
  std::vector<long long> particles;
  std::vector<bool> steady;
  for (const auto& row : st.rows) {
    const auto& o = row.outcome;
    key.push_back(row.variant.key), label.push_back(row.variant.label), group.emplace_back(name(row.variant.group));
    d.push_back(o.diameter * 1e3), rn.push_back(o.normal.value), rn_se.push_back(o.normal.se);
    rs.push_back(o.shear.value), rs_se.push_back(o.shear.se), r.push_back(o.resultant.value), r_se.push_back(o.resultant.se);
    sd_r.push_back(o.fluct_resultant), change.push_back(row.change.value), change_se.push_back(row.change.se);
    dt.push_back(o.dt), seconds.push_back(o.wall_seconds), particles.push_back(static_cast<long long>(o.particles));
    steady.push_back(o.steady);
  }
  Table t;
  t.text("variant", key), t.text("label", label), t.text("group", group), t.real(api::variant_columns().diameter, d);
  t.real("normal_force_N", rn), t.real("normal_force_se_N", rn_se), t.real("shear_force_N", rs);
  t.real("shear_force_se_N", rs_se), t.real("resultant_force_N", r), t.real("resultant_force_se_N", r_se);
  t.real("resultant_force_sd_N", sd_r), t.real("change_percent", change), t.real("change_se_percent", change_se);
  t.real("dt_s", dt), t.whole("particles", particles), t.flag("steady", steady), t.real("run_seconds", seconds);
  py::dict out;
  out["rows"] = t.dict();
  out["verdict"] = st.verdict.text;
  out["reproduced"] = st.verdict.reproduced();
  out["complete"] = st.verdict.complete();
  out["notes"] = api::run_notes(st);
  return out;
}

}  // namespace

void bind_studies(py::module_& m) {
  // The options as the library takes them, set by keyword from the Python layer; the seed checked
  // as the command line's --seed.
  py::class_<api::CalibrateOptions>(m, "CalibrateOptions")
      .def(py::init<>())
      .def_readwrite("dataset", &api::CalibrateOptions::dataset)
      .def_readwrite("quality", &api::CalibrateOptions::quality)
      .def_readwrite("rolling", &api::CalibrateOptions::rolling)
      .def_readwrite("density", &api::CalibrateOptions::density)
      .def_readwrite("shapes", &api::CalibrateOptions::shapes)
      .def_readwrite("sphere_diameter_mm", &api::CalibrateOptions::sphere_diameter_mm)
      .def_readwrite("clump_diameter_mm", &api::CalibrateOptions::clump_diameter_mm)
      .def_readwrite("target", &api::CalibrateOptions::target)
      .def_readwrite("target_bulk_density", &api::CalibrateOptions::target_bulk_density)
      .def_readwrite("target_pile_height_mm", &api::CalibrateOptions::target_pile_height_mm)
      .def_readwrite("incline", &api::CalibrateOptions::incline)
      .def_readwrite("threads", &api::CalibrateOptions::threads)
      .def_property(
          "seed", [](const api::CalibrateOptions& o) { return o.seed; },
          [](api::CalibrateOptions& o, const py::object& seed) { o.seed = seed_value(seed); })
      .def_readwrite("jobs", &api::CalibrateOptions::jobs);
  kept_class<api::CalibrateResult>(m, "Calibrated", "calibrate").def("numbers", &calibrated_numbers);
  m.def(
      "calibrate",
      [](api::CalibrateOptions o) {
        return run_kept<api::CalibrateResult>(o, [](const api::CalibrateOptions& opt) { return api::calibrate(opt); });
      },
      py::arg("options"));

  py::class_<api::SensitivityOptions>(m, "SensitivityOptions")
      .def(py::init<>())
      .def_readwrite("dataset", &api::SensitivityOptions::dataset)
      .def_readwrite("condition", &api::SensitivityOptions::condition)
      .def_readwrite("quality", &api::SensitivityOptions::quality)
      .def_readwrite("only", &api::SensitivityOptions::only)
      .def_readwrite("sizes_mm", &api::SensitivityOptions::sizes_mm)
      .def_readwrite("threads", &api::SensitivityOptions::threads)
      .def_property(
          "seed", [](const api::SensitivityOptions& o) { return o.seed; },
          [](api::SensitivityOptions& o, const py::object& seed) {
            if (seed.is_none())
              o.seed.reset();
            else
              o.seed = seed_value(seed);
          })
      .def_readwrite("limit", &api::SensitivityOptions::limit)
      .def_readwrite("jobs", &api::SensitivityOptions::jobs);
  kept_class<api::SensitivityResult>(m, "Sensitized", "sensitivity").def("numbers", &sensitivity_numbers);
  m.def(
      "sensitivity",
      [](api::SensitivityOptions o) {
        return run_kept<api::SensitivityResult>(o, [](const api::SensitivityOptions& opt) { return api::sensitivity(opt); });
      },
      py::arg("options"));
}

}  // namespace chutelab::bindings
