#pragma once
// What a library function will write, said to its caller once every input is read and checked and
// before any model runs: a front end that writes files places its output folder then (the command
// line's --out), so that a bad folder costs no DEM run. The library itself writes nothing but what
// a caller's hook returns a folder for (the DEM's per-condition series, a simulation's VTK frames).
#include <filesystem>
#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace chutelab::api {

// One file of a result: its name in the output folder and its content.
using OutputFile = std::pair<std::string, std::string>;

struct OutputPlan {
  std::vector<std::filesystem::path> inputs;  // every file and folder the run reads (none may be overwritten)
  std::vector<std::string> files;             // the result's files (ValidateResult::files(), ...)
  std::vector<std::string> folders;           // folders of result files named by the results (report.md's figures/)
  bool model_folder = false;                  // expensive models would write per-condition files
};

// Called once with the plan; returns the folder where the run may write while it runs ("" = none).
// An exception it throws ends the call before any model runs.
using PrepareOutput = std::function<std::filesystem::path(const OutputPlan&)>;

// The folders and files that the models external:NAME=DIR of a model list read.
std::vector<std::filesystem::path> model_inputs(const std::vector<std::string>& models);

}  // namespace chutelab::api
