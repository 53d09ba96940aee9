#include "validation/self_check.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <fmt/format.h>
#include <gsl/gsl_cdf.h>
#include <functional>
#include <memory>
#include <thread>

#include "core/progress.h"
#include "effects/at_condition.h"
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

bool same_causes(std::vector<std::string> a, std::vector<std::string> b) {
  std::sort(a.begin(), a.end());
  std::sort(b.begin(), b.end());
  return a == b;
}

// The fit of `truth` in a replica's ranking (single or several causes, whether named or not).
const EffectFit* fit_of(const DiagnosisResult& r, const std::vector<std::string>& truth) {
  for (const auto* list : {&r.singles, &r.pairs})
    for (const auto& f : *list)
      if (same_causes(f.effects, truth)) return &f;
  if (r.next_cause && same_causes(r.next_cause->effects, truth)) return &*r.next_cause;
  return nullptr;
}

// Every strength of the truth's fit within 2 printed sd of the truth.
bool covers(const EffectFit* f, const std::vector<std::string>& names, const std::vector<double>& truth) {
  if (!f) return false;
  for (std::size_t k = 0; k < f->estimate.size(); ++k)
    for (std::size_t i = 0; i < names.size(); ++i)
      if (f->effects[k] == names[i] && !(std::abs(f->estimate[k] - truth[i]) <= 2.0 * f->uncertainty[k])) return false;
  return true;
}

analytical::EffectList effects_of(const std::vector<std::string>& names, const std::vector<double>& strengths) {
  analytical::EffectList out;
  for (std::size_t i = 0; i < names.size(); ++i) out.push_back(effects::find_candidate(names[i])->make(strengths[i]));
  return out;
}

