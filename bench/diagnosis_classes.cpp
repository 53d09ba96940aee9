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
#include <tuple>

#include "core/units.h"
#include "effects/at_condition.h"
#include "effects/registry.h"
#include "validation/diagnosis.h"
#include "validation/parallel_runs.h"
#include "validation/synthesize.h"

using namespace chutelab;
using namespace chutelab::validation;

namespace {

struct Tally {
  int runs = 0, named_truth = 0, named_other = 0, out_of_range = 0, consistent = 0, outside_library = 0, partial = 0;
  int confident_wrong = 0, shape_said = 0, twin_said = 0;
  int covered = 0, covered_of = 0;
  int outlier_named = 0, model_form_named = 0, thin = 0, scale_flagged = 0, record_differs = 0;
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
  // The explanation that should be named, in any order (empty: none).
  std::vector<std::string> expect;
  std::uint64_t seed = 9100;
  // The true errors of a record altered by alter_rig, in the candidates' units (for the coverage).
  std::vector<std::pair<std::string, double>> record = {};
  // Hidden physics the library does not have in this form (a drag linear in speed).
  analytical::EffectList foreign = {};
  const Dataset* design_data = nullptr;  // a design made in memory instead of `design`
};

bool same_causes(std::vector<std::string> a, std::vector<std::string> b) {
  std::sort(a.begin(), a.end());
  std::sort(b.begin(), b.end());
  return a == b;
}

std::vector<std::string> causes_of(const std::string& label) {
  std::vector<std::string> out;
  for (std::size_t at = 0; at <= label.size();) {
    const auto next = label.find(" + ", at);
    out.push_back(label.substr(at, next == std::string::npos ? std::string::npos : next - at));
    if (next == std::string::npos) break;
    at = next + 3;
  }
  return out;
}

// The verdict names `expect` as about as good as what it named, or one of the named causes' twins
// (moves the data in proportion) makes it so: the truth is said, though not as the pick.
// The record wrong at one condition that a reading left out as an outlier would mean instead, when
// it is the truth: the verdict says it beside the reading.
const EffectFit* record_for_reading(const DiagnosisResult& r, const std::vector<std::string>& expect) {
  for (const auto& o : r.outliers)
    for (const auto& f : o.records)
      if (same_causes(f.effects, expect)) return &f;
  return nullptr;
}

bool truth_said(const DiagnosisResult& r, const std::vector<std::string>& expect) {
  if (!expect.empty() && record_for_reading(r, expect)) return true;
  const EffectFit* b = r.best();
  if (!b || expect.empty()) return false;
  for (const auto& l : r.indistinguishable)
    if (same_causes(causes_of(l), expect)) return true;
  for (const auto& t : r.ties)
    for (auto [from, to] : {std::pair{t.a, t.b}, std::pair{t.b, t.a}}) {
      if (same_causes(causes_of(to), expect)) return true;
      auto swapped = b->effects;
      for (auto& e : swapped)
        if (e == from) e = to;
      if (same_causes(swapped, expect)) return true;
    }
  return false;
}

// Drag proportional to the speed, not its square: a = -k v, with k chosen so that at `speed` it
// decelerates as air drag of coefficient `cd` does (a cause the library has in another shape).
class LinearDrag final : public analytical::Effect {
 public:
  LinearDrag(double cd, double speed) : cd_(cd), speed_(speed) {}
  std::string name() const override { return "linear_drag"; }
  bool has_flight_force() const override { return true; }
  Eigen::Vector2d flight_acceleration(const Eigen::Vector2d& v, const analytical::FlightContext& c) const override {
    const double k = 3.0 * 1.204 * cd_ / (4.0 * c.solid_density * c.particle_diameter) * speed_;
    return -k * v;
  }

