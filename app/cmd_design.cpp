// `chutelab design --out DIR`: writes the designer's page, one self-contained HTML file that runs
// the analytical chain (this program's own estimate, compiled to WebAssembly) from file://.
#include <fmt/format.h>
#include <fstream>
#include <iostream>
#include <sstream>

#include "app/commands.h"
#include "app/design/page.h"
#include "api/estimate_output.h"
#include "api/files.h"
#include "api/setup.h"
#include "core/input_error.h"
#include "core/units.h"

namespace chutelab::app {
using api::json_number;
using api::json_string;
namespace {

struct DesignOptions {
  std::string out, dataset, setup_file, condition;
};

std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// A dataset row as the page's inputs (its keys are those of the page's URL hash): the operating
// point and every rig field with the row's overrides applied.
std::string condition_inputs(const DesignOptions& o, const std::filesystem::path& setup_path) {
  if (!o.setup_file.empty())
    throw InputError("", 0, "--condition", "--condition picks a row of a dataset's conditions.csv; use --dataset");
  const auto dir = o.dataset.empty() ? default_dataset() : std::filesystem::path(o.dataset);
  const Setup setup = api::read_setup(setup_path);
  const Station row = api::read_condition(dir, setup, o.condition, "--condition");
  const Station* st = &row;
  std::string js = fmt::format("{{\"name\": {}, \"belt_speed\": {}, \"mass_flow\": {}, \"plate_distance\": {}, \"plate_top\": {}, "
                               "\"stream_thickness\": {}",
                               json_string(st->condition), json_number(st->belt_speed), json_number(st->mass_flow / units::tph),
                               json_number(st->plate_distance * 1e3), json_number(st->plate_top * 1e3),
                               st->stream_thickness ? json_number(*st->stream_thickness * 1e3) : "null");
  Setup with_row = setup;
  with_row.belt = st->belt;
  with_row.plate = st->plate;
  with_row.material = st->material;
  with_row.gravity = st->gravity;
  for (const auto& f : rig_fields())
    js += fmt::format(", \"{}{}{}\": {}", f.section, f.section.empty() ? "" : ".", f.key, json_number(f.ref(with_row) / f.to_si));
  js += "}";
  for (std::size_t at = js.find("</"); at != std::string::npos; at = js.find("</", at + 3)) js.replace(at, 2, "<\\/");
  return js;
}

int run_design(const DesignOptions& o) {
  namespace fs = std::filesystem;
  const auto page = design_page();
  if (!page)
    throw InputError("", 0, "design",
                     "this chutelab was built without emscripten, so it carries no designer's page; install "
                     "Debian's emscripten (scripts/setup.sh does) and rebuild");
  if (!o.dataset.empty() && !o.setup_file.empty())
    throw InputError("", 0, "--setup", "give either --dataset or --setup, not both");
  // The rig the page starts from: checked by the same reader first, so the page never opens on an
  // error the user could have been told about here.
  const fs::path setup = !o.setup_file.empty() ? fs::path(o.setup_file)
                         : !o.dataset.empty()  ? fs::path(o.dataset) / "setup.toml"
                                               : default_dataset() / "setup.toml";
  api::read_setup(setup);
  std::string literal = json_string(slurp(setup));
  for (std::size_t at = literal.find("</"); at != std::string::npos; at = literal.find("</", at + 3))
    literal.replace(at, 2, "<\\/");  // a "</script>" inside the TOML must not end the page's script
  std::string html(*page);
  auto fill = [&](const std::string& marker, const std::string& text) {
    const auto at = html.find(marker);
    if (at == std::string::npos) throw InputError("", 0, "design", "the built-in page has no slot " + marker + " (a build error)");
    html.replace(at, marker.size(), text);
  };
  fill("/*CHUTELAB_SETUP*/null", literal);
  if (!o.condition.empty()) fill("/*CHUTELAB_INPUTS*/null", condition_inputs(o, setup));
  std::error_code ec;
  if (fs::equivalent(fs::path(o.out) / "design.html", setup, ec))
    throw InputError(o.out, 0, "--out", "design.html there is this run's input; choose another folder");
  // --out may not be the dataset folder the page starts from (nor replace its setup.toml).
  std::vector<fs::path> inputs = {setup};
  if (!o.dataset.empty())
    for (auto& p : dataset_inputs(o.dataset)) inputs.push_back(std::move(p));
  api::write_files(o.out, {{"design.html", html}}, inputs, "design");
  std::cout << fmt::format("wrote {} ({:.1f} MB, self-contained: open it in a browser, no server needed)\n",
                           (fs::path(o.out) / "design.html").string(), html.size() / 1e6);
  return kExitOk;
}

}  // namespace

void add_design(CLI::App& app, Action& action) {
  auto o = std::make_shared<DesignOptions>();
  auto* cmd = app.add_subcommand(
      "design",
      "Write the designer's page: DIR/design.html, one self-contained file that runs estimate's analytical "
      "chain (Booth/CEMA, Korzen, effects) in the browser from file://, with sliders, the stream drawing, "
      "a chart against plate distance and export of the design as a dataset row.");
  cmd->add_option("--out", o->out, "folder to write design.html into")->required();
  cmd->add_option("--dataset", o->dataset, "start from this dataset's setup.toml (default: the bundled rig)");
  cmd->add_option("--setup", o->setup_file, "start from this setup.toml");
  cmd->add_option("--condition", o->condition,
                  "start from this row of the dataset's conditions.csv (operating point and per-condition overrides)");
  cmd->callback([o, &action] { action = [o] { return run_design(*o); }; });
}

}  // namespace chutelab::app
