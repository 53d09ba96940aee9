#pragma once
// The models' misfit to a dataset as a function of effect strengths, and its minimisation.
// Each measured value (quantities and trajectory points with a stated uncertainty) is compared
// with the first model, in the order given, that predicts it: with the default order
// booth-cema,korzen the trajectory, impact point and V_p come from Booth/CEMA and the forces and
// V_a from Korzen, the seed's hybrid.
#include <functional>
#include <map>
#include <tuple>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "analytical/transfer_station.h"
#include "effects/registry.h"
#include "validation/dataset.h"
#include "validation/harness.h"
#include "validation/model.h"

namespace chutelab::validation {

struct MisfitPoint {
  std::size_t condition = 0;     // index into the dataset's stations
  std::string quantity;          // boundary name (trajectory points: trajectory_<b>_y_mm)
  std::optional<Quantity> q;
  std::size_t query = 0;         // trajectory query index within the condition
  std::size_t model = 0;         // index of the model that predicts it
  double measured = 0.0, uncertainty = 0.0;  // SI
};

class Misfit {
 public:
  // Points the baseline (fixed effects only) cannot predict, or without uncertainty, are left out.
  // `threads`: conditions predicted side by side when no model is expensive (the numbers do not
  // depend on it).
  Misfit(const Dataset& d, std::vector<ModelPtr> models, analytical::EffectList fixed = {}, int threads = 1);

  std::size_t size() const { return points_.size(); }
  const std::vector<MisfitPoint>& points() const { return points_; }
  int left_out() const { return left_out_; }
  const Dataset& dataset() const { return *d_; }
  const std::vector<ModelPtr>& models() const { return models_; }

  // (prediction - measurement) / uncertainty for every point. A strength at which a model cannot
  // handle a condition (the stream misses the plate, ...) gives a large misfit, not an error.
  std::vector<double> residuals(std::span<const effects::EffectInfo* const> fx,
                                std::span<const double> strengths) const;
  double chi2(std::span<const effects::EffectInfo* const> fx, std::span<const double> strengths) const;
  // Every model's prediction of every condition with these effects. An expensive model (DEM) is
  // run once without the candidate effects and shifted by the cheap models' response to them
  // (DESIGN.md §5); chi2_exact runs it with the effects instead, to confirm a winner.
  std::vector<std::vector<ModelPrediction>> predict_all(
      std::span<const effects::EffectInfo* const> fx, std::span<const double> strengths) const;
  bool has_expensive() const;

  // How an expensive model's prediction with a candidate effect is obtained.
  enum class Signature {
    none,          // no expensive model, or the effect acts on the measurement only (applied exactly)
    own_runs,      // the expensive model run with the effect on at a probe strength (its own response)
    cheap_models,  // the cheap models' response as a difference (DESIGN.md §5): it cannot represent it
  };
  Signature signature(const effects::EffectInfo& e) const;
  // The strength of the probe run that gives an expensive model's own signature of `e`.
  double probe_strength(const effects::EffectInfo& e) const;
  // Runs every probe run the candidates need (`jobs` at a time), so that fits find them ready.
  void prepare_signatures(std::span<const effects::EffectInfo* const> candidates, int jobs) const;
  // Runs the expensive models at these strengths for every condition (`jobs` at a time).
  void prepare_exact(std::span<const effects::EffectInfo* const> fx, std::span<const double> strengths,
                     int jobs) const;
  double chi2_exact(std::span<const effects::EffectInfo* const> fx, std::span<const double> strengths) const;

