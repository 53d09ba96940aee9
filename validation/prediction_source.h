#pragma once
// Where a diagnosis's predictions come from: every model's prediction of every condition with
// candidate effects at trial strengths. The source owns the runs. The analytical chain keeps a memo
// per condition (a fit evaluates it hundreds of times); an expensive model (the DEM) is run once per
// condition without candidates, and its response to a candidate is either its own probe run carried
// to the trial strength or the cheap models' response applied as a difference (DESIGN.md §5). Those
// runs are cached here and started as campaigns (MPI ranks, --jobs), so that the cost function
// built on the source (validation/misfit.h) stays a pure function of the strengths.
#include <functional>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <tuple>
#include <vector>

#include "analytical/transfer_station.h"
#include "effects/registry.h"
#include "validation/dataset.h"
#include "validation/harness.h"
#include "validation/model.h"

namespace chutelab::validation {

using Predictions = std::vector<std::vector<ModelPrediction>>;  // [condition][model]

class PredictionSource {
 public:
  // Runs the expensive models' baselines (and their discretisation ladders) as one campaign.
  // `threads`: conditions predicted side by side when no model is expensive (the numbers do not
  // depend on it).
  PredictionSource(const Dataset& d, std::vector<ModelPtr> models, analytical::EffectList fixed = {},
                   int threads = 1);

  const Dataset& dataset() const { return *d_; }
  const std::vector<ModelPtr>& models() const { return models_; }
  const analytical::EffectList& fixed() const { return fixed_; }
  std::span<const TrajectoryQuery> queries(std::size_t condition) const { return queries_[condition]; }
  bool has_expensive() const;
  // An expensive model that can be re-run with candidate effects (a DEM; not another code's export).
  bool reruns_expensive() const;

  // How an expensive model's prediction with a candidate effect is obtained.
  enum class Signature {
    none,          // no expensive model, or the effect acts on the measurement only (applied exactly)
    own_runs,      // the expensive model run with the effect on at a probe strength (its own response)
    cheap_models,  // the cheap models' response as a difference (DESIGN.md §5): it cannot represent it
  };
  Signature signature(const effects::EffectInfo& e) const;
  // The strength of the probe run that gives an expensive model's own signature of `e`.
  double probe_strength(const effects::EffectInfo& e) const;

  // Every model's prediction of every condition with these effects: expensive models by their
  // signatures (`surrogate`) or by real runs at these strengths (`exact`, run on demand; call
  // prepare_exact first to run them as one campaign). `only`: these conditions alone (the others'
  // slots stay empty), for a cost that reads a part of the dataset; empty: every condition.
  enum class Evaluation { surrogate, exact };
  Predictions predict(std::span<const effects::EffectInfo* const> fx, std::span<const double> strengths,
                      Evaluation how = Evaluation::surrogate, std::span<const std::size_t> only = {}) const;

  // Each condition's predictions (those of `only`, or of every condition), as predict() makes them,
  // handed to `use` by the thread that made them and dropped there. A fit reads a few numbers of each
  // and keeps none: ten thousand conditions' predictions, made on the workers and freed on the
  // caller's thread, cost a quarter of a large diagnosis in the allocator (bench/log/SCALE.md). `use`
  // may run on several threads at once, for different conditions. Fails as predict() does.
  using ConditionUse = std::function<void(std::size_t condition, const std::vector<ModelPrediction>&)>;
  void visit(std::span<const effects::EffectInfo* const> fx, std::span<const double> strengths, Evaluation how,
             std::span<const std::size_t> only, const ConditionUse& use) const;

  // Runs every probe run the candidates need (`jobs` at a time), so that fits find them ready.
  void prepare_signatures(std::span<const effects::EffectInfo* const> candidates, int jobs) const;
  // Runs the expensive models at these strengths for every condition (`jobs` at a time).
  // `why`: what the runs are for, said before they start with the strengths they run at.
  void prepare_exact(std::span<const effects::EffectInfo* const> fx, std::span<const double> strengths,
                     int jobs, const std::string& why = {}) const;

