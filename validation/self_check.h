#pragma once
// What a verdict is worth for this rig: the diagnosis run on replicas of the user's own dataset
// design (its conditions, its measured values, their stated uncertainties), read anew from the
// analytical models with the fitted explanation (or none) plus noise of the stated size. It gives
// this design's false-alarm rate, its power to name the explanation found, and how often the ± the
// diagnosis prints covers the strength that made the data.
#include <cstdint>
#include <string>
#include <vector>

#include "validation/dataset.h"
#include "validation/diagnosis.h"
#include "validation/model.h"

namespace chutelab::validation {

struct SelfCheckOptions {
  int replicas = 20;           // of each kind: effect-free, and with the explanation when there is one
  std::uint64_t seed = 1;      // replica i uses seed + i
  DiagnoseOptions diagnose;    // as the user's run (its jobs run replicas side by side)
  // Progress (core/progress.h): the cost said before the replicas start, from the time the user's
  // own diagnosis took (a replica's is about as long or shorter: analytical models alone), then the
  // replicas as they finish.
  bool progress = false;
  double seconds_per_diagnosis = 0.0;
};

struct SelfCheckResult {
  std::vector<std::string> models;     // the analytical models the replicas come from and are judged by
  // Effect-free replicas: the models as they are plus noise.
  int null_replicas = 0;
  int false_alarms = 0;                // an effect named (missing or partial), or out of range
  double false_alarm_upper = 0.0;      // one-sided 95 % upper bound of the rate (Clopper-Pearson)
  // Replicas with the recommended explanation at its fitted strengths.
  std::vector<std::string> truth;      // effect names; empty: the diagnosis named none
  std::vector<double> truth_strength;
  int effect_replicas = 0;
  int named = 0;                       // named exactly the truth
  int named_other = 0;                 // named another explanation
  int covered = 0;                     // every strength of the truth's fit within 2 printed sd of the truth
  double power() const { return effect_replicas ? static_cast<double>(named) / effect_replicas : 0.0; }
  double coverage() const { return effect_replicas ? static_cast<double>(covered) / effect_replicas : 0.0; }
  double false_alarm_rate() const { return null_replicas ? static_cast<double>(false_alarms) / null_replicas : 0.0; }
  // Replicas whose truth is a rival of the explanation named: the best explanation one cause larger
  // (when it was not significant) and the one a cause smaller or the runner-up single. A choice
  // between explanations is only as good as its rate of picking each when it is the truth.
  struct Rival {
    std::vector<std::string> truth;
    std::vector<double> truth_strength;
    int replicas = 0;
    int named = 0;          // named exactly this rival
    int named_chosen = 0;   // named the user's explanation instead
    int covered = 0;        // the rival's fit held its true strengths within 2 printed sd
  };
  std::vector<Rival> rivals;
};

// `result` is the user's diagnosis of `d` (its recommended explanation is the replicas' truth).
SelfCheckResult self_check(const Dataset& d, const DiagnosisResult& result, const SelfCheckOptions& options);

std::string self_check_markdown(const SelfCheckResult& r, double alpha);
std::string self_check_csv(const SelfCheckResult& r);

}  // namespace chutelab::validation