 private:
  double cd_, speed_;
};

Tally run(const Case& c, int n) {
  const auto design = c.design_data ? *c.design_data : read_dataset(c.design);
  std::vector<ModelPtr> models;
  for (const auto& m : model_names())
    if (auto p = make_model(m); !p->expensive()) models.push_back(p);
  SynthesizeOptions so;
  for (const auto& [name, v] : c.truth) so.effects.push_back(effects::find_candidate(name)->make(v));
  for (const auto& e : c.foreign) so.effects.push_back(e);
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
  // DIAGNOSIS_SHOW=<part of a class name>: the first replica's diagnosis of that class, in full (with
  // DIAGNOSIS_SHOW_MISSED=1 the first that did not name the truth, with DIAGNOSIS_SHOW_REPLICA=k the k-th).
  if (const char* show = std::getenv("DIAGNOSIS_SHOW"); show && c.name.find(show) != std::string::npos && n > 0) {
    std::size_t k = 0;
    if (std::getenv("DIAGNOSIS_SHOW_MISSED"))
      while (k + 1 < results.size() && results[k].best() && same_causes(results[k].best()->effects, c.expect)) ++k;
    if (const char* at = std::getenv("DIAGNOSIS_SHOW_REPLICA")) k = std::min(results.size() - 1, std::strtoul(at, nullptr, 10));
    std::fprintf(stderr, "replica %zu:\n%s\n", k, diagnosis_markdown(results[k]).c_str());
  }
  Tally t;
  for (const auto& r : results) {
    ++t.runs;
    const EffectFit* b = r.best();
    if (b && same_causes(b->effects, c.expect)) ++t.named_truth;
    else if (b) ++t.named_other, ++t.others[b->label()];
    const bool said = !(b && same_causes(b->effects, c.expect)) && truth_said(r, c.expect);
    t.twin_said += said;
    t.confident_wrong += b && !same_causes(b->effects, c.expect) && !said && r.verdict_code == Verdict::missing_effect;
    t.shape_said += !r.shape.empty();
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
        if (!judged && !c.expect.empty() && same_causes(f.effects, c.expect)) judged = &f;
    if (!judged && !c.expect.empty()) judged = record_for_reading(r, c.expect);
    // Each true strength on its own (an explanation by two causes counts two).
    if (judged)
      for (std::size_t k = 0; k < judged->estimate.size(); ++k)
        for (const auto* list : {&c.truth, &c.record})
          for (const auto& [name, v] : *list)
            if (name == judged->effects[k]) {
              ++t.covered_of;
              t.covered += std::abs(judged->estimate[k] - v) <= 2.0 * judged->uncertainty[k] ? 1 : 0;
            }
    t.outlier_named += r.outliers.empty() ? 0 : 1;
    t.model_form_named += r.model_form.empty() ? 0 : 1;
    t.thin += r.thin_data ? 1 : 0;
    t.record_differs += r.record_scope && r.record_scope->differs ? 1 : 0;
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
  auto alter = [](std::function<void(Station&)> f) {
    return [f](std::vector<Station>& s) {
      for (auto& st : s) f(st);
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
      {"plate 25 mm further than recorded", rig, {}, 1.0, 0, plate_further(0.025), {}, {"plate_distance"}, 10040, {{"plate_distance", 25.0}}},
      {"plate leaning 4 deg more than recorded", rig, {}, 1.0, 0, alter([](Station& s) { s.plate.angle += 4.0 * units::deg; }), {}, {"plate_angle"}, 11000, {{"plate_angle", 4.0}}},
      {"plate top 25 mm higher than recorded", rig, {}, 1.0, 0, alter([](Station& s) { s.plate_top += 0.025; }), {}, {"plate_top"}, 11020, {{"plate_top", 25.0}}},
      {"belt 5 % faster than recorded", rig, {}, 1.0, 0, alter([](Station& s) { s.belt_speed *= 1.05; }), {}, {"belt_speed"}, 11040, {{"belt_speed", 5.0}}},
      {"bulk density 10 % above the record", rig, {}, 1.0, 0, alter([](Station& s) { s.material.bulk_density *= 1.1; }), {}, {"bulk_density"}, 11060, {{"bulk_density", 10.0}}},
      {"pulley lagging: diameter 25 mm more than recorded", rig, {}, 1.0, 0, alter([](Station& s) { s.belt.pulley_diameter += 0.025; }), {}, {"pulley_diameter"}, 11080, {{"pulley_diameter", 25.0}}},
      {"plate 25 mm further, noise 2x stated", rig, {}, 2.0, 0, plate_further(0.025), {}, {"plate_distance"}, 11100, {{"plate_distance", 25.0}}},
      {"one condition's plate 40 mm further than recorded", rig, {}, 1.0, 0,
       [](std::vector<Station>& s) { s[3].plate_distance += 0.040; }, {}, {"plate_distance@V3-41"}, 11140,
       {{"plate_distance@V3-41", 40.0}}},
      {"belt incline 3 deg off (no candidate)", rig, {}, 1.0, 0, alter([](Station& s) { s.belt.incline += 3.0 * units::deg; }), {}, {}, 11120},
      {"flow bias 0.1 + one gross outlier (peer design)", peer, {{"mass_flow_bias", 0.1}}, 1.0, 1, {}, {}, {"mass_flow_bias"}, 10060},
      {"drag 0.6 + one gross outlier", rig, {{"air_drag", 0.6}}, 1.0, 1, {}, {}, {"air_drag"}, 10080},
      {"drag 0.6 + Korzen R_s 30 % off", rig, {{"air_drag", 0.6}}, 1.0, 0, {}, scale_rs(1.3), {"air_drag"}, 10100},
      {"drag 0.6, two conditions", rig, {{"air_drag", 0.6}}, 1.0, 0, {}, thin, {"air_drag"}, 10120},
  };
  for (const auto& e : effects::library())
    cases.push_back({fmt::format("{} {} (typical), honest noise", e.name, e.typical), rig, {{e.name, e.typical}}, 1.0, 0, {},
                     {}, {e.name}, 10200 + 20 * static_cast<std::uint64_t>(&e - effects::library().data())});
  // Several causes at once (issue: the diagnosis explains the whole rig), on the reference rig and on
  // a twelve-condition design made from it (four more belt speeds and flows).
  static const Dataset twelve = [&] {
    Dataset d = read_dataset(rig);
    const std::vector<std::tuple<std::string, double, double, double>> more = {
        {"V2.5-35", 2.5, 35.0, 0.35}, {"V3.5-33", 3.5, 33.0, 0.40}, {"V4.5-36", 4.5, 36.0, 0.45}, {"V6-40", 6.0, 40.0, 0.55}};
    const std::string like = "V3-41";
    for (const auto& [name, v, tph, z] : more) {
      Station st = d.stations[3];
      st.condition = name, st.belt_speed = v, st.mass_flow = tph / 3.6, st.plate_distance = z;
      d.stations.push_back(st);
      d.station_lines.push_back(d.station_lines[3]);
      if (d.input_uncertainty.size() > 3) d.input_uncertainty.push_back(d.input_uncertainty[3]);
      for (std::size_t i = 0, n = d.measurements.size(); i < n; ++i)
        if (d.measurements[i].condition == like) {
          auto m = d.measurements[i];
          m.condition = name;
          d.measurements.push_back(m);
        }
      for (std::size_t i = 0, n = d.trajectory.size(); i < n; ++i)
        if (d.trajectory[i].condition == like) {
          auto t = d.trajectory[i];
          t.condition = name;
          d.trajectory.push_back(t);
        }
    }
    return d;
  }();
  auto two_records = [](std::vector<Station>& s) {
    for (auto& st : s) st.belt_speed *= 0.96, st.plate_distance += 0.015;
  };
  auto moved = [](double dx) {
    return [dx](std::vector<Station>& s) {
      for (auto& st : s) st.plate_distance += dx;
    };
  };
  std::vector<Case> several = {
      {"two records: belt 4 % slower and plate 15 mm further", rig, {}, 1.0, 0, two_records, {}, {"belt_speed", "plate_distance"}, 12000,
       {{"belt_speed", -4.0}, {"plate_distance", 15.0}}},
      {"two records: belt 4 % slower and plate 15 mm further (12 conditions)", rig, {}, 1.0, 0, two_records, {},
       {"belt_speed", "plate_distance"}, 12020, {{"belt_speed", -4.0}, {"plate_distance", 15.0}}, {}, &twelve},
      {"record + physics: drag 0.45 and plate 15 mm further", rig, {{"air_drag", 0.45}}, 1.0, 0, moved(0.015), {},
       {"air_drag", "plate_distance"}, 12040, {{"plate_distance", 15.0}}},
      {"weak physical pair: drag 0.45 and belt slip 0.05", rig, {{"air_drag", 0.45}, {"belt_slip", 0.05}}, 1.0, 0, {}, {},
       {"air_drag", "belt_slip"}, 12060},
      {"weak physical pair: drag 0.45 and belt slip 0.05 (12 conditions)", rig, {{"air_drag", 0.45}, {"belt_slip", 0.05}}, 1.0, 0,
       {}, {}, {"air_drag", "belt_slip"}, 12080, {}, {}, &twelve},
      {"another shape: drag linear in speed (C_d 0.6 at 3.5 m/s)", rig, {}, 1.0, 0, {}, {}, {}, 12100, {},
       {std::make_shared<LinearDrag>(0.6, 3.5)}},
      {"another shape: drag linear in speed (12 conditions)", rig, {}, 1.0, 0, {}, {}, {}, 12120, {},
       {std::make_shared<LinearDrag>(0.6, 3.5)}, &twelve},
      {"height datum: every height 6 mm high", rig, {{"height_datum", 6.0}}, 1.0, 0, {}, {}, {"height_datum"}, 12140},
  };
  for (auto& c : several) cases.push_back(std::move(c));
  // A record wrong at one condition only, each input at three times its typical error (within its range).
  for (const auto& e : effects::library()) {
    if (e.kind != effects::EffectInfo::Kind::record) continue;
    const double v = std::min(3.0 * e.typical, 0.8 * e.upper);
    const std::string name = e.name + "@V4-41";
    cases.push_back({fmt::format("{} {:g} at V4-41 alone", e.name, v), rig, {{name, v}}, 1.0, 0, {}, {}, {name},
                     13000 + 20 * static_cast<std::uint64_t>(&e - effects::library().data())});
  }
  fmt::print("| class | replicas | named the truth | named another | out of range | partial | outside library | "
             "consistent | ±2 sd covers (each true strength) | outlier named | model form named | scale flagged | thin | record differs by condition "
             "| truth said beside (as about as good, or for a reading) | wrong and confident | shape said |\n");
  fmt::print("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  const char* show = std::getenv("DIAGNOSIS_SHOW");
  for (const auto& c : cases) {
    if (show && c.name.find(show) == std::string::npos) continue;
    const bool null = c.name.rfind("null", 0) == 0;
    const Tally t = run(c, null ? n_null : n);
    std::string others;
    for (const auto& [k, v] : t.others) others += fmt::format(" {}×{}", v, k);
    fmt::print("| {} | {} | {} | {}{} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} |\n", c.name, t.runs,
               c.expect.empty() ? "–" : fmt::format("{}", t.named_truth), t.named_other, others, t.out_of_range, t.partial,
               t.outside_library, t.consistent, t.covered_of ? fmt::format("{}/{}", t.covered, t.covered_of) : "–",
               t.outlier_named, t.model_form_named, t.scale_flagged, t.thin, t.record_differs, t.twin_said,
               t.confident_wrong, t.shape_said);
    std::fflush(stdout);
  }
  return 0;
}
