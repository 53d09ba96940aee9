#define BOOST_TEST_MODULE api
// The library's face (api/): each function checks its options before any work, names a bad one by
// its neutral key (never a flag or a keyword), writes nothing then, and gives the command line's
// numbers: the command line is an adapter over these same functions, so their outputs agree byte
// for byte.
#include <boost/test/unit_test.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <functional>
#include <limits>

#include "../cli/cli_runner.h"
#include "api/calibrate.h"
#include "api/diagnose.h"
#include "api/sensitivity.h"
#include "api/estimate.h"
#include "api/simulate.h"
#include "api/synthesize.h"
#include "api/validate.h"
#include "core/input_error.h"

using namespace chutelab;
namespace fs = std::filesystem;

namespace {

const fs::path kDatasets = fs::path(CHUTELAB_SOURCE_DIR) / "datasets";
const fs::path kRig = kDatasets / "grima2010";
const fs::path kHidden = kDatasets / "hidden-effect";

// Runs `call`, which must throw InputError with this field; returns the error.
InputError refused(const std::function<void()>& call, const std::string& key) {
  try {
    call();
  } catch (const InputError& e) {
    BOOST_TEST(e.field() == key, e.what());
    // The library's message names no command-line flag (the front ends render keys their way).
    BOOST_TEST(std::string(e.what()).find("--") == std::string::npos, e.what());
    return e;
  }
  BOOST_FAIL("no InputError for " + key);
  return InputError("", 0, "", "");
}

// A prepare_output hook that counts its calls and must not be reached.
struct Hook {
  int calls = 0;
  api::PrepareOutput fn() {
    return [this](const api::OutputPlan&) -> fs::path {
      ++calls;
      return {};
    };
  }
};

}  // namespace

BOOST_AUTO_TEST_CASE(validate_checks_its_options_before_any_work) {
  struct Case {
    std::function<void(api::ValidateOptions&)> set;
    std::string key;
  };
  const Case cases[] = {
      {[](auto& o) { o.models = {"korzen", ""}; }, "models"},
      {[](auto& o) { o.models = {}; }, "models"},
      {[](auto& o) { o.models = {"korzen", "korzen"}; }, "models"},
      {[](auto& o) { o.effects = {"air_dragg=1"}; }, "effect"},
      {[](auto& o) { o.effects = {"air_drag=x"}; }, "effect"},
      {[](auto& o) { o.inputs = {"air_drag=1"}; }, "input"},
      {[](auto& o) { o.jobs = -1; }, "jobs"},
      {[](auto& o) { o.dem.threads = 300; }, "dem.threads"},
      {[](auto& o) { o.dem.quality = "fast"; }, "dem.quality"},
      {[](auto& o) { o.dem.steady_on = "shear"; }, "dem.steady_on"},
      {[](auto& o) { o.dem.cache_only = o.dem.no_cache = true; }, "dem.cache_only"},
      // A missing dataset is found only after the options: they are checked first.
      {[](auto& o) { o.dataset = "/nonexistent"; o.dem.plate_cells = 401; }, "dem.plate_cells"},
  };
  for (const auto& c : cases) {
    Hook hook;
    api::ValidateOptions o;
    o.dataset = kHidden;
    o.prepare_output = hook.fn();
    c.set(o);
    refused([&] { api::check(o); }, c.key);
    refused([&] { api::validate(o); }, c.key);
    BOOST_TEST(hook.calls == 0);  // the library writes only where the hook says, and it was never asked
  }
}

BOOST_AUTO_TEST_CASE(a_mention_of_another_input_is_rendered_by_each_front_end) {
  api::ValidateOptions o;
  o.dem.cache_only = o.dem.no_cache = true;
  const InputError e = refused([&] { api::check(o); }, "dem.cache_only");
  BOOST_TEST(std::string(e.what()) == "dem.cache_only: contradicts dem.no_cache");
  const FieldNames cli = [](std::string_view k) { return "--" + std::string(k); };
  const FieldNames python = [](std::string_view k) { return std::string(k) + "="; };
  BOOST_TEST(e.said(cli, cli) == "--dem.cache_only: contradicts --dem.no_cache");
  BOOST_TEST(e.problem_said(python) == "contradicts dem.no_cache=");
  // Made again from its parts (a campaign job's exchange, a located error), it says the same.
  const InputError again = InputError(e.file(), e.line(), e.field(), e.problem()).located("f.csv", 3);
  BOOST_TEST(again.said(cli, cli) == "f.csv:3: --dem.cache_only: contradicts --dem.no_cache");
}

