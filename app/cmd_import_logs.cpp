// `chutelab import-logs`: a dataset whose plate measurements are the rig's raw logs becomes a
// dataset of means, each row with its provenance (api/import_logs.h).
#include <fmt/format.h>
#include <iostream>

#include "api/import_logs.h"
#include "app/commands.h"
#include "app/output_hook.h"
#include "api/files.h"

namespace chutelab::app {
namespace {

struct ImportLogsCli {
  std::string dataset, out;
};

int run_import_logs(const ImportLogsCli& o) {
  api::ImportLogsOptions opt;
  opt.dataset = o.dataset;
  opt.prepare_output = check_output(o.out, "import-logs");
  const api::ImportLogsResult r = api::import_logs(opt);
  api::write_dataset(o.out, r.files(), r.dataset.dir, "import-logs");
  for (const auto& c : r.logs.conditions) {
    std::cout << fmt::format("{}: window {:.2f}-{:.2f} s{}", c.condition, c.segments.window.start,
                             c.segments.window.end, c.segments.steady ? "" : " (not steady)");
    for (const auto& q : c.quantities) {
      const auto& qi = info(q.quantity);
      std::cout << fmt::format("; {} {:.5g} ± {:.2g} {}", qi.symbol, q.value * qi.to_boundary,
                               q.budget.u * qi.to_boundary, qi.unit);
    }
    std::cout << (c.flagged() ? " [flagged]" : "") << '\n';
  }
  std::cout << fmt::format("dataset of means: {}\n", o.out);
  return 0;
}

}  // namespace

void add_import_logs(CLI::App& app, Action& action) {
  auto o = std::make_shared<ImportLogsCli>();
  auto* cmd = app.add_subcommand(
      "import-logs",
      "Read a dataset's raw logs (logs/layout.toml, one logs/<condition>.csv a condition) into means with "
      "their uncertainties: steady window, zero, drift and creep found from each log.");
  cmd->add_option("--dataset", o->dataset, "dataset folder holding logs/")->required();
  cmd->add_option("--out", o->out, "the dataset of means to write")->required();
  cmd->callback([o, &action] { action = [o] { return run_import_logs(*o); }; });
}

}  // namespace chutelab::app
