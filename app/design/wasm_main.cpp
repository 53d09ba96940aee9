// The designer's page runs `chutelab estimate` itself, compiled to WebAssembly: the page hands it
// the arguments a user would type (a setup.toml it wrote into the module's in-memory file system,
// the operating point, the effects) and shows what it prints. No physics lives in the page.
#include <CLI/CLI.hpp>
#include <emscripten/bind.h>
#include <fmt/format.h>
#include <iostream>
#include <sstream>
#include <string_view>

#include "app/commands.h"
#include "app/flag_names.h"
#include "app/option_checks.h"
#include "api/effect_library.h"
#include "api/estimate_output.h"
#include "api/setup.h"
#include "core/csv_field.h"
#include "core/input_error.h"
#include "core/message.h"
#include "core/rig.h"

// The page runs no DEM and takes none of its options: no key it names is a [dem] setting. (The
// native build has the [dem] table itself, api/dem_options.cpp, which the page does not link.)
namespace chutelab::api {
bool is_dem_setting(std::string_view) { return false; }
}  // namespace chutelab::api

namespace chutelab::app {
// The bundled rig, packed into the module's file system at build time (em++ --embed-file).
std::filesystem::path default_dataset() { return "/datasets/grima2010"; }
}  // namespace chutelab::app

namespace {
using namespace chutelab;

struct RunResult {
  int code = 0;
  std::string out, err;
  // Bad input as the library said it: the neutral key of the field (core/input_error.h), the file
  // it was found in, and the problem with each mentioned input between \x01 and \x02, so that the
  // page can name both in its own words.
  std::string field, file, problem;
};

// One `chutelab estimate ...` run, as main() does it: same parser, same messages, same exit codes.
RunResult run(const std::vector<std::string>& args) {
  RunResult r;
  std::ostringstream out, err;
  auto* old_out = std::cout.rdbuf(out.rdbuf());
  auto* old_err = std::cerr.rdbuf(err.rdbuf());
  try {
    CLI::App app{"chutelab: conveyor transfer-station models against measurements"};
    app.require_subcommand(1);
    app::Action action;
    app::add_estimate(app, action);
    app::check_every_option(app);
    std::vector<std::string> argv = {"chutelab"};
    argv.insert(argv.end(), args.begin(), args.end());
    std::vector<char*> ptrs;
    for (auto& a : argv) ptrs.push_back(a.data());
    try {
      app.parse(static_cast<int>(ptrs.size()), ptrs.data());
      r.code = action ? action() : kExitBadInput;
    } catch (const CLI::CallForHelp& e) {
      r.code = app.exit(e, out, err);
    } catch (const CLI::ParseError& e) {
      err << "chutelab: " << one_line(e.what()) << " (see --help)\n";
      r.code = kExitBadInput;
    } catch (const InputError& e) {
      err << "chutelab: " << app::said(e) << "\n";
      r.code = kExitBadInput;
      r.field = e.field();
      r.file = e.file();
      r.problem = e.problem_said([](std::string_view key) { return "\x01" + std::string(key) + "\x02"; });
    }
  } catch (const std::exception& e) {
    err << "chutelab: " << e.what() << "\n";
    r.code = kExitBadInput;
  }
  std::cout.rdbuf(old_out);
  std::cerr.rdbuf(old_err);
  r.out = out.str();
  r.err = err.str();
  return r;
}

std::string number_or_null(std::optional<double> v) { return v ? api::json_number(*v) : "null"; }

// The rig's parameters as the dataset reader knows them: the page builds its fields from this.
std::string rig_fields_json() {
  std::string o = "[";
  for (const auto& f : rig_fields())
    o += fmt::format("{}{{\"section\": {}, \"key\": {}, \"label\": {}, \"column\": {}, \"min\": {}, \"max\": {}, \"required\": {}, \"fallback\": {}}}",
                     o.size() > 1 ? "," : "", api::json_string(std::string(f.section)), api::json_string(std::string(f.key)),
                     api::json_string(std::string(f.label)),
                     api::json_string(std::string(f.column)), api::json_number(f.min), api::json_number(f.max),
                     f.required ? "true" : "false", number_or_null(f.fallback));
  return o + "]";
}

// The bounds every operating input is checked against (api::operating_limits).
std::string operating_limits_json() {
  std::string o = "{";
  for (const auto& l : api::operating_limits())
    o += fmt::format("{}{}: {{\"min\": {}, \"min_open\": {}, \"max\": {}}}", o.size() > 1 ? ", " : "",
                     api::json_string(l.column), api::json_number(l.min), l.min_open ? "true" : "false",
                     api::json_number(l.max));
  return o + "}";
}

std::string effects_json() {
  std::string o = "[";
  for (const auto& e : api::effect_library()) {
    // A designer changes an input itself; a recorded input's error is for measured data. The load
    // cells' records stay listed as measurement effects, so that the page can say why it ignores
    // one in an address.
    if (e.record && e.stage != "measurement") continue;
    o += fmt::format("{}{{\"name\": {}, \"parameter\": {}, \"unit\": {}, \"stage\": {}, \"physics\": {}, \"neutral\": {}, "
                     "\"lower\": {}, \"upper\": {}, \"typical\": {}}}",
                     o.size() > 1 ? "," : "", api::json_string(e.name), api::json_string(e.parameter),
                     api::json_string(e.unit), api::json_string(e.stage), api::json_string(e.physics),
                     api::json_number(e.neutral), api::json_number(e.lower), api::json_number(e.upper),
                     api::json_number(e.typical));
  }
  return o + "]";
}

// A setup.toml read by the dataset reader, as boundary values keyed "section.key"; an error
// comes back as {"error": "..."} with the reader's message.
std::string setup_json(const std::string& path) {
  try {
    Setup s = api::read_setup(path);
    std::string o = fmt::format("{{\"name\": {}, \"source\": {}, \"values\": {{", api::json_string(s.name),
                                api::json_string(s.source));
    bool first = true;
    for (const auto& f : rig_fields()) {
      o += fmt::format("{}\"{}{}{}\": {}", first ? "" : ", ", f.section, f.section.empty() ? "" : ".", f.key,
                       api::json_number(f.ref(s) / f.to_si));
      first = false;
    }
    return o + "}}";
  } catch (const InputError& e) {
    return fmt::format("{{\"error\": {}}}", api::json_string(app::said(e)));
  }
}

std::string csv_field_of(const std::string& text) { return csv_field(text); }

}  // namespace

EMSCRIPTEN_BINDINGS(chutelab_design) {
  emscripten::register_vector<std::string>("StringList");
  emscripten::value_object<RunResult>("RunResult")
      .field("code", &RunResult::code)
      .field("out", &RunResult::out)
      .field("err", &RunResult::err)
      .field("field", &RunResult::field)
      .field("file", &RunResult::file)
      .field("problem", &RunResult::problem);
  emscripten::function("run", &run);
  emscripten::function("rigFields", &rig_fields_json);
  emscripten::function("effects", &effects_json);
  emscripten::function("operatingLimits", &operating_limits_json);
  emscripten::function("setup", &setup_json);
  // The page's conditions.csv export goes through the one CSV writer (core/csv_field.h): quoting
  // and the spreadsheet-formula policy are the command line's.
  emscripten::function("csvField", &csv_field_of);
}
