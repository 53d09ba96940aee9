// `chutelab synthesize`: a dataset with known hidden physics, for testing the diagnosis.
#include <fmt/format.h>
#include <iostream>

#include "api/synthesize.h"
#include "app/commands.h"
#include "app/output_hook.h"
#include "app/option_checks.h"
#include "api/files.h"

namespace chutelab::app {
namespace {

struct SynthesizeCli {
  std::string dataset, out;
  std::vector<std::string> effects;
  std::vector<std::string> inputs;
  std::uint64_t seed = 1;
  double noise_scale = 1.0, noise_factor = 1.0;
  int outliers = 0;
  bool out_of_range = false;
};

int run_synthesize(const SynthesizeCli& o) {
  api::SynthesizeOptions opt;
  opt.dataset = o.dataset;
  opt.default_dataset = default_dataset();
  opt.effects = o.effects;
  opt.inputs = o.inputs;
  opt.seed = o.seed;
  opt.noise_scale = o.noise_scale;
  opt.noise_factor = o.noise_factor;
  opt.outliers = o.outliers;
  opt.allow_out_of_range = o.out_of_range;
  // Checked before any work (and again, the same way, where the dataset is written).
  opt.prepare_output = check_output(o.out, "synthesize");
  const api::SynthesizeResult r = api::synthesize(opt);
  api::write_dataset(o.out, r.files, r.source.dir, "synthesize");
  std::cout << fmt::format("synthetic dataset: {}\n", o.out);
  return 0;
}

}  // namespace

void add_synthesize(CLI::App& app, Action& action) {
  auto o = std::make_shared<SynthesizeCli>();
  auto* cmd = app.add_subcommand("synthesize",
                                 "Write a dataset whose measurements come from the analytical models "
                                 "plus hidden effects plus Gaussian noise.");
  cmd->add_option("--dataset", o->dataset, "rig and conditions to use (default: bundled grima2010)");
  cmd->add_option("--effect", o->effects, "hidden effect NAME=VALUE (repeatable)");
  cmd->add_option("--input", o->inputs,
                  "a wrong record: the recorded input NAME is off by VALUE (truth minus record, e.g. "
                  "plate_distance=25 in mm; NAME@CONDITION=VALUE at one condition alone); the measurements come from the truth (repeatable)");
  with_rule(cmd->add_option("--seed", o->seed, "random seed")->capture_default_str(), options::rules::seed);
  with_rule(cmd->add_option("--noise-scale", o->noise_scale, "multiplies every uncertainty")->capture_default_str(),
            options::rules::noise_scale);
  with_rule(cmd->add_option("--noise-factor", o->noise_factor,
                            "the real scatter in stated uncertainties (2: the stated uncertainties are half the truth)")
                ->capture_default_str(),
            options::rules::noise_factor);
  with_rule(cmd->add_option("--outliers", o->outliers,
                            "gross reading errors (8-15 stated uncertainties) among the measurements")
                ->capture_default_str(),
            options::rules::outliers);
  cmd->add_flag("--allow-out-of-range", o->out_of_range,
                "accept effect strengths outside their physical range (test data only; the README says so)");
  cmd->add_option("--out", o->out, "output folder")->required();
  cmd->callback([o, &action] { action = [o] { return run_synthesize(*o); }; });
}

}  // namespace chutelab::app
