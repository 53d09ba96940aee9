// validate() and diagnose(): the library's tables (predictions.csv, errors.csv, summary.csv,
// diagnosis.csv) as numbers, the diagnosis's verdict and findings as plain Python values.
#include "api/diagnose.h"
#include "api/files.h"
#include "api/validate.h"
#include "python/bind_common.h"

namespace chutelab::bindings {
namespace {

// predictions.csv's rows, as numbers.
py::dict predictions_table(const api::ValidationResult& r) {
  std::vector<std::string> condition, model, quantity;
  std::vector<double> value, uncertainty, x_mm;
  for (const auto& p : r.predictions)
    for (Quantity q : kAllQuantities) {
      const auto& v = p.prediction.values[q];
      if (!v) continue;
      const double s = info(q).to_boundary;
      condition.push_back(p.condition), model.push_back(p.model), quantity.emplace_back(name(q));
      value.push_back(*v * s), uncertainty.push_back(or_nan(p.prediction.uncertainty[q], s));
      x_mm.push_back(kNan);
    }
  for (const auto& c : r.comparisons)
    if (c.boundary && c.predicted) {
      condition.push_back(c.condition), model.push_back(c.model), quantity.push_back(c.quantity);
      value.push_back(*c.predicted * c.scale), uncertainty.push_back(or_nan(c.u_num_stat(), c.scale));
      x_mm.push_back(c.x * 1e3);
    }
  Table t;
  t.text("condition", condition), t.text("model", model), t.text("quantity", quantity);
  t.real("value", value), t.real("uncertainty", uncertainty), t.real("x_mm", x_mm);
  return t.dict();
}

// errors.csv's rows, as numbers; the tolerance verdict as flags and the limits as numbers.
py::dict errors_table(const api::ValidationResult& r, const api::Tolerances* tol) {
  std::vector<std::string> condition, model, quantity, limit;
  std::vector<double> measured, uncertainty, predicted, error, relative, normalised, x_mm, u_val, ratio, stat, disc,
      input, y_mm, z_mm, t_rel, t_abs, t_norm;
  std::vector<bool> checked, within;
  for (const auto& c : r.comparisons) {
    const double s = c.scale;
    condition.push_back(c.condition), model.push_back(c.model), quantity.push_back(c.quantity);
    measured.push_back(c.measured * s), uncertainty.push_back(or_nan(c.uncertainty, s));
    predicted.push_back(or_nan(c.predicted, s));
    error.push_back(c.predicted ? c.error() * s : kNan);
    relative.push_back(or_nan(c.relative_error())), normalised.push_back(or_nan(c.normalised_error()));
    x_mm.push_back(c.boundary ? c.x * 1e3 : kNan);
    u_val.push_back(or_nan(c.validation_uncertainty(), s)), ratio.push_back(or_nan(c.vv20_ratio()));
    // The parts of u_val only beside a prediction: without one nothing was propagated.
    stat.push_back(c.predicted ? or_nan(c.u_num_stat(), s) : kNan);
    disc.push_back(c.predicted ? or_nan(c.u_num_disc, s) : kNan);
    input.push_back(c.predicted ? or_nan(c.u_input, s) : kNan);
    y_mm.push_back(or_nan(c.plate_y, 1e3)), z_mm.push_back(or_nan(c.plate_z, 1e3));
    checked.push_back(c.verdict.checked), within.push_back(c.verdict.passed);
    limit.push_back(c.verdict.passed ? std::string() : c.verdict.limit);
    const api::Tolerance* t = c.verdict.checked && tol ? tol->find(c.model, c.quantity) : nullptr;
    t_rel.push_back(t ? or_nan(t->relative) : kNan), t_abs.push_back(t ? or_nan(t->absolute) : kNan);
    t_norm.push_back(t ? or_nan(t->normalised) : kNan);
  }
  Table t;
  t.text("condition", condition), t.text("model", model), t.text("quantity", quantity);
  t.real("measured", measured), t.real("uncertainty", uncertainty), t.real("predicted", predicted);
  t.real("error", error), t.real("relative_error", relative), t.real("normalised_error", normalised);
  t.real("x_mm", x_mm), t.real("validation_uncertainty", u_val), t.real("vv20_ratio", ratio);
  t.flag("tolerance_checked", checked), t.flag("within_tolerance", within), t.text("tolerance_failed", limit);
  t.real("tolerance_relative", t_rel), t.real("tolerance_absolute", t_abs), t.real("tolerance_normalised", t_norm);
  t.real("u_num_stat", stat), t.real("u_num_disc", disc), t.real("u_input", input);
  t.real("y_mm", y_mm), t.real("z_mm", z_mm);
  return t.dict();
}

py::dict summary_table(const api::ValidationResult& r) {
  std::vector<std::string> model, quantity;
  std::vector<long long> n;
  std::vector<double> rms, rms_norm, max_rel;
  std::vector<bool> checked, within;
  for (const auto& s : r.summary) {
    model.push_back(s.model), quantity.push_back(s.quantity), n.push_back(s.n);
    rms.push_back(s.rms_error), rms_norm.push_back(or_nan(s.rms_normalised_error));
    max_rel.push_back(or_nan(s.max_abs_relative_error));
    checked.push_back(s.within_tolerance.has_value()), within.push_back(s.within_tolerance.value_or(true));
  }
  Table t;
  t.text("model", model), t.text("quantity", quantity), t.whole("n", n);
  t.real("rms_error", rms), t.real("rms_normalised_error", rms_norm), t.real("max_abs_relative_error", max_rel);
  t.flag("tolerance_checked", checked), t.flag("within_tolerance", within);
  return t.dict();
}

// The ranking of diagnosis.csv as numbers: the single effects, and the pairs with one column per
// member (diagnosis.csv joins a pair's two values with "+").
py::dict ranking_table(const std::vector<api::EffectFit>& fits, bool pairs) {
  const std::size_t k = pairs ? 2 : 1;
  std::vector<std::vector<std::string>> effect(k), parameter(k);
  std::vector<std::vector<double>> estimate(k), uncertainty(k);
  std::vector<long long> rank;
  std::vector<double> chi2_before, chi2_after, bic, explained, p, p_adj, ub_est, ub_unc;
  std::vector<bool> significant, wants_outside;
  std::vector<std::string> signature, beaten;
  for (const auto& f : fits) {
    for (std::size_t i = 0; i < k; ++i) {
      effect[i].push_back(i < f.effects.size() ? f.effects[i] : "");
      parameter[i].push_back(i < f.parameters.size() ? f.parameters[i] : "");
      estimate[i].push_back(i < f.estimate.size() ? f.estimate[i] : kNan);
      uncertainty[i].push_back(i < f.uncertainty.size() ? f.uncertainty[i] : kNan);
    }
    rank.push_back(f.rank);
    chi2_before.push_back(f.chi2_before), chi2_after.push_back(f.chi2_after), bic.push_back(f.delta_bic);
    explained.push_back(f.explained_fraction), p.push_back(f.p_value), p_adj.push_back(f.p_adjusted);
    significant.push_back(f.significant), signature.push_back(f.signature);
    ub_est.push_back(f.unbounded ? f.unbounded->estimate : kNan);
    ub_unc.push_back(f.unbounded ? f.unbounded->uncertainty : kNan);
    wants_outside.push_back(f.unbounded && f.unbounded->wants_outside);
    beaten.push_back(f.beaten_outside_range_by);
  }
  Table t;
  if (pairs) {
    t.text("effect_1", effect[0]), t.text("effect_2", effect[1]);
    t.text("parameter_1", parameter[0]), t.text("parameter_2", parameter[1]);
    t.real("estimate_1", estimate[0]), t.real("uncertainty_1", uncertainty[0]);
    t.real("estimate_2", estimate[1]), t.real("uncertainty_2", uncertainty[1]);
  } else {
    t.whole("rank", rank), t.text("effect", effect[0]), t.text("parameter", parameter[0]);
    t.real("estimate", estimate[0]), t.real("uncertainty", uncertainty[0]);
  }
  t.real("chi2_before", chi2_before), t.real("chi2_after", chi2_after), t.real("delta_bic", bic);
  t.real("explained_fraction", explained), t.flag("significant", significant), t.real("p_value", p);
  t.real("p_adjusted", p_adj), t.text("signature", signature);
  if (!pairs) {
    t.real("outside_range_estimate", ub_est), t.real("outside_range_uncertainty", ub_unc);
    t.flag("wants_outside_range", wants_outside);
  }
  t.text("beaten_outside_range_by", beaten);
  return t.dict();
}

const char* verdict_name(api::Verdict v) {
  switch (v) {
    case api::Verdict::no_data: return "no_data";
    case api::Verdict::consistent: return "consistent";
    case api::Verdict::missing_effect: return "missing_effect";
    case api::Verdict::partial_explanation: return "partial_explanation";
    case api::Verdict::out_of_range: return "out_of_range";
    case api::Verdict::outside_library: return "outside_library";
  }
  return "";
}

// The numbers behind the verdict, as plain Python values.
py::dict diagnosis_numbers(const api::DiagnosisResult& x) {
  py::dict r;
  r["verdict_code"] = verdict_name(x.verdict_code);
  r["goodness_of_fit"] = x.goodness_of_fit;
  r["thin_data"] = x.thin_data;
  r["findings"] = x.findings;
  r["wants_outside"] = x.wants_outside;
  py::list outliers;
  for (const auto& o : x.outliers) {
    py::dict d;
    d["condition"] = o.condition, d["quantity"] = o.quantity, d["file"] = o.where.file, d["line"] = o.where.line;
    d["measured"] = o.measured, d["predicted"] = o.predicted, d["deviation"] = o.deviation;
    d["relative"] = o.relative;
    outliers.append(d);
  }
  r["outliers"] = outliers;
  py::list model_form;
  for (const auto& m : x.model_form) {
    py::dict d;
    d["quantity"] = m.quantity, d["model"] = m.model, d["n"] = m.n, d["discrepancy"] = m.tau;
    d["mean_error"] = m.mean_error, d["mean_relative_error"] = m.mean_relative;
    model_form.append(d);
  }
  r["model_form"] = model_form;
  py::dict scale;
  scale["factor"] = x.scale.factor, scale["dof"] = x.scale.dof, scale["applied"] = x.scale.applied;
  scale["too_large"] = x.scale.too_large, scale["p_high"] = x.scale.p_high, scale["p_low"] = x.scale.p_low;
  r["uncertainty_scale"] = scale;
  py::list fit;
  if (const auto* b = x.best())
    for (std::size_t i = 0; i < b->effects.size(); ++i)
      fit.append(strength(b->effects[i], b->parameters[i], b->estimate[i], b->uncertainty[i], true));
  r["best_fit"] = fit;
  r["ranking"] = ranking_table(x.singles, false);
  r["pairs"] = ranking_table(x.pairs, true);
  r["verdict"] = x.verdict;
  r["evidence"] = x.evidence;
  r["models"] = x.models;
  r["n_data"] = x.n_data;
  r["n_without_uncertainty"] = x.n_without_uncertainty;
  r["chi2_baseline"] = x.chi2_baseline;
  r["baseline_p_value"] = x.baseline_p_value;
  r["any_significant"] = x.any_significant;
  r["convincing"] = x.convincing;
  const auto* best = x.best();
  r["best"] = best ? py::object(py::str(best->label())) : py::object(py::none());
  r["failure_summary"] = x.failure_summary;
  r["indistinguishable"] = x.indistinguishable;
  r["discriminators"] = x.discriminators;
  r["caveats"] = x.caveats;
  Table p;
  std::vector<std::string> pm, pq, pd;
  std::vector<long long> pn;
  std::vector<double> mean, rms, corr;
  std::vector<bool> notable;
  for (const auto& q : x.patterns) {
    pm.push_back(q.model), pq.push_back(q.quantity), pd.push_back(q.driver), pn.push_back(q.n);
    mean.push_back(q.mean_normalised), rms.push_back(q.rms_normalised), corr.push_back(q.correlation);
    notable.push_back(q.notable);
  }
  p.text("model", pm), p.text("quantity", pq), p.text("driver", pd), p.whole("n", pn);
  p.real("mean_normalised", mean), p.real("rms_normalised", rms), p.real("correlation", corr);
  p.flag("notable", notable);
  r["patterns"] = p.dict();
  r["markdown"] = api::diagnosis_markdown(x);
  return r;
}

// What validate() keeps: the library's result (for the tables, and the report when asked) and the
// inputs it read (which write_report never overwrites).
using Validated = Kept<api::ValidateResult>;

py::dict validation_numbers(const Validated& v) {
  const api::ValidateResult& res = v.result;
  const api::ValidationResult& result = res.final_result();
  // The acceptance judges the models as delivered unless accept_with_effects (api/validate.h).
  const api::ValidationResult& judged = res.accepted();
  const api::ValidationResult* beside = res.beside_acceptance();
  const api::Tolerances* tol = res.tolerances ? &*res.tolerances : nullptr;
  py::dict r;
  r["predictions"] = predictions_table(result);
  r["errors"] = errors_table(result, tol);
  r["summary"] = summary_table(result);
  r["models"] = result.models;
  py::list fx;
  for (const auto& e : res.effects) fx.append(strength(e.name, e.parameter, e.value, e.uncertainty, e.fitted));
  r["effects"] = fx;
  r["notes"] = res.notes;
  r["brief"] = result.brief(&result == &judged);
  r["acceptance_checked"] = judged.acceptance_checked;
  r["acceptance_failed"] = judged.acceptance_failed;
  r["acceptance_problems"] = judged.acceptance_problems;
  r["accepted_with_effects"] = res.accepted_with_effects && res.with_effects;
  r["outside_tolerance_beside"] =
      beside && beside->acceptance_checked ? py::object(py::int_(beside->failed_count())) : py::object(py::none());
  r["combined_rms_normalised_error"] = or_nan(result.combined_rms_normalised());
  py::dict overall;
  for (const auto& m : result.models) overall[py::str(m)] = or_nan(result.overall_rms_normalised(m));
  r["rms_normalised_error"] = overall;
  r["diagnosis"] = res.diagnosis ? py::object(diagnosis_numbers(*res.diagnosis)) : py::object(py::none());
  return r;
}

std::unique_ptr<Validated> validate(const api::Dataset& d, const std::vector<std::string>& model_names,
                                    const std::vector<std::string>& effect_args, const std::string& tolerances,
                                    bool diagnose, bool accept_with_effects, const std::string& dem_quality, std::optional<int> dem_threads,
                                    const std::string& dem_cache, bool no_dem_cache) {
  api::ValidateOptions o;
  o.models = model_names;
  o.effects = effect_args;
  o.tolerances = tolerances;
  o.diagnose = diagnose;
  o.accept_with_effects = accept_with_effects;
  o.dem = dem_options(dem_quality, dem_threads, dem_cache, no_dem_cache);
  return run_kept<api::ValidateResult>(o, [&](const api::ValidateOptions& opt) { return api::validate(d, opt); });
}

using Diagnosed = Kept<api::DiagnoseResult>;

py::dict diagnosed_numbers(const Diagnosed& diagnosed) {
  py::dict r = diagnosis_numbers(diagnosed.result.diagnosis);
  const auto& sc = diagnosed.result.self_check;
  if (sc) {
    py::dict c;
    c["null_replicas"] = sc->null_replicas, c["false_alarms"] = sc->false_alarms;
    c["false_alarm_rate"] = sc->false_alarm_rate(), c["false_alarm_upper"] = sc->false_alarm_upper;
    c["truth"] = sc->truth, c["truth_strength"] = sc->truth_strength;
    c["effect_replicas"] = sc->effect_replicas, c["named"] = sc->named, c["named_other"] = sc->named_other;
    c["covered"] = sc->covered, c["power"] = sc->power(), c["coverage"] = sc->coverage();
    c["markdown"] = api::self_check_markdown(*sc, diagnosed.result.alpha);
    r["self_check"] = c;
  } else {
    r["self_check"] = py::none();
  }
  return r;
}

std::unique_ptr<Diagnosed> diagnose(const api::Dataset& d, const std::vector<std::string>& model_names,
                                    double alpha, bool pairs, const std::string& dem_quality,
                                    std::optional<int> dem_threads, const std::string& dem_cache, bool no_dem_cache,
                                    const py::object& self_check_arg, const py::object& seed_arg,
                                    const std::vector<std::string>& corrected) {
  api::DiagnoseOptions o;
  o.inputs = corrected;
  o.self_check = static_cast<int>(whole_number(self_check_arg, options::rules::self_check));
  o.seed = seed_value(seed_arg);
  o.models = model_names;
  o.alpha = alpha;
  o.pairs = pairs;
  o.dem = dem_options(dem_quality, dem_threads, dem_cache, no_dem_cache);
  return run_kept<api::DiagnoseResult>(o, [&](const api::DiagnoseOptions& opt) { return api::diagnose(d, opt); });
}

}  // namespace

void bind_validate(py::module_& m) {
  kept_class<api::ValidateResult>(m, "Validated", "validate").def("numbers", &validation_numbers);
  kept_class<api::DiagnoseResult>(m, "Diagnosed", "diagnose").def("numbers", &diagnosed_numbers);
  m.def("validate", &validate, py::arg("dataset"), py::arg("models"), py::arg("effects"), py::arg("tolerances"),
        py::arg("diagnose"), py::arg("accept_with_effects"), py::arg("dem_quality"), py::arg("dem_threads"), py::arg("dem_cache"),
        py::arg("no_dem_cache"));
  m.def("diagnose", &diagnose, py::arg("dataset"), py::arg("models"), py::arg("alpha"), py::arg("pairs"),
        py::arg("dem_quality"), py::arg("dem_threads"), py::arg("dem_cache"), py::arg("no_dem_cache"),
        py::arg("self_check"), py::arg("seed"), py::arg("inputs"));
}

}  // namespace chutelab::bindings
