#pragma once
// Each subcommand adds itself to the CLI and sets the action run after parsing.
#include <CLI/CLI.hpp>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace chutelab {
class OutputFolder;
}

namespace chutelab::app {

using Action = std::function<int()>;

void add_init(CLI::App& app, Action& action);
void add_estimate(CLI::App& app, Action& action);
void add_validate(CLI::App& app, Action& action);
void add_diagnose(CLI::App& app, Action& action);
void add_synthesize(CLI::App& app, Action& action);
void add_simulate(CLI::App& app, Action& action);
void add_calibrate(CLI::App& app, Action& action);
void add_sensitivity(CLI::App& app, Action& action);
void add_import_digitised(CLI::App& app, Action& action);
void add_import_logs(CLI::App& app, Action& action);
void add_synthesize_logs(CLI::App& app, Action& action);
void add_design(CLI::App& app, Action& action);

// "a,b,,c" -> {"a", "b", "", "c"}: the comma lists of --models, empty items kept for the library's
// check (validation::make_models refuses them).
std::vector<std::string> split_list(const std::string& s);

// "unknown command 'valdate'; did you mean 'validate'?" for the first misspelt command or flag of
// this command line, with the nearest real one when there is one (nullopt when nothing is misspelt).
std::optional<std::string> misspelt(CLI::App& app, int argc, char** argv);

// What a command reads from a dataset folder: the folder itself (--out may not be it) and its files.
std::vector<std::filesystem::path> dataset_inputs(const std::filesystem::path& dir);

// Refuses, before any long run, an --out where one of these files cannot be placed (a folder there).
void check_entries(const OutputFolder& out, std::initializer_list<const char*> files);

// The bundled default rig, found next to the source tree this binary was built from.
std::filesystem::path default_dataset();

}  // namespace chutelab::app
