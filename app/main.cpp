// chutelab: how far are transfer-station models from the measurements, and why.
#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <iostream>

#include "app/commands.h"
#include "core/campaign.h"
#include "core/input_error.h"

namespace chutelab::app {
std::vector<std::string> split_list(const std::string& s) {
  std::vector<std::string> out;
  std::size_t start = 0;
  while (start <= s.size()) {
    const auto end = s.find(',', start);
    std::string item = s.substr(start, end == std::string::npos ? std::string::npos : end - start);
    if (!item.empty()) out.push_back(item);
    if (end == std::string::npos) break;
    start = end + 1;
  }
  return out;
}

std::filesystem::path default_dataset() {
  return std::filesystem::path(CHUTELAB_DATASETS_DIR) / "grima2010";
}
}  // namespace chutelab::app

int main(int argc, char** argv) {
  using namespace chutelab;
  // Under mpirun every rank runs the command; rank 0 alone prints and writes (core/campaign.h).
  campaign::Session session(argc, argv);
  if (!session.refusal().empty()) {
    std::cerr << "chutelab: " << session.refusal() << "\n";
    return kExitBadInput;
  }
  CLI::App app{"chutelab: conveyor transfer-station models against measurements"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "chutelab 0.1.0");
  app::Action action;
  app::add_estimate(app, action);
  app::add_validate(app, action);
  app::add_diagnose(app, action);
  app::add_synthesize(app, action);
  app::add_simulate(app, action);
  app::add_calibrate(app, action);
  app::add_sensitivity(app, action);
  app::add_import_digitised(app, action);
  app::add_design(app, action);
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::cerr << "chutelab: " << e.what() << " (see --help)\n";
    return kExitBadInput;
  }
  try {
    return action ? action() : kExitBadInput;
  } catch (const InputError& e) {
    std::cerr << "chutelab: " << e.what() << "\n";
    return kExitBadInput;
  }
}