BOOST_AUTO_TEST_CASE(diagnose_synthesize_estimate_and_simulate_check_first) {
  Hook hook;
  api::DiagnoseOptions d;
  d.dataset = "/nonexistent";
  d.prepare_output = hook.fn();
  d.alpha = std::nan("");
  refused([&] { api::diagnose(d); }, "alpha");
  d.alpha = 0.01;
  d.self_check = -1;
  refused([&] { api::diagnose(d); }, "self_check");
  d.self_check = 0;
  d.jobs = 1000;
  refused([&] { api::diagnose(d); }, "jobs");

  api::SynthesizeOptions s;
  s.dataset = "/nonexistent";
  s.prepare_output = hook.fn();
  s.noise_scale = -1;
  refused([&] { api::synthesize(s); }, "noise_scale");
  s.noise_scale = 1;
  s.outliers = -1;
  refused([&] { api::synthesize(s); }, "outliers");
  s.outliers = 0;
  s.inputs = {"air_drag=0.5"};
  refused([&] { api::synthesize(s); }, "input");

  api::EstimateOptions e;
  e.dataset = "/nonexistent";
  e.setup = "/nonexistent/setup.toml";
  refused([&] { api::estimate(e); }, "setup");
  e.setup.clear();
  e.belt_speed = -1;
  refused([&] { api::estimate(e); }, "belt_speed");
  e.belt_speed.reset();
  e.effects = {"air_drag"};
  refused([&] { api::estimate(e); }, "effect");

  api::SimulateOptions m;
  m.dataset = "/nonexistent";
  m.condition = "V3-41";
  m.settings.set("quality", "fast");
  refused([&] { api::simulate(m); }, "quality");
  m.settings = {};
  m.settings.set("contact", "glue");
  refused([&] { api::simulate(m); }, "contact");
  m.settings = {};
  m.settings.set("steady_on", "shear");
  refused([&] { api::simulate(m); }, "steady_on");
  m.settings = {};
  m.settings.set("map_cell_mm", 0.5);  // between 0 and the range: refused by the table, not the type
  refused([&] { api::simulate(m); }, "map_cell_mm");
  m.settings = {};
  m.vtk_every = 0.1;  // a particle series needs a folder to go to
  const InputError v = refused([&] { api::simulate(m); }, "vtk_every");
  BOOST_TEST(v.problem_said() == "needs out DIR");
  BOOST_TEST(hook.calls == 0);
}

BOOST_AUTO_TEST_CASE(calibrate_and_sensitivity_check_first) {
  Hook hook;
  api::CalibrateOptions c;
  c.dataset = "/nonexistent";
  c.prepare_output = hook.fn();
  c.rolling = {0.1, 2.0};
  refused([&] { api::calibrate(c); }, "rolling");
  c.rolling = {0.1};
  c.density = {-5.0};
  refused([&] { api::calibrate(c); }, "density");
  c.density = {990.0};
  c.shapes = {"cube"};
  refused([&] { api::calibrate(c); }, "shape");
  c.shapes = {"sphere", "clump"};
  c.rolling = std::vector<double>(60, 0.1);  // 120 slump tests: hours
  refused([&] { api::calibrate(c); }, "rolling");
  c.rolling = {0.1};
  c.quality = "paper";
  refused([&] { api::calibrate(c); }, "quality");
  c.quality = "quick";
  c.target_bulk_density = 0.0;
  refused([&] { api::calibrate(c); }, "target_bulk_density");
  c.target_bulk_density.reset();
  c.threads = 0;
  refused([&] { api::calibrate(c); }, "threads");
  c.threads = 1;
  c.jobs = -1;
  refused([&] { api::calibrate(c); }, "jobs");

  api::SensitivityOptions s;
  s.dataset = "/nonexistent";
  s.prepare_output = hook.fn();
  s.sizes_mm = {9.0, -5.0};
  refused([&] { api::sensitivity(s); }, "sizes");
  s.sizes_mm = {1, 2, 3, 4, 5, 6, 7};  // seven station DEM runs more
  refused([&] { api::sensitivity(s); }, "sizes");
  s.sizes_mm.clear();
  s.only = {"LSD", ""};
  refused([&] { api::sensitivity(s); }, "only");
  s.only.clear();
  s.limit = -1;
  refused([&] { api::sensitivity(s); }, "limit");
  s.limit = 10;
  s.quality = "fast";
  refused([&] { api::sensitivity(s); }, "quality");
  s.quality = "quick";
  s.threads = 1000;
  refused([&] { api::sensitivity(s); }, "threads");
  BOOST_TEST(hook.calls == 0);
}

