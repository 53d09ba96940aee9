// `chutelab design --out DIR`: writes the designer's page, one self-contained HTML file that runs
// the analytical chain (this program's own estimate, compiled to WebAssembly) from file://.
#include <fmt/format.h>
#include <fstream>
#include <iostream>
#include <sstream>

#include "app/commands.h"
#include "app/design/page.h"
#include "app/output.h"
#include "core/input_error.h"
#include "validation/dataset.h"
#include "validation/output_files.h"

namespace chutelab::app {
namespace {

struct DesignOptions {
  std::string out, dataset, setup_file;
};

std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
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
  validation::read_setup(setup);
  std::string literal = json_string(slurp(setup));
  for (std::size_t at = literal.find("</"); at != std::string::npos; at = literal.find("</", at + 3))
    literal.replace(at, 2, "<\\/");  // a "</script>" inside the TOML must not end the page's script
  std::string html(*page);
  const std::string marker = "/*CHUTELAB_SETUP*/null";
  const auto at = html.find(marker);
  if (at == std::string::npos) throw InputError("", 0, "design", "the built-in page has no setup slot (a build error)");
  html.replace(at, marker.size(), literal);
  std::error_code ec;
  if (fs::equivalent(fs::path(o.out) / "design.html", setup, ec))
    throw InputError(o.out, 0, "--out", "design.html there is this run's input; choose another folder");
  validation::write_outputs(o.out, {{"design.html", html}});
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
  cmd->callback([o, &action] { action = [o] { return run_design(*o); }; });
}

}  // namespace chutelab::app
