#include "validation/misfit.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <unordered_map>

#include "core/input_error.h"
#include "validation/harness.h"
#include "validation/input_uncertainty.h"

namespace chutelab::validation {

Misfit::Misfit(const Dataset& d, std::vector<ModelPtr> models, analytical::EffectList fixed, int threads)
    : Misfit(std::make_shared<const PredictionSource>(d, std::move(models), std::move(fixed), threads)) {}

Misfit::Misfit(std::shared_ptr<const PredictionSource> source) : source_(std::move(source)) {
  const Dataset& d = source_->dataset();
  const auto& models = source_->models();
  std::unordered_map<std::string, std::size_t> index;
  for (std::size_t i = 0; i < d.stations.size(); ++i) index.emplace(d.stations[i].condition, i);
  const auto base = source_->predict({}, {});
  auto condition_index = [&](const std::string& c) {
    if (auto it = index.find(c); it != index.end()) return it->second;
    throw std::logic_error("measurement of an unknown condition");
  };
  // chi^2 weights: u_D combined with the baseline prediction's u_num (statistical and
  // discretisation parts) and u_input, as V&V 20's u_val.
  std::map<std::pair<std::size_t, std::size_t>, InputUncertaintyResult> u_input;
  auto input_part = [&](std::size_t ci, std::size_t k) -> const InputUncertaintyResult& {
    auto [it, fresh] = u_input.try_emplace({ci, k});
    if (fresh && ci < d.input_uncertainty.size() && !d.input_uncertainty[ci].empty())
      it->second = input_uncertainty(*models[k], d.stations[ci], d.input_uncertainty[ci], source_->fixed(),
                                     source_->queries(ci), base[ci][k]);
    return it->second;
  };
  auto weight = [](double u_d, std::initializer_list<std::optional<double>> parts) {
    double sum = u_d * u_d;
    for (const auto& u : parts) sum += std::pow(u.value_or(0.0), 2);
    return std::sqrt(sum);
  };
  std::map<std::pair<std::size_t, std::string>, std::size_t> group_of;
  auto add = [&](MisfitPoint p) {
    auto [it, fresh] = group_of.try_emplace({p.model, p.quantity}, groups_.size());
    if (fresh) groups_.push_back({p.quantity, p.model, {}});
    p.group = it->second;
    groups_[p.group].points.push_back(points_.size());
    points_.push_back(std::move(p));
  };
  for (const auto& m : d.measurements) {
    const std::size_t ci = condition_index(m.condition);
    std::optional<std::size_t> by;
    for (std::size_t k = 0; k < models.size() && !by; ++k)
      if (base[ci][k].values[m.quantity]) by = k;
    if (!by || !m.uncertainty) {
      ++left_out_;
      continue;
    }
    const ModelPrediction& b = base[ci][*by];
    const double u = weight(*m.uncertainty, {b.uncertainty[m.quantity], b.discretisation[m.quantity],
                                             input_part(ci, *by).u[m.quantity]});
    add({ci, std::string(name(m.quantity)), m.quantity, 0, *by, 0, m.value, u, *m.uncertainty, m.where});
  }
  std::vector<std::size_t> next(d.stations.size(), 0);
  for (const auto& p : d.trajectory) {
    const std::size_t ci = condition_index(p.condition);
    const std::size_t qi = next[ci]++;
    std::optional<std::size_t> by;
    for (std::size_t k = 0; k < models.size() && !by; ++k)
      if (qi < base[ci][k].trajectory.size() && base[ci][k].trajectory[qi]) by = k;
    if (!by || !p.uncertainty) {
      ++left_out_;
      continue;
    }
    const ModelPrediction& b = base[ci][*by];
    auto nth = [qi](const std::vector<std::optional<double>>& v) {
      return qi < v.size() ? v[qi] : std::nullopt;
    };
    const double u = weight(*p.uncertainty, {nth(b.trajectory_uncertainty), nth(b.trajectory_discretisation),
                                             nth(input_part(ci, *by).trajectory)});
    add({ci, trajectory_quantity(p.boundary), std::nullopt, qi, *by, 0, p.y, u, *p.uncertainty, p.where});
  }
  condition_begin_.assign(d.stations.size() + 1, 0);
  for (const auto& p : points_) ++condition_begin_[p.condition + 1];
  for (std::size_t c = 0; c < d.stations.size(); ++c) condition_begin_[c + 1] += condition_begin_[c];
  by_condition_.resize(points_.size());
  std::vector<std::size_t> at(condition_begin_.begin(), condition_begin_.end() - 1);
  for (std::size_t i = 0; i < points_.size(); ++i) by_condition_[at[points_[i].condition]++] = i;
  infeasible_.resize(points_.size());
  for (std::size_t i = 0; i < points_.size(); ++i) infeasible_[i] = kInfeasible + std::abs(residual(base, i));
}

std::vector<std::optional<double>> Misfit::predicted(std::span<const effects::EffectInfo* const> fx,
                                                     std::span<const double> strengths) const {
  const auto pred = source_->predict(fx, strengths);
  std::vector<std::optional<double>> v(points_.size());
  for (std::size_t i = 0; i < points_.size(); ++i) {
    const auto& p = points_[i];
    const ModelPrediction& mp = pred[p.condition][p.model];
    if (p.q) v[i] = mp.values[*p.q];
    else if (p.query < mp.trajectory.size()) v[i] = mp.trajectory[p.query];
  }
  return v;
}

std::vector<double> Misfit::residuals(std::span<const effects::EffectInfo* const> fx,
                                      std::span<const double> strengths) const {
  std::vector<double> r(points_.size());
  try {
    // Each condition's residuals where its predictions are made, which are then dropped there.
    source_->visit(fx, strengths, PredictionSource::Evaluation::surrogate, {},
                   [&](std::size_t c, const std::vector<ModelPrediction>& pred) {
                     for (std::size_t k = condition_begin_[c]; k < condition_begin_[c + 1]; ++k)
                       r[by_condition_[k]] = residual(pred, by_condition_[k]);
                   });
  } catch (const InputError&) {
    r = infeasible_;
  }
  return r;
}

std::vector<double> Misfit::residuals_exact(std::span<const effects::EffectInfo* const> fx,
                                            std::span<const double> strengths) const {
  try {
    return residuals_of(source_->predict(fx, strengths, PredictionSource::Evaluation::exact));
  } catch (const InputError&) {
    return infeasible_;
  }
}

double Misfit::residual(const Predictions& pred, std::size_t i) const { return residual(pred[points_[i].condition], i); }

double Misfit::residual(const std::vector<ModelPrediction>& condition, std::size_t i) const {
  const auto& p = points_[i];
  const ModelPrediction& mp = condition[p.model];
  std::optional<double> v;
  if (p.q) v = mp.values[*p.q];
  else if (p.query < mp.trajectory.size()) v = mp.trajectory[p.query];
  // A prediction that an effect makes vanish (Korzen's V_a when stationary flow stops) counts as
  // zero: the effect has to explain the measurement, not remove it.
  return (v.value_or(0.0) - p.measured) / p.uncertainty;
}

std::vector<double> Misfit::residuals_of(const Predictions& pred) const {
  std::vector<double> r(points_.size());
  for (std::size_t i = 0; i < points_.size(); ++i) r[i] = residual(pred, i);
  return r;
}

MisfitPart Misfit::part(std::vector<std::size_t> conditions) const {
  MisfitPart out;
  std::sort(conditions.begin(), conditions.end());
  conditions.erase(std::unique(conditions.begin(), conditions.end()), conditions.end());
  out.begin.assign(conditions.size() + 1, 0);
  for (std::size_t k = 0; k < conditions.size(); ++k) {
    const std::size_t c = conditions[k];
    out.begin[k + 1] = out.begin[k] + (c < condition_begin_.size() - 1 ? condition_begin_[c + 1] - condition_begin_[c] : 0);
  }
  std::vector<std::size_t> at(out.begin.begin(), out.begin.end() - 1);
  out.by_condition.resize(out.begin.back());
  for (std::size_t i = 0; i < points_.size(); ++i) {
    const auto it = std::lower_bound(conditions.begin(), conditions.end(), points_[i].condition);
    if (it == conditions.end() || *it != points_[i].condition) continue;
    out.by_condition[at[static_cast<std::size_t>(it - conditions.begin())]++] = out.rows.size();
    out.rows.push_back(i);
  }
  out.conditions = std::move(conditions);
  return out;
}

std::vector<double> Misfit::residuals(std::span<const effects::EffectInfo* const> fx,
                                      std::span<const double> strengths, const MisfitPart& part) const {
  std::vector<double> r(part.rows.size());
  try {
    source_->visit(fx, strengths, PredictionSource::Evaluation::surrogate, part.conditions,
                   [&](std::size_t c, const std::vector<ModelPrediction>& pred) {
                     const auto k = static_cast<std::size_t>(
                         std::lower_bound(part.conditions.begin(), part.conditions.end(), c) - part.conditions.begin());
                     for (std::size_t j = part.begin[k]; j < part.begin[k + 1]; ++j)
                       r[part.by_condition[j]] = residual(pred, part.rows[part.by_condition[j]]);
                   });
  } catch (const InputError&) {
    for (std::size_t j = 0; j < part.rows.size(); ++j) r[j] = infeasible_[part.rows[j]];
  }
  return r;
}

double Misfit::chi2(std::span<const effects::EffectInfo* const> fx, std::span<const double> strengths) const {
  double s = 0.0;
  for (double x : residuals(fx, strengths)) s += x * x;
  return s;
}

Cost::Cost(const Misfit& m, std::vector<double> weights) : m_(&m), w_(std::move(weights)) {
  if (w_.empty()) w_.assign(m.size(), 1.0);
  if (w_.size() != m.size()) throw std::logic_error("Cost: one weight per point");
  for (double w : w_) counted_ += w > 0.0 ? 1 : 0;
}

Cost Cost::only(std::vector<std::size_t> conditions) const {
  Cost c = *this;
  c.part_ = std::make_shared<const MisfitPart>(m_->part(std::move(conditions)));
  c.counted_ = 0;
  for (std::size_t row = 0; row < c.rows(); ++row) c.counted_ += c.weight(row) > 0.0 ? 1 : 0;
  return c;
}

std::vector<std::size_t> Cost::conditions() const {
  if (part_) return part_->conditions;
  std::vector<std::size_t> all(m_->dataset().stations.size());
  std::iota(all.begin(), all.end(), std::size_t{0});
  return all;
}

std::vector<double> Cost::weighted(std::vector<double> r) const {
  for (std::size_t i = 0; i < r.size(); ++i) r[i] *= weight(i);
  return r;
}

std::vector<double> Cost::residuals(std::span<const effects::EffectInfo* const> fx,
                                    std::span<const double> strengths) const {
  return weighted(part_ ? m_->residuals(fx, strengths, *part_) : m_->residuals(fx, strengths));
}

double Cost::chi2_of(const std::vector<double>& r) const {
  double s = 0.0;
  for (std::size_t i = 0; i < r.size(); ++i) s += std::pow(r[i] * weight(i), 2);
  return s;
}

double Cost::chi2(std::span<const effects::EffectInfo* const> fx, std::span<const double> strengths) const {
  return chi2_of(part_ ? m_->residuals(fx, strengths, *part_) : m_->residuals(fx, strengths));
}

}  // namespace chutelab::validation