// The rivals of the named explanation: the best one a cause larger (not significant), and the one a
// cause smaller (several causes named) or else the runner-up single.
std::vector<SelfCheckResult::Rival> rivals_of(const DiagnosisResult& r) {
  std::vector<SelfCheckResult::Rival> out;
  const EffectFit* b = r.best();
  if (!b) return out;
  auto add = [&](const EffectFit& f) {
    if (same_causes(f.effects, b->effects)) return;
    for (const auto& o : out)
      if (same_causes(o.truth, f.effects)) return;
    out.push_back({f.effects, f.estimate});
  };
  if (r.next_cause) add(*r.next_cause);
  if (b->effects.size() > 1 && r.pairs.size() > 1) add(r.pairs[1]);
  else if (b->effects.size() > 1 && !r.singles.empty()) add(r.singles.front());
  else if (r.singles.size() > 1 && r.singles[1].significant) add(r.singles[1]);
  return out;
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
    truth = effects_of(b->effects, b->estimate);
  }
  out.rivals = rivals_of(result);
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
      so.effects = opt.diagnose.fixed;
      alarm[i] = names_any(diagnose(replica(d, models, so), models, each)) ? 1 : 0;
    });
    if (truth.empty()) continue;
    work.push_back([&, i] {
      SynthesizeOptions so;
      so.seed = opt.seed + static_cast<std::uint64_t>(n + i);
      so.effects = opt.diagnose.fixed;
      so.effects.insert(so.effects.end(), truth.begin(), truth.end());
      const auto r = diagnose(replica(d, models, so), models, each);
      const EffectFit* b = r.best();
      named[i] = b && same_causes(b->effects, out.truth) ? 1 : 0;
      other[i] = names_any(r) && !named[i] ? 1 : 0;
      covered[i] = covers(fit_of(r, out.truth), out.truth, out.truth_strength) ? 1 : 0;
    });
  }
  // Each rival as the truth: how often the diagnosis tells it from the explanation it named.
  std::vector<std::vector<std::array<int, 3>>> rival(out.rivals.size(), std::vector<std::array<int, 3>>(n));
  for (std::size_t k = 0; k < out.rivals.size(); ++k)
    for (int i = 0; i < n; ++i)
      work.push_back([&, k, i] {
        SynthesizeOptions so;
        so.seed = opt.seed + static_cast<std::uint64_t>((2 + k) * n + i);
        so.effects = opt.diagnose.fixed;
        for (auto& e : effects_of(out.rivals[k].truth, out.rivals[k].truth_strength)) so.effects.push_back(std::move(e));
        const auto r = diagnose(replica(d, models, so), models, each);
        const EffectFit* b = r.best();
        rival[k][i] = {b && same_causes(b->effects, out.rivals[k].truth) ? 1 : 0,
                       b && same_causes(b->effects, out.truth) ? 1 : 0,
                       covers(fit_of(r, out.rivals[k].truth), out.rivals[k].truth, out.rivals[k].truth_strength) ? 1 : 0};
      });
  const int jobs = opt.diagnose.jobs > 0 ? opt.diagnose.jobs : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  // Said before a request of hours starts, not discovered after it; then each replica as it ends
  // (a stop asked between replicas is seen by run_concurrently).
  if (opt.progress && !work.empty()) {
    progress::line(fmt::format("diagnose: self-check of up to {} replica diagnoses; this diagnosis took {:.1f} s, so "
                               "the self-check may take up to about {:.0f} min on {} thread{}",
                               work.size(), opt.seconds_per_diagnosis,
                               std::ceil(static_cast<double>(work.size()) / jobs) * opt.seconds_per_diagnosis / 60.0,
                               jobs, jobs == 1 ? "" : "s"));
    const auto started = std::chrono::steady_clock::now();
    auto done = std::make_shared<std::atomic<std::size_t>>(0);
    const std::size_t total = work.size();
    for (auto& w : work)
      w = [inner = std::move(w), done, total, started] {
        inner();
        const std::size_t k = done->fetch_add(1) + 1;
        const std::chrono::duration<double> spent = std::chrono::steady_clock::now() - started;
        progress::status_prefix(k == total ? "" : fmt::format("self-check: {}/{} replicas, {:.0f} s", k, total, spent.count()));
        if (k * 4 / total != (k - 1) * 4 / total)
          progress::line(fmt::format("diagnose: self-check {}/{} replicas done ({:.0f} s)", k, total, spent.count()));
      };
  }
  run_concurrently(work, jobs);
  out.null_replicas = n;
  for (int i = 0; i < n; ++i) {
    out.false_alarms += alarm[i];
    if (truth.empty()) continue;
    ++out.effect_replicas;
    out.named += named[i], out.named_other += other[i], out.covered += covered[i];
  }
  out.false_alarm_upper = upper_bound(out.false_alarms, out.null_replicas, 0.95);
  for (std::size_t k = 0; k < out.rivals.size(); ++k) {
    auto& rv = out.rivals[k];
    rv.replicas = n;
    for (const auto& [named_it, named_chosen, covered_it] : rival[k])
      rv.named += named_it, rv.named_chosen += named_chosen, rv.covered += covered_it;
  }
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
  for (const auto& rv : r.rivals) {
    std::vector<std::string> rt;
    for (std::size_t i = 0; i < rv.truth.size(); ++i) rt.push_back(fmt::format("{} = {:.4g}", rv.truth[i], rv.truth_strength[i]));
    o += fmt::format("- **If the truth were the rival {}**: the diagnosis named it in {} of {}, named {} (the "
                     "explanation it chose here) in {}, and its ± 2 sd held the rival's strengths in {}.\n",
                     fmt::join(rt, ", "), rv.named, rv.replicas, fmt::join(r.truth, " + "), rv.named_chosen, rv.covered);
  }
  if (!r.rivals.empty()) {
    int named = r.named, of = r.effect_replicas, covered = r.covered;
    for (const auto& rv : r.rivals) named += rv.named, of += rv.replicas, covered += rv.covered;
    o += fmt::format("- **Over the choice**: with the named explanation or a rival as the truth, the diagnosis named "
                     "the truth in {} of {} ({:.0f} %) and its ± 2 sd held the true strengths in {} ({:.0f} %).\n",
                     named, of, 100.0 * named / of, covered, 100.0 * covered / of);
  }
  return o;
}

std::string self_check_csv(const SelfCheckResult& r) {
  std::string o = "kind,replicas,named_truth,named_other,covered,rate\n";
  o += fmt::format("effect_free,{},0,{},,{}\n", r.null_replicas, r.false_alarms, csv_number(r.false_alarm_rate()));
  if (!r.truth.empty())
    o += fmt::format("with_{},{},{},{},{},{}\n", fmt::join(r.truth, "+"), r.effect_replicas, r.named, r.named_other,
                     r.covered, csv_number(r.power()));
  for (const auto& rv : r.rivals)
    o += fmt::format("rival_{},{},{},{},{},{}\n", fmt::join(rv.truth, "+"), rv.replicas, rv.named, rv.named_chosen,
                     rv.covered, csv_number(rv.replicas ? static_cast<double>(rv.named) / rv.replicas : 0.0));
  return o;
}

}  // namespace chutelab::validation
