#include "validation/diagnosis.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fmt/format.h>
#include <iostream>
#include <gsl/gsl_cdf.h>
#include <map>
#include <set>
#include <thread>

#include "analytical/transfer_station.h"
#include "core/campaign.h"
#include "validation/effect_fit.h"
#include "validation/output_files.h"

namespace chutelab::validation {

std::string EffectFit::label() const { return fmt::format("{}", fmt::join(effects, " + ")); }

const EffectFit* DiagnosisResult::best() const {
  if (!any_significant) return nullptr;
  if (!pairs.empty()) return &pairs.front();
  return singles.empty() ? nullptr : &singles.front();
}

namespace {

double pearson(const std::vector<double>& a, const std::vector<double>& b) {
  const std::size_t n = a.size();
  double ma = 0, mb = 0;
  for (std::size_t i = 0; i < n; ++i) ma += a[i], mb += b[i];
  ma /= n, mb /= n;
  double sab = 0, saa = 0, sbb = 0;
  for (std::size_t i = 0; i < n; ++i) {
    sab += (a[i] - ma) * (b[i] - mb);
    saa += (a[i] - ma) * (a[i] - ma);
    sbb += (b[i] - mb) * (b[i] - mb);
  }
  return (saa > 0 && sbb > 0) ? sab / std::sqrt(saa * sbb) : 0.0;
}

std::string quantity_words(const std::string& q) {
  if (auto parsed = parse_quantity(q)) return fmt::format("{} ({})", info(*parsed).label, info(*parsed).symbol);
  if (q.rfind("trajectory_", 0) == 0) {
    const std::string b = q.substr(11, q.find("_y_mm") - 11);
    return fmt::format("{} stream limit", b == "centre" ? "centre of the" : b);
  }
  return q;
}

// Residual patterns: for each quantity, the normalised residuals of the models as they are,
// against the operating variables an engineer would suspect.
std::vector<ResidualPattern> residual_patterns(const Misfit& m, const std::vector<double>& r,
                                               std::vector<std::string>& sentences) {
  const Dataset& d = m.dataset();
  std::vector<double> speed, flow, tflight, drop;
  for (const auto& st : d.stations) {
    speed.push_back(st.belt_speed);
    flow.push_back(st.mass_flow * 3.6);
    try {
      const auto a = analytical::analyse_transfer(st);
      tflight.push_back(a.flight_time());
      drop.push_back(a.drop_height() * 1e3);
    } catch (const std::exception&) {
      tflight.push_back(0.0);
      drop.push_back(0.0);
    }
  }
  std::map<std::pair<std::size_t, std::string>, std::vector<std::size_t>> groups;
  for (std::size_t i = 0; i < m.size(); ++i)
    groups[{m.points()[i].model, m.points()[i].quantity}].push_back(i);

  std::vector<ResidualPattern> out;
  for (const auto& [key, idx] : groups) {
    const auto& [model, quantity] = key;
    std::vector<double> z, s, f, t, h;
    for (std::size_t i : idx) {
      const auto c = m.points()[i].condition;
      z.push_back(r[i]);
      s.push_back(speed[c]);
      f.push_back(flow[c]);
      t.push_back(tflight[c]);
      h.push_back(drop[c]);
    }
    const int n = static_cast<int>(z.size());
    double mean = 0, ss = 0;
    for (double x : z) mean += x, ss += x * x;
    mean /= n;
    const double rms = std::sqrt(ss / n);
    // A bias is notable when the mean normalised residual is 3 standard errors from zero; a trend
    // when the residuals are large (RMS > 2) and line up with a driver (|r| >= 0.7).
    const bool bias = std::abs(mean) > 3.0 / std::sqrt(n);
    const std::vector<std::pair<std::string, const std::vector<double>*>> drivers = {
        {"belt speed", &s}, {"mass flow", &f}, {"flight time", &t}, {"drop height", &h}};
    std::string strongest;
    double strongest_r = 0.0;
    for (const auto& [dn, dv] : drivers) {
      ResidualPattern p;
      p.model = m.models()[model]->name();
      p.quantity = quantity;
      p.driver = dn;
      p.n = n;
      p.mean_normalised = mean;
      p.rms_normalised = rms;
      p.correlation = n >= 3 ? pearson(z, *dv) : 0.0;
      p.notable = bias || (rms > 2.0 && std::abs(p.correlation) >= 0.7);
      if (std::abs(p.correlation) > std::abs(strongest_r)) strongest_r = p.correlation, strongest = dn;
      out.push_back(p);
    }
    if (rms <= 2.0 && !bias) continue;
    std::string sentence = fmt::format("{}: {} ", quantity_words(quantity), m.models()[model]->name());
    if (bias)
      sentence += fmt::format("{} it by {:.1f} standard deviations on average", mean > 0 ? "over-predicts" : "under-predicts",
                              std::abs(mean));
    else
      sentence += fmt::format("misses it by {:.1f} standard deviations (RMS) without a steady bias", rms);
    if (n >= 3 && std::abs(strongest_r) >= 0.7) {
      // Residual = prediction - measurement: a positive trend means over-prediction grows.
      const bool grows = (strongest_r > 0) == (mean >= 0);
      sentence += fmt::format("; the misfit {} with {} (r = {:+.2f})",
                              grows ? "grows" : "shrinks", strongest, strongest_r);
    }
    sentences.push_back(sentence + ".");
  }
  return out;
}

// Where the chi^2 of the models as they are comes from, by quantity, largest first (top three).
std::string largest_misfit(const Misfit& m, const std::vector<double>& r) {
  std::map<std::string, double> share;
  double total = 0.0;
  for (std::size_t i = 0; i < r.size(); ++i) {
    share[quantity_words(m.points()[i].quantity)] += r[i] * r[i];
    total += r[i] * r[i];
  }
  std::vector<std::pair<double, std::string>> sorted;
  for (const auto& [q, c] : share) sorted.emplace_back(c, q);
  std::sort(sorted.rbegin(), sorted.rend());
  std::vector<std::string> parts;
  for (std::size_t i = 0; i < sorted.size() && i < 3; ++i)
    parts.push_back(fmt::format("{} ({:.0f} % of chi^2)", sorted[i].second, 100 * sorted[i].first / total));
  return fmt::format("{}", fmt::join(parts, ", "));
}

// chi^2 after a fit of n data and what follows from it: BIC change, share of the excess misfit
// (chi^2 - n) removed, and the likelihood-ratio p-value against chi2_before.
void score(EffectFit& e, double chi2, double n) {
  const double k = static_cast<double>(e.effects.size());
  e.chi2_after = chi2;
  e.delta_bic = (chi2 + k * std::log(n)) - e.chi2_before;
  const double excess = e.chi2_before - n;
  e.explained_fraction = excess > 0 ? std::clamp((e.chi2_before - chi2) / excess, 0.0, 1.0) : 0.0;
  e.p_value = gsl_cdf_chisq_Q(std::max(0.0, e.chi2_before - chi2), k);
}

EffectFit make_fit(const Misfit& m, std::vector<const effects::EffectInfo*> fx, const StrengthFit& f,
                   double chi2_before) {
  EffectFit e;
  for (const auto* i : fx) {
    e.effects.push_back(i->name);
    e.parameters.push_back(i->unit.empty() ? i->parameter : fmt::format("{}_{}", i->parameter, i->unit));
  }
  e.estimate = f.estimate;
  e.uncertainty = f.uncertainty;
  e.chi2_before = chi2_before;
  score(e, f.chi2, static_cast<double>(m.size()));
  return e;
}

// A fit's chi^2 replaced by the one real runs at its strengths give, and what follows from it.
void rescore(EffectFit& e, double chi2, double n) {
  e.chi2_from_signatures = e.chi2_after;
  score(e, chi2, n);
}

std::vector<const effects::EffectInfo*> infos_of(const EffectFit& f) {
  std::vector<const effects::EffectInfo*> v;
  for (const auto& n : f.effects) v.push_back(effects::find(n));
  return v;
}

// Which measurement tells two fitted explanations apart: the quantity and condition where their
// predictions differ most, in units of the uncertainty such a measurement has in this dataset.
std::string discriminator(const Misfit& m, const EffectFit& a, const EffectFit& b) {
  const auto ia = infos_of(a), ib = infos_of(b);
  const auto pa = m.predict_all(ia, a.estimate), pb = m.predict_all(ib, b.estimate);
  // Typical uncertainty per quantity from the dataset; where a quantity is not measured, 2 % of
  // its size (forces) or 0.05 m/s or 3 mm, the resolution of the seed's instruments.
  std::map<Quantity, double> typical;
  for (const auto& meas : m.dataset().measurements)
    if (meas.uncertainty) typical[meas.quantity] = std::max(typical[meas.quantity], *meas.uncertainty);
  double best = 0.0;
  std::string text;
  for (std::size_t c = 0; c < pa.size(); ++c)
    for (std::size_t k = 0; k < pa[c].size(); ++k)
      for (Quantity q : kAllQuantities) {
        const auto& va = pa[c][k].values[q];
        const auto& vb = pb[c][k].values[q];
        if (!va || !vb) continue;
        double u = typical.count(q) ? typical[q] : 0.0;
        if (u <= 0.0)
          u = (q == Quantity::impact_point_y) ? 3e-3
              : (q == Quantity::impact_velocity || q == Quantity::exit_velocity)
                  ? 0.05
                  : std::max(0.02 * std::abs(*va), 0.1);
        const double sep = std::abs(*va - *vb) / u;
        if (sep > best) {
          best = sep;
          const double s = info(q).to_boundary;
          text = fmt::format("{} at {} ({}): {} predicts {:.3g} {}, {} predicts {:.3g} {} ({:.1f} "
                             "uncertainties apart){}",
                             name(q), m.dataset().stations[c].condition, m.models()[k]->name(),
                             a.label(), *va * s, info(q).unit, b.label(), *vb * s, info(q).unit, sep,
                             typical.count(q) ? "" : "; not measured in this dataset");
        }
      }
  if (best < 1.0)
    return fmt::format("{} and {}: no quantity in chutelab's vocabulary separates them by even one "
                       "uncertainty at these conditions; test other belt speeds or drop heights",
                       a.label(), b.label());
  return fmt::format("{} vs {}: measure {}", a.label(), b.label(), text);
}

std::string signature_words(Misfit::Signature s) {
  switch (s) {
    case Misfit::Signature::own_runs: return "own runs";
    case Misfit::Signature::cheap_models: return "analytical only";
    case Misfit::Signature::none: return "exact (measurement)";
  }
  return "";
}

// The change a fitted candidate makes to every normalised residual.
std::vector<double> fitted_change(const Misfit& m, const EffectFit& f, const std::vector<double>& r0) {
  std::vector<const effects::EffectInfo*> fx;
  for (const auto& n : f.effects) fx.push_back(effects::find(n));
  auto r = m.residuals(fx, f.estimate);
  for (std::size_t i = 0; i < r.size(); ++i) r[i] -= r0[i];
  return r;
}

double cosine(const std::vector<double>& a, const std::vector<double>& b) {
  double ab = 0, aa = 0, bb = 0;
  for (std::size_t i = 0; i < a.size(); ++i) ab += a[i] * b[i], aa += a[i] * a[i], bb += b[i] * b[i];
  return aa > 0 && bb > 0 ? ab / std::sqrt(aa * bb) : 0.0;
}

// What would tell two candidates apart that these data cannot: quantities of the vocabulary this
// dataset does not measure on which their fitted predictions differ, and each effect's own check.
std::string separating_measurement(const Misfit& m, const EffectFit& a, const EffectFit& b) {
  std::set<Quantity> measured;
  for (const auto& meas : m.dataset().measurements) measured.insert(meas.quantity);
  const auto pa = m.predict_all(infos_of(a), a.estimate), pb = m.predict_all(infos_of(b), b.estimate);
  std::map<Quantity, double> largest;  // largest relative difference over the conditions
  for (std::size_t c = 0; c < pa.size(); ++c)
    for (std::size_t k = 0; k < pa[c].size(); ++k)
      for (Quantity q : kAllQuantities) {
        if (measured.count(q)) continue;
        const auto &va = pa[c][k].values[q], &vb = pb[c][k].values[q];
        if (!va || !vb) continue;
        const double scale = std::max({std::abs(*va), std::abs(*vb), 1e-12});
        largest[q] = std::max(largest[q], std::abs(*va - *vb) / scale);
      }
  std::vector<std::string> ways;
  for (const auto& [q, rel] : largest)
    if (rel > 0.01) ways.push_back(fmt::format("{} (not measured here; they differ by up to {:.0f} %)", name(q), 100 * rel));
  for (const auto* f : {&a, &b})
    for (const auto& n : f->effects)
      if (const auto* i = effects::find(n); i && !i->check.empty()) ways.push_back(fmt::format("for {}: {}", n, i->check));
  if (ways.empty()) return "no quantity in chutelab's vocabulary separates them: test other belt speeds or drop heights";
  return fmt::format("{}", fmt::join(ways, "; "));
}

}  // namespace

DiagnosisResult diagnose(const Dataset& d, const std::vector<ModelPtr>& models,
                         const DiagnoseOptions& opt) {
  DiagnosisResult out;
  out.dataset = d.setup.name.empty() ? d.dir.filename().string() : d.setup.name;
  for (const auto& m : models) out.models.push_back(m->name());
  const int jobs = opt.jobs > 0 ? opt.jobs : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  // Every MPI rank fits the same candidates (their results must agree on every rank), so the
  // threads of one rank are its share of the cores.
  const Misfit m(d, models, {}, std::max(1, jobs / campaign::ranks()));
  out.n_data = static_cast<int>(m.size());
  out.n_without_uncertainty = m.left_out();
  const auto r0 = m.residuals({}, {});
  for (double x : r0) out.chi2_baseline += x * x;
  out.baseline_p_value = m.size() ? gsl_cdf_chisq_Q(out.chi2_baseline, static_cast<double>(m.size())) : 1.0;
  out.patterns = residual_patterns(m, r0, out.failure_summary);
  if (m.size() == 0) {
    out.verdict = "No measurement has an uncertainty, so nothing can be judged: state uncertainties "
                  "in measurements.csv.";
    return out;
  }

  const auto& lib = effects::library();
  if (m.has_expensive()) {
    // An expensive baseline's own response to every candidate it can represent: one probe run per
    // candidate and condition, side by side (they are independent).
    std::vector<const effects::EffectInfo*> all;
    for (const auto& e : lib) all.push_back(&e);
    m.prepare_signatures(all, jobs);
  }
  const bool progress = opt.progress && d.stations.size() >= 500;
  const auto started = std::chrono::steady_clock::now();
  // Where a long run is and how long it has taken so far: singles, then pairs, each of a known count.
  auto report = [&](const std::string& what, std::size_t k, std::size_t of) {
    if (!progress) return;
    const std::chrono::duration<double> spent = std::chrono::steady_clock::now() - started;
    std::cerr << fmt::format("diagnose: fitting {} ({}/{}, {:.0f} s so far)\n", what, k, of, spent.count());
  };
  for (const auto& e : lib) {
    report(e.name, static_cast<std::size_t>(&e - lib.data()) + 1, lib.size());
    const std::vector<const effects::EffectInfo*> fx = {&e};
    EffectFit f = make_fit(m, fx, fit_strengths(m, fx), out.chi2_baseline);
    if (m.has_expensive()) f.signature = signature_words(m.signature(e));
    out.singles.push_back(std::move(f));
  }
  // Control the family-wise false-alarm rate over every single candidate tried (Bonferroni).
  const double k = static_cast<double>(out.singles.size());
  auto judge = [&] {
    for (auto& s : out.singles) {
      s.p_adjusted = std::min(1.0, s.p_value * k);
      s.significant = s.p_adjusted < opt.alpha;
    }
    std::stable_sort(out.singles.begin(), out.singles.end(),
                     [](const auto& a, const auto& b) { return a.chi2_after < b.chi2_after; });
  };
  judge();
  // An expensive model that runs with effects ranks by signatures, which are differences carried
  // along a response (Misfit): close to the data they can misorder candidates whose real runs
  // differ. So the leading significant candidates are run for real at their fitted strengths, and
  // the ranking is the runs'. Nothing is run when nothing is significant.
  bool runs_with_effects = false;
  for (const auto& mm : models) runs_with_effects = runs_with_effects || (mm->expensive() && mm->runs_with_effects());
  const double n_data = static_cast<double>(m.size());
  if (runs_with_effects) {
    int confirmed = 0;
    for (auto& s : out.singles) {
      if (confirmed >= opt.confirm || !s.significant) break;
      const auto fx = infos_of(s);
      m.prepare_exact(fx, s.estimate, jobs);
      rescore(s, m.chi2_exact(fx, s.estimate), n_data);
      ++confirmed;
    }
    judge();
  }
  for (std::size_t i = 0; i < out.singles.size(); ++i) out.singles[i].rank = static_cast<int>(i) + 1;
  out.any_significant = !out.singles.empty() && out.singles.front().significant;

  // A pair is sought only when the best single leaves more misfit than noise would (chi^2 of its
  // n - 1 degrees of freedom at the same false-alarm rate): a second effect cannot be told from
  // noise once the first explains the data.
  const bool misfit_left = !out.singles.empty() &&
                           gsl_cdf_chisq_Q(out.singles.front().chi2_after, std::max(1.0, n_data - 1.0)) < opt.alpha;
  if (opt.pairs && out.any_significant && misfit_left) {
    // A pair must beat the best single effect: its extra parameter is tested against that single
    // (likelihood ratio, one degree of freedom), Bonferroni over all pairs, and by a clear BIC margin.
    const EffectFit& top = out.singles.front();
    std::map<std::string, double> single_estimate;
    for (const auto& s : out.singles) single_estimate[s.effects[0]] = s.estimate[0];
    const double npairs = k * (k - 1) / 2;
    auto test_pair = [&](EffectFit& f) {
      f.p_value = gsl_cdf_chisq_Q(std::max(0.0, top.chi2_after - f.chi2_after), 1.0);
      f.p_adjusted = std::min(1.0, f.p_value * npairs);
      f.significant = f.p_adjusted < opt.alpha && f.delta_bic < top.delta_bic - opt.pair_margin_bic;
    };
    std::size_t tried = 0;
    for (std::size_t i = 0; i < lib.size(); ++i)
      for (std::size_t j = i + 1; j < lib.size(); ++j) {
        report(fmt::format("the pair {} + {}", lib[i].name, lib[j].name), ++tried, lib.size() * (lib.size() - 1) / 2);
        const std::vector<const effects::EffectInfo*> fx = {&lib[i], &lib[j]};
        const std::vector<std::vector<double>> starts = {
            {single_estimate[lib[i].name], lib[j].neutral},
            {lib[i].neutral, single_estimate[lib[j].name]},
            {single_estimate[lib[i].name], single_estimate[lib[j].name]}};
        EffectFit f = make_fit(m, fx, fit_strengths(m, fx, starts), out.chi2_baseline);
        if (m.has_expensive())
          f.signature = signature_words(m.signature(lib[i])) + " + " + signature_words(m.signature(lib[j]));
        test_pair(f);
        if (f.significant) out.pairs.push_back(f);
      }
    std::stable_sort(out.pairs.begin(), out.pairs.end(),
                     [](const auto& a, const auto& b) { return a.chi2_after < b.chi2_after; });
    if (runs_with_effects && !out.pairs.empty()) {
      // Only a pair whose real runs still beat the best single by the same tests is kept.
      EffectFit f = out.pairs.front();
      const auto fx = infos_of(f);
      m.prepare_exact(fx, f.estimate, jobs);
      rescore(f, m.chi2_exact(fx, f.estimate), n_data);
      test_pair(f);
      out.pairs.clear();
      if (f.significant) out.pairs.push_back(f);
    }
  }

  if (out.any_significant) {
    const EffectFit& top = out.singles.front();
    for (std::size_t i = 1; i < out.singles.size(); ++i) {
      const auto& s = out.singles[i];
      if (s.significant && s.delta_bic - top.delta_bic < opt.tie_margin_bic) {
        out.indistinguishable.push_back(s.label());
        out.discriminators.push_back(discriminator(m, top, s));
      }
    }
    // Candidates that move the measured quantities in proportion to the best one explain the data
    // equally well at their own strengths: the data cannot tell them apart, whatever the ranking.
    {
      const auto d_top = fitted_change(m, top, r0);
      for (std::size_t i = 1; i < out.singles.size(); ++i) {
        const auto& s = out.singles[i];
        if (!s.significant) continue;
        if (std::abs(cosine(d_top, fitted_change(m, s, r0))) < opt.proportional_cosine) continue;
        if (s.chi2_after - top.chi2_after > std::max(4.0, 0.05 * top.chi2_after)) continue;
        out.proportional.push_back(fmt::format("{} and {} move every measured quantity in proportion (these data "
                                               "cannot tell them apart); to separate them, measure {}",
                                               top.label(), s.label(), separating_measurement(m, top, s)));
      }
    }
    const EffectFit& b = *out.best();
    std::string est;
    for (std::size_t i = 0; i < b.effects.size(); ++i) {
      const auto* info = effects::find(b.effects[i]);
      est += fmt::format("{}{} = {:.4g} ± {:.2g}{}", i ? ", " : "", info->parameter, b.estimate[i],
                         b.uncertainty[i], info->unit.empty() ? "" : " " + info->unit);
    }
    bool at_bound = false;
    for (std::size_t i = 0; i < b.effects.size(); ++i) {
      const auto* info = effects::find(b.effects[i]);
      const double span = info->upper - info->lower;
      at_bound = at_bound || b.estimate[i] <= info->lower + 1e-3 * span ||
                 b.estimate[i] >= info->upper - 1e-3 * span;
    }
    out.convincing = b.explained_fraction >= 0.7 && !at_bound;
    if (out.convincing) {
      out.verdict = fmt::format(
          "Missing effect: {} ({}). It lowers chi^2 from {:.1f} to {:.1f} for {} data, explains {:.0f} % "
          "of the excess misfit, delta BIC {:.1f}{}.",
          b.label(), est, b.chi2_before, b.chi2_after, out.n_data, 100 * b.explained_fraction, b.delta_bic,
          out.indistinguishable.empty()
              ? ""
              : fmt::format("; about as good: {}", fmt::join(out.indistinguishable, ", ")));
      for (const auto& p : out.proportional) out.verdict += " But " + p + ".";
    } else {
      out.verdict = fmt::format(
          "No effect in the library explains the misfit well: the best candidate, {} ({}), removes "
          "only {:.0f} % of the excess misfit{}. Most of the failure lies elsewhere: {}.",
          b.label(), est, 100 * b.explained_fraction,
          at_bound ? " and needs a strength at the edge of its physical range" : "", largest_misfit(m, r0));
    }
  } else if (out.baseline_p_value < opt.alpha) {
    out.verdict = fmt::format(
        "The models miss the data (chi^2 = {:.1f} for {} data, p = {:.2g}) but no effect in the "
        "library explains it significantly: look outside the library (geometry, inputs, model form).",
        out.chi2_baseline, out.n_data, out.baseline_p_value);
  } else {
    out.verdict = fmt::format(
        "No significant missing effect: the models explain the data within the stated uncertainties "
        "(chi^2 = {:.1f} for {} data, p = {:.2g}).",
        out.chi2_baseline, out.n_data, out.baseline_p_value);
  }
  out.used_surrogate = m.has_expensive();
  if (out.used_surrogate) {
    std::vector<std::string> slow, slow_none, fixed;
    for (const auto& mm : models)
      if (mm->expensive()) (mm->runs_with_effects() ? slow : fixed).push_back(mm->name());
    for (const auto& mm : models)
      if (mm->expensive() && !mm->runs_with_effects())
        out.caveats.push_back(fmt::format(
            "{} is another code's exported results ({}): chutelab cannot re-run it, so every {} prediction with a "
            "candidate effect is its result plus the analytical models' response to the effect (DESIGN.md §5), "
            "including the recommended fit's, which no run confirms.",
            mm->name(), mm->description(), mm->name()));
    std::vector<std::string> own, cheap;
    for (const auto& e : lib)
      (m.signature(e) == Misfit::Signature::own_runs ? own : m.signature(e) == Misfit::Signature::cheap_models ? cheap
                                                                                                           : slow_none)
          .push_back(e.name);
    if (!own.empty() && !slow.empty())
      out.caveats.push_back(fmt::format(
          "{}'s response to {} comes from its own runs, one per condition with the effect at a probe strength "
          "(twice its typical value) and the baseline's seed, carried to other strengths along the analytical "
          "models' response.",
          fmt::join(slow, ", "), fmt::join(own, ", ")));
    if (!cheap.empty() && !slow.empty())
      out.caveats.push_back(fmt::format(
          "{} cannot represent {}: their signatures are the analytical models' response applied as a difference "
          "(DESIGN.md §5), marked \"analytical only\" in the ranking.",
          fmt::join(slow, ", "), fmt::join(cheap, ", ")));
    std::vector<std::string> rerun;
    for (const auto* list : {&out.singles, &out.pairs})
      for (const auto& f : *list)
        if (f.chi2_from_signatures)
          rerun.push_back(fmt::format("{} (chi^2 {:.1f} from the runs, {:.1f} from the signatures)", f.label(),
                                      f.chi2_after, *f.chi2_from_signatures));
    if (!rerun.empty() && !slow.empty())
      out.caveats.push_back(fmt::format(
          "The leading candidates were run with {} at their fitted strengths, and they are ranked by those runs: {}.",
          fmt::join(slow, ", "), fmt::join(rerun, "; ")));
    if (const EffectFit* b = out.best(); b && !slow.empty()) {
      const auto fx = infos_of(*b);
      m.prepare_exact(fx, b->estimate, jobs);
      out.confirmed_chi2 = m.chi2_exact(fx, b->estimate);
      if (!b->chi2_from_signatures)
        out.caveats.push_back(fmt::format(
            "Confirmed by running {} with {} on: chi^2 = {:.1f} (the estimate from differences was {:.1f}).",
            fmt::join(slow, ", "), b->label(), *out.confirmed_chi2, b->chi2_after));
    }
  }
  if (const EffectFit* b = out.best()) {
    for (std::size_t i = 0; i < b->effects.size(); ++i) {
      const auto* info = effects::find(b->effects[i]);
      const double span = info->upper - info->lower;
      if (b->estimate[i] <= info->lower + 1e-3 * span || b->estimate[i] >= info->upper - 1e-3 * span)
        out.caveats.push_back(fmt::format(
            "{} sits at the edge of its physical range ({} = {:.4g} {}): the data ask for more than "
            "this effect can physically give, so it is probably standing in for something else.",
            b->effects[i], info->parameter, b->estimate[i], info->unit));
    }
    const double left = b->chi2_after - (out.n_data - static_cast<double>(b->effects.size()));
    if (b->explained_fraction < 0.7 && left > 0)
      out.caveats.push_back(fmt::format(
          "The best explanation removes only {:.0f} % of the excess misfit (chi^2 {:.1f} remains for "
          "{} data): a large part of the failure lies outside the library - look at the quantities "
          "with the largest residuals above, and at how they were measured.",
          100 * b->explained_fraction, b->chi2_after, out.n_data));
  }
  out.caveats.push_back(fmt::format(
      "Significance: likelihood-ratio test per candidate, Bonferroni-corrected over the {} "
      "candidates tried (family-wise false-alarm rate {:.0f} %).",
      out.singles.size(), 100 * opt.alpha));
  out.caveats.push_back("Only the effects in chutelab's library were tried; a misfit they cannot "
                        "explain points to physics outside it.");
  if (out.n_without_uncertainty > 0)
    out.caveats.push_back(fmt::format("{} measured values had no uncertainty or no prediction and were "
                                      "left out of chi^2.",
                                      out.n_without_uncertainty));
  return out;
}

std::string diagnosis_csv(const DiagnosisResult& r) {
  std::string o =
      "rank,effect,parameter,estimate,uncertainty,chi2_before,chi2_after,delta_bic,"
      "explained_fraction,significant,p_value,p_adjusted,signature\n";
  auto row = [&](const EffectFit& f, const std::string& rank) {
    std::vector<std::string> est, unc;
    for (double v : f.estimate) est.push_back(csv_number(v));
    for (double v : f.uncertainty) unc.push_back(std::isfinite(v) ? csv_number(v) : "inf");
    o += fmt::format("{},{},{},{},{},{},{},{},{},{},{},{},{}\n", rank, fmt::join(f.effects, "+"),
                     fmt::join(f.parameters, "+"), fmt::join(est, "+"), fmt::join(unc, "+"),
                     csv_number(f.chi2_before), csv_number(f.chi2_after), csv_number(f.delta_bic),
                     csv_number(f.explained_fraction), f.significant ? "yes" : "no",
                     csv_number(f.p_value), csv_number(f.p_adjusted), f.signature);
  };
  for (const auto& f : r.singles) row(f, std::to_string(f.rank));
  for (const auto& f : r.pairs) row(f, "pair");
  return o;
}

std::string diagnosis_markdown(const DiagnosisResult& r) {
  std::string o = fmt::format("# chutelab diagnosis: {}\n\n", r.dataset);
  o += fmt::format("**{}**\n\n", r.verdict);
  o += fmt::format("Models: {}; each measured value is compared with the first of them that predicts "
                   "it. {} data with uncertainties; chi^2 of the models as they are: {:.1f} (p = {:.2g}).\n\n",
                   fmt::join(r.models, ", "), r.n_data, r.chi2_baseline, r.baseline_p_value);
  o += "## Where the models fail\n\n";
  if (r.failure_summary.empty()) o += "Every quantity is within about two uncertainties of its measurement.\n";
  for (const auto& s : r.failure_summary) o += "- " + s + "\n";
  o += "\n| model | quantity | n | mean E/u | RMS E/u | r(belt speed) | r(mass flow) | r(flight time) | r(drop height) |\n";
  o += "|---|---|---|---|---|---|---|---|---|\n";
  for (std::size_t i = 0; i + 3 < r.patterns.size(); i += 4) {
    const auto& p = r.patterns[i];
    o += fmt::format("| {} | {} | {} | {:+.2f} | {:.2f} | {:+.2f} | {:+.2f} | {:+.2f} | {:+.2f} |\n", p.model,
                     p.quantity, p.n, p.mean_normalised, p.rms_normalised, r.patterns[i].correlation,
                     r.patterns[i + 1].correlation, r.patterns[i + 2].correlation,
                     r.patterns[i + 3].correlation);
  }
  o += "\n## Candidate effects, ranked\n\n";
  const bool sig = r.used_surrogate;
  o += fmt::format("| rank | effect | estimate ± sd | chi^2 after | delta BIC | explained | p (adjusted) | significant |{}\n",
                   sig ? " signature |" : "");
  o += fmt::format("|---|---|---|---|---|---|---|---|{}\n", sig ? "---|" : "");
  auto est = [](const EffectFit& f) {
    std::vector<std::string> v;
    for (std::size_t i = 0; i < f.estimate.size(); ++i)
      v.push_back(fmt::format("{} = {:.4g} ± {}", f.parameters[i], f.estimate[i],
                              std::isfinite(f.uncertainty[i]) ? fmt::format("{:.2g}", f.uncertainty[i])
                                                              : std::string("unconstrained")));
    return fmt::format("{}", fmt::join(v, "; "));
  };
  for (const auto& f : r.singles)
    o += fmt::format("| {} | {} | {} | {:.1f} | {:.1f} | {:.0f} % | {:.2g} | {} |{}\n", f.rank, f.label(), est(f),
                     f.chi2_after, f.delta_bic, 100 * f.explained_fraction, f.p_adjusted,
                     f.significant ? "yes" : "no", sig ? " " + f.signature + " |" : "");
  if (!r.pairs.empty()) {
    o += "\nPairs that beat every single effect by a clear margin:\n\n";
    for (const auto& f : r.pairs)
      o += fmt::format("- {} ({}): chi^2 {:.1f}, delta BIC {:.1f}\n", f.label(), est(f), f.chi2_after, f.delta_bic);
  }
  if (!r.indistinguishable.empty() || !r.proportional.empty()) {
    o += "\n## Indistinguishable alternatives\n\n";
    for (const auto& s : r.proportional) o += "- " + s + "\n";
    for (const auto& s : r.discriminators) o += "- " + s + "\n";
  }
  o += "\n## Caveats\n\n";
  for (const auto& c : r.caveats) o += "- " + c + "\n";
  return o;
}

}  // namespace chutelab::validation
