#pragma once
// Many runs of expensive models as one campaign (core/campaign.h): spread over the ranks of
// `mpirun`, or over `--jobs N` worker threads, or run in order — with the same numbers every way.
// The entry point for every command with a list of independent model runs: validate (each
// condition of an expensive model, with or without effects), the diagnosis with a DEM baseline
// (the baseline runs, the confirmation runs, signature runs per candidate effect and condition).
//
//   std::vector<validation::ModelRun> runs;
//   for (const Station& st : dataset.stations) runs.push_back({dem, st, effects});
//   validation::run_models(runs);   // collective: every rank calls it with the same list
//   dem->predict(st, effects, request);  // afterwards: no run, the campaign's result
//
// Runs of models that answer at once (no campaign_jobs), runs whose result this process already
// holds and repeated runs are left out, so a caller can list everything it will predict.
#include <span>
#include <string>
#include <vector>

#include "analytical/effect.h"
#include "core/rig.h"
#include "validation/model.h"

namespace chutelab::validation {

struct ModelRun {
  ModelPtr model;
  Station station;
  analytical::EffectList effects;
  std::string file;  // where a bad-input error of this run is located (e.g. conditions.csv), optional
  long line = 0;
  // What the prediction will ask for: a signature run (a cheaper quality) and whether its
  // discretisation ladder is wanted too (its runs join the campaign).
  bool signature = false;
  bool discretisation = true;
};

struct RunModelsOptions {
  std::string label = "runs";  // prefix of the campaign's progress lines
  int jobs = 0;                // runs side by side in this process (campaign::Options::threads); 0 or 1: in order
  // What the runs are for, said once before they start ("": nothing said), so that a user who
  // waits for a diagnosis's fifth set of runs knows what each set is.
  std::string purpose;
};

// Throws the first failing run's InputError (in list order) on every rank.
void run_models(std::span<const ModelRun> runs, const RunModelsOptions& options = {});

}  // namespace chutelab::validation
