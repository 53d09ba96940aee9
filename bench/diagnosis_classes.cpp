// How honest the diagnosis is when the data break its assumptions (bench/DIAGNOSIS.md): for each
// class of data a batch of replicas of two bundled designs is made in memory, diagnosed, and the
// verdicts, named effects and the coverage of the printed ± are counted.
//   build/bench/diagnosis_classes [replicas per class, default 20] [null replicas, default 200]
// Seeds 9100-9999 are this bench's own (the suite's blind tests use 7100-7199, other tests 61xx).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fmt/format.h>
#include <functional>
#include <map>
#include <set>
#include <thread>

#include "effects/registry.h"
#include "validation/diagnosis.h"
#include "validation/parallel_runs.h"
#include "validation/synthesize.h"

using namespace chutelab;
using namespace chutelab::validation;

namespace {

struct Tally {
  int runs = 0, named_truth = 0, named_other = 0, out_of_range = 0, consistent = 0, outside_library = 0, partial = 0;
  int covered = 0, covered_of = 0;
  int outlier_named = 0, model_form_named = 0, thin = 0, scale_flagged = 0;
  std::map<std::string, int> others;
};

struct Case {
  std::string name;
  std::string design;                  // dataset folder
  std::vector<std::pair<std::string, double>> truth;
  double noise_factor = 1.0;
  int outliers = 0;
  std::function<void(std::vector<Station>&)> alter_rig;  // what the rig really was (the record stays)
  std::function<void(Dataset&)> alter_data;             // after the readings (a model-form error)
  std::vector<std::string> expect;     // the explanation that should be named (empty: none)
  std::uint64_t seed = 9100;
};

Tally run(const Case& c, int n) {
  const auto design = read_dataset(c.design);
  std::vector<ModelPtr> models;
  for (const auto& m : model_names())
    if (auto p = make_model(m); !p->expensive()) models.push_back(p);
  SynthesizeOptions so;
  for (const auto& [name, v] : c.truth) so.effects.push_back(effects::find(name)->make(v));
  so.noise_factor = c.noise_factor;
  so.outliers = c.outliers;
  std::vector<Station> truth = design.stations;
  if (c.alter_rig) c.alter_rig(truth);
  std::vector<DiagnosisResult> results(n);
  std::vector<std::function<void()>> work;
  for (int i = 0; i < n; ++i)
    work.push_back([&, i] {
      SynthesizeOptions s = so;
      s.seed = c.seed + static_cast<std::uint64_t>(i);
      Dataset d = replica(design, models, s, c.alter_rig ? &truth : nullptr);
      if (c.alter_data) c.alter_data(d);
      DiagnoseOptions opt;
      opt.jobs = 1;
      results[i] = diagnose(d, models, opt);
    });
  run_concurrently(work, static_cast<int>(std::max(1u, std::thread::hardware_concurrency())));
  // DIAGNOSIS_SHOW=<part of a class name>: the first replica's diagnosis of that class, in full.
  if (const char* show = std::getenv("DIAGNOSIS_SHOW"); show && c.name.find(show) != std::string::npos && n > 0)
    std::fprintf(stderr, "%s\n", diagnosis_markdown(results[0]).c_str());
  Tally t;
  for (const auto& r : results) {
    ++t.runs;
    const EffectFit* b = r.best();
    if (b && b->effects == c.expect) ++t.named_truth;
    else if (b) ++t.named_other, ++t.others[b->label()];
    switch (r.verdict_code) {
      case Verdict::out_of_range: ++t.out_of_range; break;
      case Verdict::consistent: ++t.consistent; break;
      case Verdict::outside_library: ++t.outside_library; break;
      case Verdict::partial_explanation: ++t.partial; break;
      default: break;
    }
    // The printed ± of the truth's strengths: in the named fit when it holds the truth, else in the
    // truth's own fit in the ranking.
    auto holds = [&](const EffectFit& f) {
      for (const auto& e : c.expect)
        if (std::find(f.effects.begin(), f.effects.end(), e) == f.effects.end()) return false;
      return true;
    };
    const EffectFit* judged = b && holds(*b) ? b : nullptr;
    for (const auto* list : {&r.singles, &r.pairs})
      for (const auto& f : *list)
        if (!judged && !c.expect.empty() && f.effects == c.expect) judged = &f;
    if (judged) {
      ++t.covered_of;
      bool all = true;
      for (std::size_t k = 0; k < judged->estimate.size(); ++k)
        for (const auto& [name, v] : c.truth)
          if (name == judged->effects[k]) all = all && std::abs(judged->estimate[k] - v) <= 2.0 * judged->uncertainty[k];
      t.covered += all ? 1 : 0;
    }
    t.outlier_named += r.outliers.empty() ? 0 : 1;
    t.model_form_named += r.model_form.empty() ? 0 : 1;
    t.thin += r.thin_data ? 1 : 0;
    t.scale_flagged += (r.scale.applied || r.scale.too_large) ? 1 : 0;
  }
  return t;
}

}  // namespace

