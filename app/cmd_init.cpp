// `chutelab init`: a minimal dataset to fill with a rig's numbers, or the dataset reference, both
// from the dataset readers' own tables (api/files.h).
#include <fmt/format.h>
#include <iostream>

#include "app/commands.h"
#include "core/campaign.h"
#include "core/input_error.h"
#include "api/files.h"

namespace chutelab::app {
namespace {

struct InitCli {
  std::string out;
  bool reference = false;
};

int run_init(const InitCli& o) {
  if (o.reference) {
    if (!o.out.empty())
      throw InputError("", 0, "reference", "--reference prints the reference page; give it without --out");
    std::cout << api::dataset_reference();
    return 0;
  }
  if (o.out.empty())
    throw InputError("", 0, "out", "give the folder to write the dataset in (--out DIR), or --reference");
  if (campaign::ranks() > 1)  // every rank would write the same new folder
    throw InputError("", 0, "mpirun", "init writes one dataset folder: run it as one process");
  api::write_dataset_skeleton(o.out, default_dataset());
  std::cout << fmt::format(
      "dataset: {} (setup.toml, conditions.csv, measurements.csv, README.md: the reference study's rig and five "
      "conditions, the measured values placeholders)\nnext: replace the numbers with your rig's, then\n"
      "  chutelab validate --dataset {} --out {}-report\n",
      o.out, o.out, o.out);
  return 0;
}

}  // namespace

void add_init(CLI::App& app, Action& action) {
  auto o = std::make_shared<InitCli>();
  auto* cmd = app.add_subcommand(
      "init",
      "Write a minimal dataset (setup, five conditions, placeholder measurements), every line commented, to fill "
      "with your rig's numbers; or print the reference of every file, column and key.");
  cmd->add_option("--out", o->out, "the new dataset's folder");
  cmd->add_flag("--reference", o->reference,
                "print the dataset reference (docs/dataset-reference.md) as Markdown instead");
  cmd->callback([o, &action] { action = [o] { return run_init(*o); }; });
}

}  // namespace chutelab::app