// The study's campaign takes its runs side by side as an option, not from the process: one at a
// time and two side by side give the same bytes (the determinism rule), and an unknown variant is
// refused once the variants are known, before any run.
BOOST_AUTO_TEST_CASE(sensitivity_is_the_same_at_any_number_of_jobs) {
  api::SensitivityOptions s;
  s.dataset = chutelab::test::tiny_station_dataset("api-sensitivity");
  s.condition = "T3";
  s.only = {"cube"};
  int planned = 0;
  s.planned = [&](const studies::SensitivityStudy&, const std::vector<studies::SensitivityVariant>&) { ++planned; };
  refused([&] { api::sensitivity(s); }, "only");
  BOOST_TEST(planned == 0);
  s.only = {"G/10"};
  s.jobs = 1;
  const api::SensitivityResult one = api::sensitivity(s);
  s.jobs = 2;
  const api::SensitivityResult two = api::sensitivity(s);
  BOOST_TEST(planned == 2);
  BOOST_REQUIRE(one.study.rows.size() == 2u);
  BOOST_TEST(one.study.rows[1].variant.key == "G/10");
  const auto f1 = one.files(), f2 = two.files();
  BOOST_REQUIRE(f1.size() == f2.size());
  for (std::size_t k = 0; k < f1.size(); ++k)
    if (f1[k].first != "sensitivity-timing.csv") BOOST_TEST(f1[k].second == f2[k].second, f1[k].first);
}

BOOST_AUTO_TEST_CASE(the_output_hook_is_told_the_plan_once_before_the_runs) {
  api::ValidateOptions o;
  o.dataset = kHidden;
  o.effects = {"air_drag=fit"};
  api::OutputPlan seen;
  int calls = 0;
  o.prepare_output = [&](const api::OutputPlan& p) -> fs::path {
    ++calls;
    seen = p;
    return {};
  };
  const api::ValidateResult r = api::validate(o);
  BOOST_TEST(calls == 1);
  BOOST_TEST(!seen.model_folder);
  // Every file by name, and the report's charts in the folder the plan names for them.
  std::vector<std::string> names;
  std::size_t charts = 0;
  for (const auto& [n, text] : r.files()) {
    if (n.starts_with("figures/")) ++charts;
    else names.push_back(n);
  }
  BOOST_TEST(names == seen.files, boost::test_tools::per_element());
  BOOST_TEST(charts > 0u);
  BOOST_TEST((seen.folders == std::vector<std::string>{"figures"}));
  const bool reads_measurements =
      std::find(seen.inputs.begin(), seen.inputs.end(), kHidden / "measurements.csv") != seen.inputs.end();
  BOOST_TEST(reads_measurements);

  // A hook that refuses (a bad output folder) ends the call before any model runs.
  o.prepare_output = [](const api::OutputPlan&) -> fs::path { throw InputError("", 0, "out", "refused"); };
  refused([&] { api::validate(o); }, "out");
}

BOOST_AUTO_TEST_CASE(the_command_line_writes_what_the_library_returns) {
  // validate: the same tables, pages and charts, byte for byte (the fit and the diagnosis included).
  const fs::path out = test::fresh_dir("api_validate_cli");
  const auto cli = test::run_chutelab("validate --quiet --dataset " + kHidden.string() +
                                      " --effect air_drag=fit --out " + out.string());
  BOOST_TEST(cli.exit_code == 0, cli.err);
  api::ValidateOptions o;
  o.dataset = kHidden;
  o.effects = {"air_drag=fit"};
  const api::ValidateResult r = api::validate(o);
  std::size_t charts = 0;
  for (const auto& [name, text] : r.files()) charts += name.starts_with("figures/") ? 1 : 0;
  BOOST_TEST(charts >= 6u);  // the report's charts beside report.md
  BOOST_TEST(r.files().size() == 7u + charts);
  for (const auto& [name, text] : r.files()) BOOST_TEST(test::read_file(out / name) == text, name);

  // diagnose: its two files.
  const fs::path dout = test::fresh_dir("api_diagnose_cli");
  const auto dcli = test::run_chutelab("diagnose --quiet --dataset " + kHidden.string() + " --out " + dout.string());
  BOOST_TEST(dcli.exit_code == 0, dcli.err);
  api::DiagnoseOptions d;
  d.dataset = kHidden;
  for (const auto& [name, text] : api::diagnose(d).files()) BOOST_TEST(test::read_file(dout / name) == text, name);

  // estimate: the JSON.
  const auto ecli = test::run_chutelab("estimate --dataset " + kRig.string() +
                                       " --condition V5-44 --effect air_drag=0.5 --format json");
  BOOST_TEST(ecli.exit_code == 0, ecli.err);
  api::EstimateOptions e;
  e.dataset = kRig;
  e.condition = "V5-44";
  e.effects = {"air_drag=0.5"};
  BOOST_TEST(api::estimate(e).json() == ecli.out);

  // synthesize: the dataset's files.
  const fs::path sout = test::fresh_dir("api_synthesize_cli");
  const auto scli = test::run_chutelab("synthesize --effect air_drag=0.7 --seed 3 --out " + (sout / "d").string());
  BOOST_TEST(scli.exit_code == 0, scli.err);
  api::SynthesizeOptions s;
  s.default_dataset = kRig;
  s.effects = {"air_drag=0.7"};
  s.seed = 3;
  for (const auto& [name, text] : api::synthesize(s).files)
    BOOST_TEST(test::read_file(sout / "d" / name) == text, name);
}