 private:
  enum class Evaluation { surrogate, exact };
  std::vector<std::vector<ModelPrediction>> predict(std::span<const effects::EffectInfo* const> fx,
                                                    std::span<const double> strengths, Evaluation how) const;
  std::vector<double> residuals_of(const std::vector<std::vector<ModelPrediction>>& pred) const;
  double chi2_of(const std::vector<std::vector<ModelPrediction>>& pred) const;
  const ModelPrediction& expensive_base(std::size_t condition, std::size_t model) const;
  // Every condition of the expensive models with these effects, run as one campaign
  // (validation/campaign_runs.h) before they are predicted one by one.
  // The expensive models' runs of every condition with each list of effects, as one campaign (MPI ranks,
  // --jobs): `discretisation` adds their ladders (the baseline), `signature` runs them at the
  // signature quality (probes).
  void run_expensive(std::span<const analytical::EffectList> lists, bool discretisation, bool signature = false) const;
  void run_expensive(const analytical::EffectList& effects, bool discretisation) const {
    run_expensive(std::span(&effects, 1), discretisation);
  }
  const ModelPrediction& cheap_base(std::size_t condition, const ModelPtr& model) const;
  const ModelPrediction& expensive_probe(std::size_t condition, std::size_t model, const effects::EffectInfo& e) const;
  // The expensive model without candidates, made the way its probe runs are (their reference).
  const ModelPrediction& signature_base(std::size_t condition, std::size_t model) const;
  const ModelPrediction& exact_run(std::size_t condition, std::size_t model, std::span<const effects::EffectInfo* const> fx,
                                   std::span<const double> strengths) const;
  // One candidate effect's shift of the expensive models at one condition and strength.
  struct Shift {
    bool active = false;  // false: the effect is neutral at this strength
    double strength = 0.0;
    std::vector<ModelPrediction> cheap_at_s, cheap_at_probe;  // per signature model, raw
    std::optional<double> value(const Misfit& m, std::size_t condition, std::size_t model, const effects::EffectInfo& e,
                                const std::function<std::optional<double>(const ModelPrediction&)>& pick) const;
  };
  Shift shift_of(std::size_t condition, const effects::EffectInfo& e, double strength) const;

  // Below this many conditions per thread, starting the threads costs more than they save.
  static constexpr std::size_t kConditionsPerThread = 64;

  const Dataset* d_;
  std::vector<ModelPtr> models_;
  analytical::EffectList fixed_;
  int threads_ = 1;
  // Per condition: what its analyses keep from one to the next (one fit evaluates hundreds).
  mutable std::vector<analytical::TransferMemo> memo_;
  std::vector<ModelPtr> signature_;  // cheap models whose response to an effect shifts an expensive one
  std::vector<std::vector<TrajectoryQuery>> queries_;
  std::vector<MisfitPoint> points_;
  int left_out_ = 0;
  mutable std::map<std::pair<std::size_t, std::size_t>, std::optional<ModelPrediction>> expensive_cache_;
  mutable std::map<std::pair<std::size_t, std::string>, std::optional<ModelPrediction>> cheap_cache_;
  // Probe runs of expensive models: (condition, model, effect name).
  mutable std::map<std::tuple<std::size_t, std::size_t, std::string>, std::optional<ModelPrediction>> probe_cache_;
  mutable std::map<std::string, Signature> signature_cache_;
  mutable std::map<std::string, double> probe_cache_strength_;
  mutable std::map<std::pair<std::size_t, std::size_t>, std::optional<ModelPrediction>> signature_base_cache_;
  // Exact runs with candidate effects: (condition, model, effects and strengths as text).
  mutable std::map<std::tuple<std::size_t, std::size_t, std::string>, std::optional<ModelPrediction>> exact_cache_;
};

struct StrengthFit {
  std::vector<double> estimate;     // boundary units
  std::vector<double> uncertainty;  // one sd from (J^T J)^-1; infinite where the data say nothing
  double chi2 = 0.0;
  bool converged = false;
};

// Minimise chi^2 over the strengths of `fx` within their physical ranges: a grid scan (effects
// with a threshold have no gradient at their neutral value) followed by GSL's trust-region
// least squares. `starts` (optional, one vector per start) adds starting points.
StrengthFit fit_strengths(const Misfit& m, std::span<const effects::EffectInfo* const> fx,
                          const std::vector<std::vector<double>>& starts = {});

}  // namespace chutelab::validation
