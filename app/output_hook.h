#pragma once
// The command line's answer to the library's prepare_output hook (api/output_plan.h): --out is
// checked, and for a command that writes its files there placed, once every input is read and
// before any model runs, so that a bad --out costs no DEM run. One rule for every command: an
// --out that holds an input, or an entry this command's record does not own, is refused then
// (core/output_folder.h), with the words commit() would use.
#include <filesystem>
#include <functional>
#include <optional>
#include <string>

#include "api/output_plan.h"
#include "core/output_folder.h"

namespace chutelab::app {

// What else a command checks in its placed folder once the plan's files and folders are checked,
// and where the library may write while it runs ("" = nowhere).
using MorePlanned = std::function<std::filesystem::path(OutputFolder&, const api::OutputPlan&)>;

// The hook of a command whose result files go into --out: `out` is placed in `dir` as `command`'s
// output, every planned file and folder checked, then `more` (none: the library writes nothing).
api::PrepareOutput place_output(std::optional<OutputFolder>& out, const std::string& dir, std::string command,
                                MorePlanned more = {});

// The hook of a command that writes a dataset folder itself afterwards (api::write_dataset): --out
// checked as `command` would place it, nothing placed yet.
api::PrepareOutput check_output(const std::string& dir, std::string command);

}  // namespace chutelab::app
