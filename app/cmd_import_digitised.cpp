// `chutelab import-digitised`: curves digitised from published figures (WebPlotDigitizer's CSV
// export or project JSON) become trajectory.csv / measurements.csv rows of a dataset.
#include <fmt/format.h>
#include <iostream>

#include "api/import_digitised.h"
#include "app/commands.h"
#include "core/campaign.h"
#include "core/input_error.h"
#include "core/message.h"

namespace chutelab::app {
namespace {

struct ImportCli {
  std::string dataset, mapping, out;
  std::vector<std::string> inputs;
};

int run_import(const ImportCli& o) {
  if (campaign::ranks() > 1)  // every rank would write the same new folder
    throw InputError("", 0, "mpirun", "import-digitised writes one dataset folder: run it as one process");
  api::ImportDigitisedOptions opt;
  opt.dataset = o.dataset;
  opt.mapping = o.mapping;
  opt.inputs.assign(o.inputs.begin(), o.inputs.end());
  opt.out = o.out;
  const api::ImportDigitisedResult imp = api::import_digitised(opt);
  for (const auto& n : imp.unmapped)
    warn(fmt::format("curve {} is not in the mapping and was not imported", shown(n)));
  for (const auto& s : imp.summary) std::cout << one_line(s) << "\n";
  std::cout << fmt::format("dataset: {} ({} measurements, {} trajectory points imported)\n", o.out,
                           imp.measurements, imp.trajectory_points);
  return kExitOk;
}

}  // namespace

void add_import_digitised(CLI::App& app, Action& action) {
  auto o = std::make_shared<ImportCli>();
  auto* cmd = app.add_subcommand(
      "import-digitised",
      "Turn curves digitised from figures (WebPlotDigitizer CSV export or project JSON) into trajectory.csv "
      "and measurements.csv rows: writes a new dataset folder (the source dataset plus the imported rows), "
      "checked by the dataset reader.");
  cmd->add_option("--dataset", o->dataset, "dataset whose setup.toml and conditions.csv the curves belong to")
      ->required();
  cmd->add_option("--mapping", o->mapping, "TOML file: which curve is which condition and boundary or quantity, "
                                           "axis units, digitising uncertainty (README, import-digitised)")
      ->required();
  cmd->add_option("--input", o->inputs, "WebPlotDigitizer CSV export or project .json (repeatable)")->required();
  cmd->add_option("--out", o->out, "new dataset folder (must not exist, or be empty)")->required();
  cmd->callback([o, &action] { action = [o] { return run_import(*o); }; });
}

}  // namespace chutelab::app
