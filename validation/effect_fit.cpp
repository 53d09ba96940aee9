#include "validation/effect_fit.h"

#include <Eigen/Dense>
#include <cmath>
#include <functional>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_multifit_nlinear.h>
#include <limits>

#include "core/input_error.h"
#include "validation/harness.h"
#include "validation/input_uncertainty.h"

namespace chutelab::validation {

Misfit::Misfit(const Dataset& d, std::vector<ModelPtr> models, analytical::EffectList fixed)
    : d_(&d), models_(std::move(models)), fixed_(std::move(fixed)) {
  for (const auto& st : d.stations) queries_.push_back(trajectory_queries(d, st.condition));
  // The cheap models carry effect signatures for an expensive one even when they are not among
  // the models being judged (e.g. --models dem).
  if (has_expensive())
    for (const auto& n : model_names())
      if (auto m = make_model(n); !m->expensive()) signature_.push_back(m);
  const auto base = predict_all({}, {});
  auto condition_index = [&](const std::string& c) {
    for (std::size_t i = 0; i < d.stations.size(); ++i)
      if (d.stations[i].condition == c) return i;
    throw std::logic_error("measurement of an unknown condition");
  };
  // chi^2 weights: u_D combined with the baseline prediction's u_num (statistical and
  // discretisation parts) and u_input, as V&V 20's u_val.
  std::map<std::pair<std::size_t, std::size_t>, InputUncertaintyResult> u_input;
  auto input_part = [&](std::size_t ci, std::size_t k) -> const InputUncertaintyResult& {
    auto [it, fresh] = u_input.try_emplace({ci, k});
    if (fresh && ci < d.input_uncertainty.size() && !d.input_uncertainty[ci].empty())
      it->second = input_uncertainty(*models_[k], d.stations[ci], d.input_uncertainty[ci], fixed_,
                                     queries_[ci], base[ci][k]);
    return it->second;
  };
  auto weight = [](double u_d, std::initializer_list<std::optional<double>> parts) {
    double sum = u_d * u_d;
    for (const auto& u : parts) sum += std::pow(u.value_or(0.0), 2);
    return std::sqrt(sum);
  };
  for (const auto& m : d.measurements) {
    const std::size_t ci = condition_index(m.condition);
    std::optional<std::size_t> by;
    for (std::size_t k = 0; k < models_.size() && !by; ++k)
      if (base[ci][k].values[m.quantity]) by = k;
    if (!by || !m.uncertainty) {
      ++left_out_;
      continue;
    }
    const ModelPrediction& b = base[ci][*by];
    const double u = weight(*m.uncertainty, {b.uncertainty[m.quantity], b.discretisation[m.quantity],
                                             input_part(ci, *by).u[m.quantity]});
    points_.push_back({ci, std::string(name(m.quantity)), m.quantity, 0, *by, m.value, u});
  }
  std::vector<std::size_t> next(d.stations.size(), 0);
  for (const auto& p : d.trajectory) {
    const std::size_t ci = condition_index(p.condition);
    const std::size_t qi = next[ci]++;
    std::optional<std::size_t> by;
    for (std::size_t k = 0; k < models_.size() && !by; ++k)
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
    points_.push_back({ci, trajectory_quantity(p.boundary), std::nullopt, qi, *by, p.y, u});
  }
}

std::vector<std::vector<ModelPrediction>> Misfit::predict_all(
    std::span<const effects::EffectInfo* const> fx, std::span<const double> strengths) const {
  return predict(fx, strengths, Evaluation::surrogate);
}

std::vector<std::vector<ModelPrediction>> Misfit::predict(std::span<const effects::EffectInfo* const> fx,
                                                          std::span<const double> strengths,
                                                          Evaluation how) const {
  analytical::EffectList list = fixed_;
  for (std::size_t i = 0; i < fx.size(); ++i) list.push_back(fx[i]->make(strengths[i]));
  std::vector<std::vector<ModelPrediction>> out(d_->stations.size());
  for (std::size_t c = 0; c < d_->stations.size(); ++c) {
    const Station& st = d_->stations[c];
    std::vector<ConditionResult> same(models_.size());
    for (std::size_t k = 0; k < models_.size(); ++k)
      if (!models_[k]->expensive() || how == Evaluation::exact)
        same[k] = {st.condition, models_[k]->name(), models_[k]->predict(st, list, {queries_[c], false})};
    std::vector<ModelPrediction> signature;  // cheap models with the effects, raw
    bool need_signature = how == Evaluation::surrogate && has_expensive();
    if (need_signature)
      for (const auto& m : signature_) signature.push_back(m->predict(st, list, {queries_[c], false}));
    for (std::size_t k = 0; k < models_.size(); ++k) {
      if (!models_[k]->expensive() || how == Evaluation::exact) continue;
      // DESIGN.md §5: an expensive model is run once without the candidate effects; an effect's
      // signature comes from the cheap models, applied as a difference: dem + (cheap(e) - cheap).
      ModelPrediction p = expensive_base(c, k);
      for (Quantity q : kAllQuantities)
        if (p.values[q])
          if (auto d = cheap_delta(c, signature, [q](const ModelPrediction& mp) { return mp.values[q]; }))
            *p.values[q] += *d;
      for (std::size_t t = 0; t < p.trajectory.size(); ++t)
        if (p.trajectory[t])
          if (auto d = cheap_delta(c, signature, [t](const ModelPrediction& mp) {
                return t < mp.trajectory.size() ? mp.trajectory[t] : std::nullopt;
              }))
            *p.trajectory[t] += *d;
      same[k] = {st.condition, models_[k]->name(), std::move(p)};
    }
    apply_measurement_effects(list, same);
    for (auto& s : same) out[c].push_back(std::move(s.prediction));
  }
  return out;
}

const ModelPrediction& Misfit::expensive_base(std::size_t c, std::size_t k) const {
  auto& slot = expensive_cache_[{c, k}];
  if (!slot) slot = models_[k]->predict(d_->stations[c], fixed_, {queries_[c], false});
  return *slot;
}

std::optional<double> Misfit::cheap_delta(
    std::size_t c, const std::vector<ModelPrediction>& with_effects,
    const std::function<std::optional<double>(const ModelPrediction&)>& pick) const {
  // The first cheap model (registry order) that predicts the value carries the signature; raw
  // predictions, before measurement effects, since those are applied to every model afterwards.
  for (std::size_t k = 0; k < signature_.size(); ++k) {
    const auto b = pick(cheap_base(c, signature_[k]));
    if (!b) continue;
    const auto e = pick(with_effects[k]);
    if (!e) return std::nullopt;
    return *e - *b;
  }
  return std::nullopt;
}

const ModelPrediction& Misfit::cheap_base(std::size_t c, const ModelPtr& m) const {
  auto& slot = cheap_cache_[{c, m->name()}];
  if (!slot) slot = m->predict(d_->stations[c], fixed_, {queries_[c], false});
  return *slot;
}

bool Misfit::has_expensive() const {
  for (const auto& m : models_)
    if (m->expensive()) return true;
  return false;
}

double Misfit::chi2_exact(std::span<const effects::EffectInfo* const> fx,
                          std::span<const double> strengths) const {
  return chi2_of(predict(fx, strengths, Evaluation::exact));
}

std::vector<double> Misfit::residuals(std::span<const effects::EffectInfo* const> fx,
                                      std::span<const double> strengths) const {
  // Off the map: the misfit of a model that predicts nothing useful, large but finite so that
  // the minimiser can still step back.
  constexpr double kInfeasible = 1e3;
  try {
    return residuals_of(predict_all(fx, strengths));
  } catch (const InputError&) {
    return std::vector<double>(points_.size(), kInfeasible);
  }
}

std::vector<double> Misfit::residuals_of(const std::vector<std::vector<ModelPrediction>>& pred) const {
  std::vector<double> r(points_.size());
  for (std::size_t i = 0; i < points_.size(); ++i) {
    const auto& p = points_[i];
    const ModelPrediction& mp = pred[p.condition][p.model];
    std::optional<double> v;
    if (p.q) v = mp.values[*p.q];
    else if (p.query < mp.trajectory.size()) v = mp.trajectory[p.query];
    // A prediction that an effect makes vanish (Korzen's V_a when stationary flow stops) counts as
    // zero: the effect has to explain the measurement, not remove it.
    r[i] = (v.value_or(0.0) - p.measured) / p.uncertainty;
  }
  return r;
}

double Misfit::chi2_of(const std::vector<std::vector<ModelPrediction>>& pred) const {
  double s = 0.0;
  for (double x : residuals_of(pred)) s += x * x;
  return s;
}

double Misfit::chi2(std::span<const effects::EffectInfo* const> fx,
                    std::span<const double> strengths) const {
  double s = 0.0;
  for (double x : residuals(fx, strengths)) s += x * x;
  return s;
}

namespace {

// Bounds by a logistic map: p = lo + (hi - lo) / (1 + e^-u) keeps every trial inside the range.
double to_p(double u, double lo, double hi) { return lo + (hi - lo) / (1.0 + std::exp(-u)); }
double to_u(double p, double lo, double hi) {
  const double f = std::clamp((p - lo) / (hi - lo), 1e-9, 1.0 - 1e-9);
  return std::log(f / (1.0 - f));
}

struct GslContext {
  const Misfit* m;
  std::span<const effects::EffectInfo* const> fx;
};

int gsl_residuals(const gsl_vector* u, void* params, gsl_vector* f) {
  const auto* ctx = static_cast<GslContext*>(params);
  std::vector<double> p(ctx->fx.size());
  for (std::size_t i = 0; i < p.size(); ++i)
    p[i] = to_p(gsl_vector_get(u, i), ctx->fx[i]->lower, ctx->fx[i]->upper);
  const auto r = ctx->m->residuals(ctx->fx, p);
  for (std::size_t i = 0; i < r.size(); ++i) gsl_vector_set(f, i, r[i]);
  return GSL_SUCCESS;
}

// Grid over the physical range, finer for one parameter than for two.
void grid_scan(const Misfit& m, std::span<const effects::EffectInfo* const> fx,
               std::vector<double>& best, double& best_chi2) {
  const int n = fx.size() == 1 ? 40 : 5;
  std::vector<double> p(fx.size());
  std::vector<int> idx(fx.size(), 0);
  while (true) {
    for (std::size_t i = 0; i < fx.size(); ++i)
      p[i] = fx[i]->lower + (fx[i]->upper - fx[i]->lower) * idx[i] / n;
    const double c = m.chi2(fx, p);
    if (c < best_chi2) {
      best_chi2 = c;
      best = p;
    }
    std::size_t k = 0;
    while (k < idx.size() && ++idx[k] > n) idx[k++] = 0;
    if (k == idx.size()) break;
  }
}

}  // namespace

StrengthFit fit_strengths(const Misfit& m, std::span<const effects::EffectInfo* const> fx,
                          const std::vector<std::vector<double>>& starts) {
  gsl_set_error_handler_off();
  const std::size_t k = fx.size();
  StrengthFit out;
  std::vector<double> best(k);
  for (std::size_t i = 0; i < k; ++i) best[i] = fx[i]->neutral;
  double best_chi2 = m.chi2(fx, best);
  for (const auto& s : starts)
    if (s.size() == k) {
      const double c = m.chi2(fx, s);
      if (c < best_chi2) {
        best_chi2 = c;
        best = s;
      }
    }
  grid_scan(m, fx, best, best_chi2);

  if (m.size() > k) {
    GslContext ctx{&m, fx};
    gsl_multifit_nlinear_fdf fdf{};
    fdf.f = gsl_residuals;
    fdf.df = nullptr;  // forward-difference Jacobian
    fdf.n = m.size();
    fdf.p = k;
    fdf.params = &ctx;
    gsl_multifit_nlinear_parameters par = gsl_multifit_nlinear_default_parameters();
    gsl_multifit_nlinear_workspace* w =
        gsl_multifit_nlinear_alloc(gsl_multifit_nlinear_trust, &par, m.size(), k);
    gsl_vector* u = gsl_vector_alloc(k);
    for (std::size_t i = 0; i < k; ++i) gsl_vector_set(u, i, to_u(best[i], fx[i]->lower, fx[i]->upper));
    int info = 0;
    gsl_multifit_nlinear_init(u, &fdf, w);
    const int status = gsl_multifit_nlinear_driver(100, 1e-10, 1e-10, 1e-12, nullptr, nullptr, &info, w);
    std::vector<double> p(k);
    for (std::size_t i = 0; i < k; ++i)
      p[i] = to_p(gsl_vector_get(w->x, i), fx[i]->lower, fx[i]->upper);
    const double c = m.chi2(fx, p);
    out.converged = status == GSL_SUCCESS;
    if (c <= best_chi2) {
      best_chi2 = c;
      best = p;
    }
    gsl_vector_free(u);
    gsl_multifit_nlinear_free(w);
  }
  out.estimate = best;
  out.chi2 = best_chi2;

  // Uncertainty in the parameters' own units: central differences of the residuals give J, and
  // the covariance of a weighted least-squares estimate is (J^T J)^-1.
  Eigen::MatrixXd J(m.size(), k);
  for (std::size_t j = 0; j < k; ++j) {
    const double h = 1e-4 * (fx[j]->upper - fx[j]->lower);
    std::vector<double> lo = best, hi = best;
    lo[j] = std::max(fx[j]->lower, best[j] - h);
    hi[j] = std::min(fx[j]->upper, best[j] + h);
    const auto rl = m.residuals(fx, lo), rh = m.residuals(fx, hi);
    for (std::size_t i = 0; i < m.size(); ++i) J(i, j) = (rh[i] - rl[i]) / (hi[j] - lo[j]);
  }
  const Eigen::MatrixXd JtJ = J.transpose() * J;
  Eigen::FullPivLU<Eigen::MatrixXd> lu(JtJ);
  out.uncertainty.assign(k, std::numeric_limits<double>::infinity());
  if (lu.isInvertible() && lu.rcond() > 1e-12) {
    const Eigen::MatrixXd cov = lu.inverse();
    for (std::size_t j = 0; j < k; ++j) out.uncertainty[j] = std::sqrt(std::max(0.0, cov(j, j)));
  }
  return out;
}

}  // namespace chutelab::validation
