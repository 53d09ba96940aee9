#include "validation/strength_fit.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <exception>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_multifit_nlinear.h>
#include <limits>
#include <map>
#include <memory>

namespace chutelab::validation {
namespace {

// Bounds by a logistic map: p = lo + (hi - lo) / (1 + e^-u) keeps every trial inside the range.
double to_p(double u, double lo, double hi) { return lo + (hi - lo) / (1.0 + std::exp(-u)); }
double to_u(double p, double lo, double hi) {
  const double f = std::clamp((p - lo) / (hi - lo), 1e-9, 1.0 - 1e-9);
  return std::log(f / (1.0 - f));
}

// The sample's lowest grid basins judged on the whole data: two basins of similar depth may swap
// between a sample and the whole.
constexpr std::size_t kSampleBasins = 3;

struct Bounds {
  std::vector<double> lo, hi;
};

Bounds bounds_of(std::span<const effects::EffectInfo* const> fx, StrengthRange range) {
  Bounds b;
  for (const auto* e : fx) {
    const auto r = range == StrengthRange::physical ? effects::Range{e->lower, e->upper} : effects::extended_range(*e);
    b.lo.push_back(r.lower);
    b.hi.push_back(r.upper);
  }
  return b;
}

struct GslContext {
  const Cost* cost;
  std::span<const effects::EffectInfo* const> fx;
  const Bounds* b;
  std::exception_ptr failure = nullptr;
};

// GSL calls this from C: an exception (an interrupt, a model's refusal) may not unwind through its
// frames, which would also leave its workspace allocated. It is kept and rethrown once GSL returns.
int gsl_residuals(const gsl_vector* u, void* params, gsl_vector* f) {
  auto* ctx = static_cast<GslContext*>(params);
  try {
    std::vector<double> p(ctx->fx.size());
    for (std::size_t i = 0; i < p.size(); ++i) p[i] = to_p(gsl_vector_get(u, i), ctx->b->lo[i], ctx->b->hi[i]);
    const auto r = ctx->cost->residuals(ctx->fx, p);
    for (std::size_t i = 0; i < r.size(); ++i) gsl_vector_set(f, i, r[i]);
    return GSL_SUCCESS;
  } catch (...) {
    ctx->failure = std::current_exception();
    return GSL_EBADFUNC;
  }
}

// The grid over the range, finer for one parameter than for two: each point with its index.
template <class Visit>
void for_each_grid_point(std::size_t k, const Bounds& b, Visit&& visit) {
  const int n = k == 1 ? 40 : 5;
  std::vector<double> p(k);
  std::vector<int> idx(k, 0);
  while (true) {
    for (std::size_t i = 0; i < k; ++i) p[i] = b.lo[i] + (b.hi[i] - b.lo[i]) * idx[i] / n;
    visit(idx, p);
    std::size_t j = 0;
    while (j < idx.size() && ++idx[j] > n) idx[j++] = 0;
    if (j == idx.size()) break;
  }
}

void grid_scan(const Cost& cost, std::span<const effects::EffectInfo* const> fx, const Bounds& b,
               std::vector<double>& best, double& best_chi2) {
  for_each_grid_point(fx.size(), b, [&](const std::vector<int>&, const std::vector<double>& p) {
    const double c = cost.chi2(fx, p);
    if (c < best_chi2) {
      best_chi2 = c;
      best = p;
    }
  });
}

// The grid's local minima (no neighbour, diagonals included, lower), lowest first, at most `most`:
// where a sample's grid may rank two basins differently from the whole data, each is tried.
std::vector<std::vector<double>> grid_basins(const Cost& cost, std::span<const effects::EffectInfo* const> fx,
                                             const Bounds& b, std::size_t most) {
  struct Point {
    std::vector<int> idx;
    std::vector<double> p;
    double chi2;
  };
  std::vector<Point> grid;
  for_each_grid_point(fx.size(), b, [&](const std::vector<int>& idx, const std::vector<double>& p) {
    grid.push_back({idx, p, cost.chi2(fx, p)});
  });
  std::vector<const Point*> minima;
  for (const auto& a : grid) {
    bool lowest = true;
    for (const auto& o : grid) {
      bool near = &o != &a;
      for (std::size_t i = 0; near && i < a.idx.size(); ++i) near = std::abs(o.idx[i] - a.idx[i]) <= 1;
      if (near && o.chi2 < a.chi2) {
        lowest = false;
        break;
      }
    }
    if (lowest) minima.push_back(&a);
  }
  std::stable_sort(minima.begin(), minima.end(), [](const Point* x, const Point* y) { return x->chi2 < y->chi2; });
  std::vector<std::vector<double>> out;
  for (std::size_t i = 0; i < minima.size() && i < most; ++i) out.push_back(minima[i]->p);
  return out;
}

// Trust-region refinement from `best`; returns the status and updates best where it improved.
FitStatus refine(const Cost& cost, std::span<const effects::EffectInfo* const> fx, const Bounds& b,
                 std::vector<double>& best, double& best_chi2) {
  const std::size_t k = fx.size();
  GslContext ctx{&cost, fx, &b};
  gsl_multifit_nlinear_fdf fdf{};
  fdf.f = gsl_residuals;
  fdf.df = nullptr;  // forward-difference Jacobian
  fdf.n = cost.rows();
  fdf.p = k;
  fdf.params = &ctx;
  gsl_multifit_nlinear_parameters par = gsl_multifit_nlinear_default_parameters();
  const std::unique_ptr<gsl_multifit_nlinear_workspace, decltype(&gsl_multifit_nlinear_free)> w(
      gsl_multifit_nlinear_alloc(gsl_multifit_nlinear_trust, &par, cost.rows(), k), gsl_multifit_nlinear_free);
  const std::unique_ptr<gsl_vector, decltype(&gsl_vector_free)> u(gsl_vector_alloc(k), gsl_vector_free);
  for (std::size_t i = 0; i < k; ++i) gsl_vector_set(u.get(), i, to_u(best[i], b.lo[i], b.hi[i]));
  int info = 0;
  gsl_multifit_nlinear_init(u.get(), &fdf, w.get());
  const int status = ctx.failure ? GSL_EBADFUNC
                                 : gsl_multifit_nlinear_driver(100, 1e-10, 1e-10, 1e-12, nullptr, nullptr, &info, w.get());
  if (ctx.failure) std::rethrow_exception(ctx.failure);
  std::vector<double> p(k);
  for (std::size_t i = 0; i < k; ++i) p[i] = to_p(gsl_vector_get(w->x, i), b.lo[i], b.hi[i]);
  const double c = cost.chi2(fx, p);
  if (c <= best_chi2) {
    best_chi2 = c;
    best = p;
  }
  return status == GSL_SUCCESS ? FitStatus::converged : FitStatus::stopped;
}

// The weighted residuals' Jacobian by central differences (one-sided at an edge of the range).
Eigen::MatrixXd jacobian(const Cost& cost, std::span<const effects::EffectInfo* const> fx, const Bounds& b,
                         const std::vector<double>& at) {
  const std::size_t k = fx.size();
  Eigen::MatrixXd J(cost.rows(), k);
  for (std::size_t j = 0; j < k; ++j) {
    const double h = 1e-4 * (fx[j]->upper - fx[j]->lower);
    std::vector<double> lo = at, hi = at;
    lo[j] = std::max(b.lo[j], at[j] - h);
    hi[j] = std::min(b.hi[j], at[j] + h);
    const auto rl = cost.residuals(fx, lo), rh = cost.residuals(fx, hi);
    for (std::size_t i = 0; i < cost.rows(); ++i) J(i, j) = (rh[i] - rl[i]) / (hi[j] - lo[j]);
  }
  return J;
}

// Uncertainty in the parameters' own units: the covariance of a weighted least-squares estimate is
// (J^T J)^-1, J the weighted residuals' Jacobian.
std::vector<double> sd_of(const Eigen::MatrixXd& J) {
  const auto k = static_cast<std::size_t>(J.cols());
  const Eigen::MatrixXd JtJ = J.transpose() * J;
  Eigen::FullPivLU<Eigen::MatrixXd> lu(JtJ);
  std::vector<double> sd(k, std::numeric_limits<double>::infinity());
  if (lu.isInvertible() && lu.rcond() > 1e-12) {
    const Eigen::MatrixXd cov = lu.inverse();
    for (std::size_t j = 0; j < k; ++j) sd[j] = std::sqrt(std::max(0.0, cov(j, j)));
  }
  return sd;
}

std::vector<double> covariance_sd(const Cost& cost, std::span<const effects::EffectInfo* const> fx, const Bounds& b,
                                  const std::vector<double>& best) {
  return sd_of(jacobian(cost, fx, b, best));
}

// A forward-difference Jacobian from the residuals at `at` (backward at the upper edge): half the
// evaluations of the central one, precise enough for a Gauss-Newton step and an sd.
Eigen::MatrixXd forward_jacobian(const Cost& cost, std::span<const effects::EffectInfo* const> fx, const Bounds& b,
                                 const std::vector<double>& at, const std::vector<double>& r_at) {
  Eigen::MatrixXd J(cost.rows(), fx.size());
  for (std::size_t j = 0; j < fx.size(); ++j) {
    const double h = 1e-4 * (fx[j]->upper - fx[j]->lower);
    std::vector<double> p = at;
    p[j] = at[j] + h <= b.hi[j] ? at[j] + h : at[j] - h;
    const double step = p[j] - at[j];
    const auto r = cost.residuals(fx, p);
    for (std::size_t i = 0; i < cost.rows(); ++i) J(i, j) = (r[i] - r_at[i]) / step;
  }
  return J;
}

double squared_norm(const std::vector<double>& r) {
  double s = 0.0;
  for (double x : r) s += x * x;
  return s;
}

enum class Polish { converged, stopped, failed };

// Gauss-Newton steps on the whole cost from a point already in the minimum's basin, halving a step
// that does not lower chi^2, until every step is below a hundredth of its sd. A strength at an edge
// that the data push beyond is held there (an active set), as the bounds of the grid's range
// demand. Each step takes a fresh Jacobian: an updated one (Broyden's) is the secant of the last
// step, and where the model bends it gave sds 10-40 % off. `failed`: no step could be taken at all
// (a singular or non-descending system), so the caller falls back to the trust region. On
// convergence `J` is the Jacobian at a point within a hundredth of an sd of the estimate, which
// gives its sd without evaluating it again. `rv`: the weighted residuals at `best`, in (when the
// caller has them; else empty) and out.
Polish polish(const Cost& cost, std::span<const effects::EffectInfo* const> fx, const Bounds& b,
              std::vector<double>& best, double& best_chi2, Eigen::MatrixXd& J, std::vector<double>& rv) {
  const std::size_t k = fx.size();
  if (rv.size() != cost.rows()) rv = cost.residuals(fx, best);
  best_chi2 = squared_norm(rv);
  for (int iteration = 0; iteration < 30; ++iteration) {
    const Eigen::Map<const Eigen::VectorXd> r(rv.data(), static_cast<Eigen::Index>(rv.size()));
    J = forward_jacobian(cost, fx, b, best, rv);
    const Eigen::VectorXd g = J.transpose() * r;
    std::vector<Eigen::Index> free;
    for (std::size_t j = 0; j < k; ++j) {
      const double span = b.hi[j] - b.lo[j];
      const bool held = (best[j] <= b.lo[j] + 1e-9 * span && g(j) > 0.0) || (best[j] >= b.hi[j] - 1e-9 * span && g(j) < 0.0);
      if (!held) free.push_back(static_cast<Eigen::Index>(j));
    }
    if (free.empty()) return Polish::converged;
    const auto f = static_cast<Eigen::Index>(free.size());
    Eigen::MatrixXd H(f, f);
    Eigen::VectorXd gf(f);
    for (Eigen::Index a = 0; a < f; ++a) {
      gf(a) = g(free[a]);
      for (Eigen::Index c = 0; c < f; ++c) H(a, c) = J.col(free[a]).dot(J.col(free[c]));
    }
    const Eigen::LDLT<Eigen::MatrixXd> ldlt(H);
    if (ldlt.info() != Eigen::Success || !ldlt.isPositive() || ldlt.rcond() < 1e-12) return iteration ? Polish::stopped : Polish::failed;
    const Eigen::VectorXd d = ldlt.solve(-gf);
    const Eigen::MatrixXd cov = ldlt.solve(Eigen::MatrixXd::Identity(f, f));
    bool small = true;
    for (Eigen::Index a = 0; a < f; ++a) small = small && std::abs(d(a)) < 0.01 * std::sqrt(std::max(0.0, cov(a, a)));
    bool moved = false;
    for (double t = 1.0; t > 1e-3 && !moved; t /= 2.0) {
      std::vector<double> trial = best;
      for (Eigen::Index a = 0; a < f; ++a) {
        const auto j = static_cast<std::size_t>(free[a]);
        trial[j] = std::clamp(best[j] + t * d(a), b.lo[j], b.hi[j]);
      }
      auto rt = cost.residuals(fx, trial);
      if (const double c = squared_norm(rt); c < best_chi2) {
        best_chi2 = c;
        best = std::move(trial);
        rv = std::move(rt);
        moved = true;
      }
      if (small) break;  // a step this small is not worth halving
    }
    if (small) return Polish::converged;
    if (!moved) return iteration ? Polish::stopped : Polish::failed;
  }
  return Polish::stopped;
}

// Many conditions: the grid and a first refinement on an even sample of them, each of the sample's
// lowest basins judged on all, then the polish on all.
// `J` and `r_best` (the weighted residuals at the estimate): as polish leaves them on convergence,
// else empty.
FitStatus fit_sampled(const Cost& cost, std::span<const effects::EffectInfo* const> fx, const Bounds& b,
                      std::size_t sample_size, std::vector<double>& best, double& best_chi2, Eigen::MatrixXd& J,
                      std::vector<double>& r_best) {
  const auto all = cost.conditions();
  std::vector<std::size_t> pick(sample_size);
  for (std::size_t i = 0; i < sample_size; ++i) pick[i] = all[(2 * i + 1) * all.size() / (2 * sample_size)];
  const Cost sample = cost.only(std::move(pick));
  const std::vector<std::size_t> sampled = sample.conditions();
  struct Basin {
    std::vector<double> p;
    std::vector<double> per_condition;  // the sample's chi^2 by condition (sample order)
    double chi2 = 0.0;
  };
  std::vector<Basin> basins;
  for (auto p : grid_basins(sample, fx, b, kSampleBasins)) {
    double c = sample.chi2(fx, p);
    if (sample.size() > fx.size()) refine(sample, fx, b, p, c);
    Basin basin{p, std::vector<double>(sample_size, 0.0), 0.0};
    const auto r = sample.residuals(fx, p);
    for (std::size_t row = 0; row < r.size(); ++row) {
      const auto at = std::lower_bound(sampled.begin(), sampled.end(), sample.condition_of_row(row)) - sampled.begin();
      basin.per_condition[static_cast<std::size_t>(at)] += r[row] * r[row];
      basin.chi2 += r[row] * r[row];
    }
    basins.push_back(std::move(basin));
  }
  std::stable_sort(basins.begin(), basins.end(), [](const Basin& x, const Basin& y) { return x.chi2 < y.chi2; });
  // A basin the sample finds worse than the lowest by more than four standard errors of the
  // difference (summed over all the conditions, from its spread over the sampled ones) is worse on
  // all the data too: it is not judged there.
  r_best.clear();
  for (std::size_t i = 0; i < basins.size(); ++i) {
    if (i > 0) {
      double mean = 0.0, sq = 0.0;
      for (std::size_t c = 0; c < sample_size; ++c) mean += basins[i].per_condition[c] - basins[0].per_condition[c];
      mean /= static_cast<double>(sample_size);
      for (std::size_t c = 0; c < sample_size; ++c)
        sq += std::pow(basins[i].per_condition[c] - basins[0].per_condition[c] - mean, 2);
      const double se = std::sqrt(sq / static_cast<double>(sample_size - 1) / static_cast<double>(sample_size));
      if (mean > 4.0 * se) continue;
    }
    auto r = cost.residuals(fx, basins[i].p);
    if (const double whole = squared_norm(r); whole < best_chi2) {
      best_chi2 = whole;
      best = basins[i].p;
      r_best = std::move(r);
    }
  }
  switch (polish(cost, fx, b, best, best_chi2, J, r_best)) {
    case Polish::converged: return FitStatus::converged;
    case Polish::stopped: break;
    case Polish::failed:
      J.resize(0, 0);
      r_best.clear();
      return refine(cost, fx, b, best, best_chi2);
  }
  J.resize(0, 0);
  r_best.clear();
  return FitStatus::stopped;
}
}  // namespace

StrengthFit fit_strengths(const Cost& cost, std::span<const effects::EffectInfo* const> fx, const FitOptions& opt) {
  gsl_set_error_handler_off();
  const std::size_t k = fx.size();
  const Bounds b = bounds_of(fx, opt.range);
  StrengthFit out;
  std::vector<double> best(k);
  for (std::size_t i = 0; i < k; ++i) best[i] = fx[i]->neutral;
  double best_chi2 = cost.chi2(fx, best);
  for (const auto& s : opt.starts)
    if (s.size() == k) {
      std::vector<double> p(k);
      for (std::size_t i = 0; i < k; ++i) p[i] = std::clamp(s[i], b.lo[i], b.hi[i]);
      if (const double c = cost.chi2(fx, p); c < best_chi2) {
        best_chi2 = c;
        best = p;
      }
    }
  Eigen::MatrixXd J;
  if (!opt.grid) {
    if (cost.size() > k) out.status = refine(cost, fx, b, best, best_chi2);
  } else if (const std::size_t g = opt.grid_conditions; g > 0 && cost.conditions().size() > 2 * g && cost.size() > k) {
    out.status = fit_sampled(cost, fx, b, g, best, best_chi2, J, out.residuals);
  } else {
    grid_scan(cost, fx, b, best, best_chi2);
    if (cost.size() > k) out.status = refine(cost, fx, b, best, best_chi2);
  }
  out.estimate = best;
  out.chi2 = best_chi2;
  out.uncertainty = J.size() ? sd_of(J) : covariance_sd(cost, fx, b, best);
  for (std::size_t i = 0; i < k; ++i) {
    const double span = b.hi[i] - b.lo[i];
    out.at_bound.push_back(best[i] <= b.lo[i] + 1e-3 * span || best[i] >= b.hi[i] - 1e-3 * span);
  }
  return out;
}

StrengthFit fit_strengths(const Misfit& m, std::span<const effects::EffectInfo* const> fx,
                          const std::vector<std::vector<double>>& starts) {
  return fit_strengths(Cost(m), fx, FitOptions{StrengthRange::physical, starts});
}

double round_number(double x) {
  if (!(x > 0.0) || !std::isfinite(x)) return x;
  const double mag = std::pow(10.0, std::floor(std::log10(x)));
  const double f = x / mag;
  return (f < 1.5 ? 1.0 : f < 3.5 ? 2.0 : f < 7.5 ? 5.0 : 10.0) * mag;
}

double on_grid(double value, double sd) {
  if (!(sd > 0.0) || !std::isfinite(sd)) return value;
  const double step = std::pow(10.0, std::floor(std::log10(sd / 4.0)));
  return std::round(value / step) * step;
}

namespace {

// The parabola through three (strength, chi^2) points: chi^2 ~ a (s - vertex)^2 + min.
struct Parabola {
  double a = 0.0, vertex = 0.0, min = 0.0;
};
Parabola through(std::pair<double, double> p0, std::pair<double, double> p1, std::pair<double, double> p2) {
  const auto [x0, y0] = p0;
  const auto [x1, y1] = p1;
  const auto [x2, y2] = p2;
  const double d01 = (y1 - y0) / (x1 - x0), d12 = (y2 - y1) / (x2 - x1);
  Parabola p;
  p.a = (d12 - d01) / (x2 - x0);
  if (!(p.a > 0.0)) return p;
  const double b = d01 - p.a * (x0 + x1);
  p.vertex = -b / (2.0 * p.a);
  p.min = y1 - p.a * std::pow(x1 - p.vertex, 2);
  return p;
}

}  // namespace

ProfileFit profile_strength(const std::function<double(double)>& chi2_at, double first, double step, double lower,
                            double upper, int budget, const std::vector<std::pair<double, double>>& known) {
  ProfileFit out;
  // The step as a round number (1, 2 or 5 times a power of ten), strengths on its half-grid.
  const double h = std::min(std::max(round_number(std::abs(step)), 1e-12), (upper - lower) / 2.0);
  const double grid = h / 2.0;
  std::map<double, double> seen(known.begin(), known.end());
  auto snap = [&](double s) { return std::clamp(first + std::round((s - first) / grid) * grid, lower, upper); };
  auto at = [&](double s) {
    s = snap(s);
    if (seen.count(s)) return false;
    seen.emplace(s, chi2_at(s));
    --budget;
    return true;
  };
  auto lowest = [&] {
    return std::min_element(seen.begin(), seen.end(), [](auto& a, auto& b) { return a.second < b.second; });
  };
  const double centre = first - lower < h ? snap(lower + h) : upper - first < h ? snap(upper - h) : first;
  at(centre - h);
  at(centre);
  at(centre + h);
  // Successive parabolic steps: jump to the vertex of the parabola through the lowest point and its
  // two neighbours (inside), or through the three points at the end it sits on (outward, at most
  // eight steps; one step where the vertex is the end itself, to bracket it); walk two steps
  // outward where the three are not convex; stop when the next strength was seen.
  while (budget > 0) {
    const auto low = lowest();
    const bool at_low_end = low == seen.begin(), at_high_end = std::next(low) == seen.end();
    double next;
    if (!at_low_end && !at_high_end) {
      const Parabola p = through(*std::prev(low), *low, *std::next(low));
      if (!(p.a > 0.0)) break;
      next = std::clamp(p.vertex, low->first - 4.0 * h, low->first + 4.0 * h);
    } else if (seen.size() >= 3) {
      const double out_dir = at_low_end ? -1.0 : 1.0;
      const auto a = at_low_end ? low : std::prev(low, 2);
      const Parabola p = through(*a, *std::next(a), *std::next(a, 2));
      next = p.a > 0.0 ? std::clamp(p.vertex, low->first - 8.0 * h, low->first + 8.0 * h) : low->first + 2.0 * out_dir * h;
      if (snap(next) == low->first) next = low->first + out_dir * h;
    } else {
      break;
    }
    if (!at(next)) break;
  }
  // Three points fix a parabola exactly, so their runs' own noise cannot show in its sd (the peer
  // flow-bias case: three runs drew a minimum 2 sd from the truth). The half-steps beside a bracketed
  // minimum give the least-squares fit below a scatter to measure, where the budget allows.
  if (const auto low = lowest(); seen.size() < 5 && low != seen.begin() && std::next(low) != seen.end()) {
    const double s = low->first;
    if (budget > 0) at(s - grid);
    if (budget > 0) at(s + grid);
  }
  for (const auto& p : seen) out.points.push_back(p);
  const auto low = lowest();
  out.estimate = low->first;
  out.chi2 = low->second;
  out.uncertainty = std::numeric_limits<double>::infinity();
  if (low == seen.begin() || std::next(low) == seen.end()) return out;
  const Parabola p = through(*std::prev(low), *low, *std::next(low));
  if (!(p.a > 0.0)) return out;
  out.estimate = std::clamp(p.vertex, std::prev(low)->first, std::next(low)->first);
  out.chi2 = p.min;
  out.uncertainty = 1.0 / std::sqrt(p.a);
  out.bracketed = true;
  // An expensive model's chi^2 at each strength carries its runs' own noise, so three points can
  // draw a parabola far sharper than the profile is. With four or more, a least-squares parabola
  // through them all: its vertex, and an sd that adds to its curvature's the vertex's own
  // uncertainty from the points' scatter about it.
  if (out.points.size() >= 4) {
    const double x0 = low->first, sx = h;  // centred and scaled, for a well-conditioned fit
    Eigen::MatrixXd X(static_cast<Eigen::Index>(out.points.size()), 3);
    Eigen::VectorXd y(static_cast<Eigen::Index>(out.points.size()));
    for (std::size_t i = 0; i < out.points.size(); ++i) {
      const double t = (out.points[i].first - x0) / sx;
      X.row(static_cast<Eigen::Index>(i)) << t * t, t, 1.0;
      y(static_cast<Eigen::Index>(i)) = out.points[i].second;
    }
    const Eigen::MatrixXd XtX = X.transpose() * X;
    const Eigen::Vector3d c = XtX.ldlt().solve(X.transpose() * y);
    const double a = c(0) / (sx * sx);
    if (a > 0.0) {
      const double t_min = -c(1) / (2.0 * c(0));
      const double v = x0 + t_min * sx;
      if (v >= out.points.front().first && v <= out.points.back().first) {
        const double dof = static_cast<double>(out.points.size()) - 3.0;
        double var_v = 0.0;
        if (dof > 0.0) {
          const double sigma2 = (y - X * c).squaredNorm() / dof;
          const Eigen::Matrix3d cov = sigma2 * XtX.inverse();
          // v = x0 - sx c1 / (2 c0): its gradient in (c0, c1).
          const Eigen::Vector3d g(sx * c(1) / (2.0 * c(0) * c(0)), -sx / (2.0 * c(0)), 0.0);
          var_v = g.dot(cov * g);
        }
        out.estimate = v;
        out.chi2 = c(2) - c(1) * c(1) / (4.0 * c(0));
        out.uncertainty = std::sqrt(1.0 / a + var_v);
        out.scatter = dof > 0.0 ? std::sqrt((y - X * c).squaredNorm() / dof) : 0.0;
      }
    }
  }
  return out;
}

}  // namespace chutelab::validation