 private:
  analytical::EffectList with(std::span<const effects::EffectInfo* const> fx, std::span<const double> strengths) const;
  void predict_condition(std::size_t c, const analytical::EffectList& list,
                         std::span<const effects::EffectInfo* const> fx, std::span<const double> strengths,
                         Evaluation how, bool reuse_raw, std::vector<ModelPrediction>& out) const;
  // Predicts the conditions of `only` (empty: all), side by side where they may be, and hands each
  // condition's predictions to `take` on the thread that made them (predict and visit).
  void for_conditions(std::span<const effects::EffectInfo* const> fx, std::span<const double> strengths, Evaluation how,
                      std::span<const std::size_t> only,
                      const std::function<void(std::size_t, std::vector<ModelPrediction>&)>& take) const;
  // Every model's prediction of a condition before the measurement effects act.
  std::vector<ConditionResult> raw_condition(std::size_t c, const analytical::EffectList& list,
                                             std::span<const effects::EffectInfo* const> fx,
                                             std::span<const double> strengths, Evaluation how) const;
  // The candidates act on the measurement alone (EffectInfo::stage "measurement", checked once per
  // effect on the first condition: its raw prediction with the effect is the one without), so the
  // raw predictions with the fixed effects serve every strength of theirs.
  bool on_measurement_only(std::span<const effects::EffectInfo* const> fx) const;
  // The expensive models' runs of every condition with each list of effects, as one campaign:
  // `discretisation` adds their ladders (the baseline), `signature` runs them at the signature
  // quality (probes).
  void run_expensive(std::span<const analytical::EffectList> lists, bool discretisation, bool signature,
                     const std::string& purpose) const;
  const ModelPrediction& expensive_base(std::size_t condition, std::size_t model) const;
  const ModelPrediction& cheap_base(std::size_t condition, const ModelPtr& model) const;
  const ModelPrediction& expensive_probe(std::size_t condition, std::size_t model, const effects::EffectInfo& e) const;
  // The expensive model without candidates, made the way its probe runs are (their reference).
  const ModelPrediction& signature_base(std::size_t condition, std::size_t model) const;
  struct RunPart {
    std::vector<const effects::EffectInfo*> fx;
    std::vector<double> strengths;
  };
  RunPart run_part(std::span<const effects::EffectInfo* const> fx, std::span<const double> strengths) const;
  const ModelPrediction& exact_run(std::size_t condition, std::size_t model, std::span<const effects::EffectInfo* const> fx,
                                   std::span<const double> strengths) const;
  // One value of a prediction: a quantity, or (no quantity) the trajectory query `query`.
  struct Value {
    std::optional<Quantity> q;
    std::size_t query = 0;
    std::optional<double> of(const ModelPrediction& mp) const;
    std::optional<double> sd_of(const ModelPrediction& mp) const;  // its statistical sd
  };
  // An expensive model's own response to an effect at its probe strength, per condition, each read
  // together with the other conditions' (validation/response_pooling.h); absent where the probe or
  // its base has no value.
  struct OwnResponse {
    std::vector<QuantityValues> values;                          // per condition
    std::vector<std::vector<std::optional<double>>> trajectory;  // per condition, per query
    std::vector<bool> failed;  // per condition: the probe run has no answer there
  };
  const OwnResponse& own_response(std::size_t model, const effects::EffectInfo& e) const;
  // The cheap models' shift of one value at a condition (`with`: their predictions there, one per
  // signature model): the first of them (registry order) that predicts it.
  std::optional<double> cheap_shift(std::size_t condition, std::span<const ModelPrediction> with, const Value& v) const;
  // One candidate effect's shift of the expensive models at one condition and strength.
  struct Shift {
    bool active = false;  // false: the effect is neutral at this strength
    double strength = 0.0;
    std::vector<ModelPrediction> cheap_at_s, cheap_at_probe;  // per signature model, raw
    std::optional<double> value(const PredictionSource& src, std::size_t condition, std::size_t model,
                                const effects::EffectInfo& e, const Value& v) const;
  };
  Shift shift_of(std::size_t condition, const effects::EffectInfo& e, double strength) const;

  // Below this many conditions per thread, starting the threads costs more than they save.
  static constexpr std::size_t kConditionsPerThread = 64;

  const Dataset* d_;
  std::vector<ModelPtr> models_;
  analytical::EffectList fixed_;
  int threads_ = 1;
  std::vector<std::vector<TrajectoryQuery>> queries_;
  std::vector<ModelPtr> signature_;  // cheap models whose response to an effect shifts an expensive one
  // The run cache. Per condition: what its analyses keep from one to the next.
  mutable std::vector<analytical::TransferMemo> memo_;
  mutable std::vector<std::optional<std::vector<ConditionResult>>> raw_fixed_;  // per condition, cheap models only
  mutable std::map<std::string, bool> measurement_only_;
  mutable std::map<std::pair<std::size_t, std::size_t>, std::optional<ModelPrediction>> expensive_cache_;
  mutable std::map<std::pair<std::size_t, std::string>, std::optional<ModelPrediction>> cheap_cache_;
  // Probe runs of expensive models: (condition, model, effect name).
  mutable std::map<std::tuple<std::size_t, std::size_t, std::string>, std::optional<ModelPrediction>> probe_cache_;
  mutable std::map<std::pair<std::size_t, std::string>, OwnResponse> own_response_cache_;
  mutable std::map<std::string, Signature> signature_cache_;
  mutable std::map<std::string, double> probe_strength_cache_;
  mutable std::map<std::pair<std::size_t, std::size_t>, std::optional<ModelPrediction>> signature_base_cache_;
  // Exact runs with candidate effects: (condition, model, effects and strengths as text).
  mutable std::map<std::tuple<std::size_t, std::size_t, std::string>, std::optional<ModelPrediction>> exact_cache_;
};

}  // namespace chutelab::validation