int main(int argc, char** argv) {
  const int n = argc > 1 ? std::atoi(argv[1]) : 20;
  const int n_null = argc > 2 ? std::atoi(argv[2]) : 200;
  const std::string src = CHUTELAB_SOURCE_DIR;
  const std::string rig = src + "/datasets/hidden-effect", peer = src + "/datasets/liggghts-rig";
  auto scale_rs = [](double f) {
    return [f](Dataset& d) {
      for (auto& m : d.measurements)
        if (m.quantity == Quantity::shear_force) m.value *= f;
    };
  };
  auto plate_further = [](double dx) {
    return [dx](std::vector<Station>& s) {
      for (auto& st : s) st.plate_distance += dx;
    };
  };
  auto thin = [](Dataset& d) {
    std::set<std::string> keep = {d.stations[0].condition, d.stations[1].condition};
    std::erase_if(d.measurements, [&](const auto& m) { return !keep.count(m.condition); });
    std::erase_if(d.trajectory, [&](const auto& m) { return !keep.count(m.condition); });
  };
  std::vector<Case> cases = {
      {"null, honest noise", rig, {}, 1.0, 0, {}, {}, {}, 9100},
      {"null, honest noise (peer design)", peer, {}, 1.0, 0, {}, {}, {}, 9300},
      {"null, noise 2x stated", rig, {}, 2.0, 0, {}, {}, {}, 9500},
      {"null, one gross outlier", rig, {}, 1.0, 1, {}, {}, {}, 9700},
      {"drag 0.6, honest noise", rig, {{"air_drag", 0.6}}, 1.0, 0, {}, {}, {"air_drag"}, 9900},
      {"drag 0.6, noise 2x stated", rig, {{"air_drag", 0.6}}, 2.0, 0, {}, {}, {"air_drag"}, 9920},
      {"drag 0.6, stated 2x the noise", rig, {{"air_drag", 0.6}}, 0.5, 0, {}, {}, {"air_drag"}, 9940},
      {"flow bias 0.1, noise 2x stated (peer design)", peer, {{"mass_flow_bias", 0.1}}, 2.0, 0, {}, {}, {"mass_flow_bias"}, 9960},
      {"drag -0.56 (wrong sign)", rig, {{"air_drag", -0.56}}, 1.0, 0, {}, {}, {}, 9980},
      {"drag -0.3 (wrong sign)", rig, {{"air_drag", -0.3}}, 1.0, 0, {}, {}, {}, 10000},
      {"slip -0.03 (wrong sign)", rig, {{"belt_slip", -0.03}}, 1.0, 0, {}, {}, {}, 10020},
      {"plate 25 mm further than recorded", rig, {}, 1.0, 0, plate_further(0.025), {}, {}, 10040},
      {"flow bias 0.1 + one gross outlier (peer design)", peer, {{"mass_flow_bias", 0.1}}, 1.0, 1, {}, {}, {"mass_flow_bias"}, 10060},
      {"drag 0.6 + one gross outlier", rig, {{"air_drag", 0.6}}, 1.0, 1, {}, {}, {"air_drag"}, 10080},
      {"drag 0.6 + Korzen R_s 30 % off", rig, {{"air_drag", 0.6}}, 1.0, 0, {}, scale_rs(1.3), {"air_drag"}, 10100},
      {"drag 0.6, two conditions", rig, {{"air_drag", 0.6}}, 1.0, 0, {}, thin, {"air_drag"}, 10120},
  };
  for (const auto& e : effects::library())
    cases.push_back({fmt::format("{} {} (typical), honest noise", e.name, e.typical), rig, {{e.name, e.typical}}, 1.0, 0, {},
                     {}, {e.name}, 10200 + 20 * static_cast<std::uint64_t>(&e - effects::library().data())});
  fmt::print("| class | replicas | named the truth | named another | out of range | partial | outside library | "
             "consistent | ±2 sd covers | outlier named | model form named | scale flagged | thin |\n");
  fmt::print("|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  const char* show = std::getenv("DIAGNOSIS_SHOW");
  for (const auto& c : cases) {
    if (show && c.name.find(show) == std::string::npos) continue;
    const bool null = c.name.rfind("null", 0) == 0;
    const Tally t = run(c, null ? n_null : n);
    std::string others;
    for (const auto& [k, v] : t.others) others += fmt::format(" {}×{}", v, k);
    fmt::print("| {} | {} | {} | {}{} | {} | {} | {} | {} | {} | {} | {} | {} | {} |\n", c.name, t.runs,
               c.expect.empty() ? "–" : fmt::format("{}", t.named_truth), t.named_other, others, t.out_of_range, t.partial,
               t.outside_library, t.consistent, t.covered_of ? fmt::format("{}/{}", t.covered, t.covered_of) : "–",
               t.outlier_named, t.model_form_named, t.scale_flagged, t.thin);
    std::fflush(stdout);
  }
  return 0;
}
