#include "validation/self_check.h"

#include <fmt/format.h>
#include <gsl/gsl_cdf.h>
#include <functional>
#include <thread>

#include "effects/registry.h"
#include "validation/output_files.h"
#include "validation/parallel_runs.h"
#include "validation/synthesize.h"

namespace chutelab::validation {
namespace {

// The one-sided upper confidence bound of a rate from k events in n trials (Clopper-Pearson).
double upper_bound(int k, int n, double confidence) {
  if (n == 0) return 1.0;
  if (k >= n) return 1.0;
  return gsl_cdf_beta_Pinv(confidence, k + 1.0, static_cast<double>(n - k));
}

bool names_any(const DiagnosisResult& r) {
  return r.best() || r.verdict_code == Verdict::out_of_range;
}

// The fit of `truth` in a replica's ranking (single or pair, whether named or not).
const EffectFit* fit_of(const DiagnosisResult& r, const std::vector<std::string>& truth) {
  for (const auto* list : {&r.singles, &r.pairs})
    for (const auto& f : *list)
      if (f.effects == truth) return &f;
  return nullptr;
}

}  // namespace

SelfCheckResult self_check(const Dataset& d, const DiagnosisResult& result, const SelfCheckOptions& opt) {
  check(opt.diagnose);
  SelfCheckResult out;
  std::vector<ModelPtr> models;
  for (const auto& n : model_names())
    if (auto m = make_model(n); !m->expensive()) {
      models.push_back(m);
      out.models.push_back(n);
    }
  analytical::EffectList truth;
  if (const EffectFit* b = result.best()) {
    out.truth = b->effects;
    out.truth_strength = b->estimate;
    for (std::size_t i = 0; i < b->effects.size(); ++i) truth.push_back(effects::find(b->effects[i])->make(b->estimate[i]));
  }
  DiagnoseOptions each = opt.diagnose;
  each.jobs = 1;  // the replicas go side by side instead
  each.progress = false;
  const int n = std::max(0, opt.replicas);
  std::vector<int> alarm(n, 0), named(n, 0), other(n, 0), covered(n, 0);
  std::vector<std::function<void()>> work;
  for (int i = 0; i < n; ++i) {
    work.push_back([&, i] {
      SynthesizeOptions so;
      so.seed = opt.seed + static_cast<std::uint64_t>(i);
      alarm[i] = names_any(diagnose(replica(d, models, so), models, each)) ? 1 : 0;
    });
    if (truth.empty()) continue;
    work.push_back([&, i] {
      SynthesizeOptions so;
      so.seed = opt.seed + static_cast<std::uint64_t>(n + i);
      so.effects = truth;
      const auto r = diagnose(replica(d, models, so), models, each);
      const EffectFit* b = r.best();
      named[i] = b && b->effects == out.truth ? 1 : 0;
      other[i] = names_any(r) && !named[i] ? 1 : 0;
      if (const EffectFit* f = fit_of(r, out.truth)) {
        bool all = true;
        for (std::size_t k = 0; k < f->estimate.size(); ++k)
          all = all && std::abs(f->estimate[k] - out.truth_strength[k]) <= 2.0 * f->uncertainty[k];
        covered[i] = all ? 1 : 0;
      }
    });
  }
  const int jobs = opt.diagnose.jobs > 0 ? opt.diagnose.jobs : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  run_concurrently(work, jobs);
  out.null_replicas = n;
  for (int i = 0; i < n; ++i) {
    out.false_alarms += alarm[i];
    if (truth.empty()) continue;
    ++out.effect_replicas;
    out.named += named[i], out.named_other += other[i], out.covered += covered[i];
  }
  out.false_alarm_upper = upper_bound(out.false_alarms, out.null_replicas, 0.95);
  return out;
}

std::string self_check_markdown(const SelfCheckResult& r, double alpha) {
  std::string o = "# chutelab self-check: what the verdict is worth for this rig\n\n";
  o += fmt::format("Replicas of this dataset's design (its conditions, measured values and stated uncertainties), "
                   "read anew from the analytical models ({}) plus noise of the stated size, and diagnosed as the data "
                   "were.\n\n",
                   fmt::join(r.models, ", "));
  o += fmt::format("- **False alarms**: {} of {} effect-free replicas named an effect ({:.1f} %; 95 % upper bound "
                   "{:.1f} %; the diagnosis aims at {:.0f} %).\n",
                   r.false_alarms, r.null_replicas, 100 * r.false_alarm_rate(), 100 * r.false_alarm_upper, 100 * alpha);
  if (r.truth.empty()) {
    o += "- The diagnosis named no effect, so there is no power or coverage to check: the replicas with an effect "
         "need one.\n";
    return o;
  }
  std::vector<std::string> t;
  for (std::size_t i = 0; i < r.truth.size(); ++i) t.push_back(fmt::format("{} = {:.4g}", r.truth[i], r.truth_strength[i]));
  o += fmt::format("- **Power**: with {} in the replicas, the diagnosis named it in {} of {} ({:.0f} %), and "
                   "named something else in {}.\n",
                   fmt::join(t, ", "), r.named, r.effect_replicas, 100 * r.power(), r.named_other);
  o += fmt::format("- **Coverage**: the printed ± 2 sd held the true strength in {} of {} ({:.0f} %; 95 % is what an "
                   "honest ± gives).\n",
                   r.covered, r.effect_replicas, 100 * r.coverage());
  return o;
}

std::string self_check_csv(const SelfCheckResult& r) {
  std::string o = "kind,replicas,named_truth,named_other,covered,rate\n";
  o += fmt::format("effect_free,{},0,{},,{}\n", r.null_replicas, r.false_alarms, csv_number(r.false_alarm_rate()));
  if (!r.truth.empty())
    o += fmt::format("with_{},{},{},{},{},{}\n", fmt::join(r.truth, "+"), r.effect_replicas, r.named, r.named_other,
                     r.covered, csv_number(r.power()));
  return o;
}

}  // namespace chutelab::validation
