#pragma once
// The models' misfit to a dataset as a function of candidate effect strengths: the cost function
// of the diagnosis and of `--effect NAME=fit`. Each measured value (quantities and trajectory points
// with a stated uncertainty) is compared with the first model, in the order given, that predicts
// it: with the default order booth-cema,korzen the trajectory, impact point and V_p come from
// Booth/CEMA and the forces and V_a from Korzen, the reference study's hybrid. The misfit is a pure
// function of the strengths: the predictions and their runs come from a PredictionSource.
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "effects/registry.h"
#include "validation/dataset.h"
#include "validation/model.h"
#include "validation/prediction_source.h"

namespace chutelab::validation {

struct MisfitPoint {
  std::size_t condition = 0;     // index into the dataset's stations
  std::string quantity;          // boundary name (trajectory points: trajectory_<b>_y_mm)
  std::optional<Quantity> q;
  std::size_t query = 0;         // trajectory query index within the condition
  std::size_t model = 0;         // index of the model that predicts it
  std::size_t group = 0;         // index into Misfit::groups(): one per model and quantity
  double measured = 0.0, uncertainty = 0.0;  // SI; u_val of V&V 20 (u_D, u_num, u_input)
  double stated = 0.0;           // SI, u_D alone: what the dataset states for the reading
  SourceLine where;              // the reading's line in the dataset
};

// The points of one quantity as predicted by one model (the unit a discrepancy is fitted for).
struct MisfitGroup {
  std::string quantity;          // boundary name
  std::size_t model = 0;
  std::vector<std::size_t> points;
};

// A part of the misfit: the points of some conditions. A condition's points depend on its own
// predictions only, so a part costs what its conditions cost, not what the dataset does.
struct MisfitPart {
  std::vector<std::size_t> conditions;  // ascending
  std::vector<std::size_t> rows;        // the points of those conditions, ascending
  // The positions in `rows` of conditions[k]'s points: by_condition[begin[k] .. begin[k + 1]).
  std::vector<std::size_t> begin, by_condition;
};

class Misfit {
 public:
  // Points the baseline (fixed effects only) cannot predict, or without uncertainty, are left out.
  explicit Misfit(std::shared_ptr<const PredictionSource> source);
  // The same over a source of its own.
  Misfit(const Dataset& d, std::vector<ModelPtr> models, analytical::EffectList fixed = {}, int threads = 1);

  std::size_t size() const { return points_.size(); }
  const std::vector<MisfitPoint>& points() const { return points_; }
  const std::vector<MisfitGroup>& groups() const { return groups_; }
  int left_out() const { return left_out_; }
  const Dataset& dataset() const { return source_->dataset(); }
  const std::vector<ModelPtr>& models() const { return source_->models(); }
  const PredictionSource& source() const { return *source_; }

  // (prediction - measurement) / uncertainty for every point, expensive models by their
  // signatures. A strength at which a model cannot handle a condition (the stream misses the
  // plate, ...) gives a large misfit, not an error.
  std::vector<double> residuals(std::span<const effects::EffectInfo* const> fx,
                                std::span<const double> strengths) const;
  // The same for a part's points alone (one residual per part row), from its conditions alone.
  std::vector<double> residuals(std::span<const effects::EffectInfo* const> fx, std::span<const double> strengths,
                                const MisfitPart& part) const;
  MisfitPart part(std::vector<std::size_t> conditions) const;
  // The same from real runs of the expensive models (PredictionSource::prepare_exact runs them).
  std::vector<double> residuals_exact(std::span<const effects::EffectInfo* const> fx,
                                      std::span<const double> strengths) const;
  std::vector<double> residuals_of(const Predictions& predictions) const;
  double chi2(std::span<const effects::EffectInfo* const> fx, std::span<const double> strengths) const;
  // Each point's predicted value (SI) with these effects; absent where the models cannot say.
  std::vector<std::optional<double>> predicted(std::span<const effects::EffectInfo* const> fx,
                                               std::span<const double> strengths) const;

  // The misfit of a model that predicts nothing useful: large but finite, so that a minimiser can
  // still step back. A point's residual at a strength where the rig has no answer (the stream
  // misses the plate) is this beyond its residual without candidates, so that such a trial is
  // worse than the models as they are under any weights: a fixed residual would beat a baseline
  // whose own residuals are larger (forces recorded in kN under N columns), the fit would settle
  // where the rig is impossible, and that candidate's problem would surface as the dataset's.
  static constexpr double kInfeasible = 1e3;

 private:
  double residual(const Predictions& pred, std::size_t i) const;
  // Point i's residual from its own condition's predictions.
  double residual(const std::vector<ModelPrediction>& condition, std::size_t i) const;

  std::shared_ptr<const PredictionSource> source_;
  std::vector<MisfitPoint> points_;
  std::vector<MisfitGroup> groups_;
  // The points of condition c: by_condition_[condition_begin_[c] .. condition_begin_[c + 1]).
  std::vector<std::size_t> condition_begin_, by_condition_;
  int left_out_ = 0;
  std::vector<double> infeasible_;  // per point: kInfeasible + |its residual without candidates|
};

// What a fit minimises: the misfit's residuals, each multiplied by a weight (1 / the factor its
// uncertainty is widened by; 0 leaves the point out). Empty weights: every point counts as stated.
class Cost {
 public:
  explicit Cost(const Misfit& m, std::vector<double> weights = {});
  // The same cost over the points of these conditions alone: where a strength moves only their
  // predictions (one condition's recorded input), a fit of it reads them and nothing else.
  Cost only(std::vector<std::size_t> conditions) const;
  const Misfit& misfit() const { return *m_; }
  // The conditions whose points it reads (ascending), and the condition of each row.
  std::vector<std::size_t> conditions() const;
  std::size_t condition_of_row(std::size_t row) const { return m_->points()[part_ ? part_->rows[row] : row].condition; }
  const std::vector<double>& weights() const { return w_; }  // of every point of the misfit
  std::size_t rows() const { return part_ ? part_->rows.size() : m_->size(); }  // residuals() gives one per row
  std::size_t size() const { return counted_; }  // rows that count
  std::vector<double> residuals(std::span<const effects::EffectInfo* const> fx, std::span<const double> strengths) const;
  std::vector<double> weighted(std::vector<double> residuals) const;
  double chi2(std::span<const effects::EffectInfo* const> fx, std::span<const double> strengths) const;
  double chi2_of(const std::vector<double>& residuals) const;  // unweighted residuals of the rows in, weighted chi^2 out

 private:
  double weight(std::size_t row) const { return w_[part_ ? part_->rows[row] : row]; }

  const Misfit* m_;
  std::vector<double> w_;
  std::shared_ptr<const MisfitPart> part_;  // null: every point
  std::size_t counted_ = 0;
};

}  // namespace chutelab::validation
