#pragma once
// The working parts the diagnosis's stages share (validation/diagnosis.cpp: the stages in order and
// the verdict; diagnosis_explain.cpp: the single candidates and the noise model's rounds;
// diagnosis_causes.cpp: every cause the data support; diagnosis_shape.cpp: whether a named cause has
// the shape the data want; diagnosis_findings.cpp: what the named explanation leaves, its profile,
// outliers and rivals). Internal to the diagnosis, not part of the library's interface.
#include <chrono>
#include <cmath>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "effects/registry.h"
#include "validation/diagnosis.h"
#include "validation/misfit.h"
#include "validation/noise_model.h"
#include "validation/strength_fit.h"

namespace chutelab::validation::detail {

using Fx = std::vector<const effects::EffectInfo*>;

// The candidates of a fit (library effects, or records at one condition: effects/at_condition.h).
Fx infos_of(const EffectFit& f);

// A step of the diagnosis under one noise model: the cost fits minimise and the tests' yardsticks.
struct Stage {
  const Misfit& m;
  const DiagnoseOptions& opt;
  NoiseModel nm;
  Cost cost;
  double chi2_0 = 0.0;  // the models as they are
  double n = 0.0;       // points that count
  std::size_t candidates = 0;

  std::map<std::string, std::pair<double, bool>> prior;  // recorded input -> (width, stated)
  // A single's estimate and the weighted residuals there, where its fit kept them (many conditions):
  // the screens read them instead of evaluating every single again.
  mutable std::map<std::string, std::pair<std::vector<double>, std::vector<double>>> at_estimate;

  Stage(const Misfit& misfit, const DiagnoseOptions& o, NoiseModel noise);
  double dof(double k) const { return std::max(1.0, n - k); }
  // The chance of a fall of chi^2 this large from k more strengths: a likelihood ratio against the
  // stated uncertainties, or an F test against the scatter itself once they were widened.
  double p_improvement(double drop, double k, double after) const;
  // The plausible error of a record (its library name, or the record's at one condition).
  std::optional<std::pair<double, bool>> prior_of(const std::string& candidate) const;
};

// A fit's chi^2 and what follows from it: delta BIC, the record's implausibility, the share of the
// misfit beyond noise removed, and its p against the models as they are.
void score(EffectFit& e, double chi2, const Stage& s);
EffectFit make_fit(const Fx& fx, const StrengthFit& f, const Stage& s);
// A fit's chi^2 replaced by the one real runs at its strengths give, and what follows from it.
void rescore(EffectFit& e, double chi2, const Stage& s);
std::string signature_words(PredictionSource::Signature s);

// Where a long run is and how long it has taken so far.
struct Progress {
  bool on = false;
  std::chrono::steady_clock::time_point started = std::chrono::steady_clock::now();
  // Which pass of the noise model's rounds (validation/diagnosis_explain.cpp, settle) the fits belong to:
  // each round that leaves out a reading or adds a discrepancy fits every candidate again.
  int round = 1;
  void operator()(const std::string& what, std::size_t k, std::size_t of) const;
};

// Is what an explanation with k strengths leaves (its residuals r) noise? Per quantity, and the
// whole chi^2 while the uncertainties stand as stated.
std::vector<Leftover> leftovers_of(const Stage& s, const std::vector<double>& r, double k, double chi2,
                                   const Drivers& drivers);

// Where each effect of an explanation finds its evidence, when nine tenths of it lie in one quantity
// at the expense of another (validation/diagnosis_findings.cpp).
struct Evidence {
  std::size_t effect = 0;      // index into the explanation's effects
  std::size_t group = 0;
  double share = 0.0;
  std::vector<double> before;  // residuals (unweighted) with the effect switched off
};
std::optional<Evidence> concentrated(const Stage& s, const Fx& fx, const std::vector<double>& v);

// The change a fitted explanation makes to every normalised residual, from the residuals r0.
std::vector<double> fitted_change(const Misfit& m, const EffectFit& f, const std::vector<double>& r0);
double cosine(const std::vector<double>& a, const std::vector<double>& b);

// One strength fitted with the others held at theirs (fx, at): a grid over its physical range,
// golden-section steps in the best cell, the sd from the curvature there (chi^2 rises by one at one
// sd). For a part of the cost (one condition's readings) it costs what that condition costs.
struct Held {
  double estimate = 0.0, uncertainty = INFINITY, chi2 = 0.0;
};
Held fit_held(const Cost& cost, Fx fx, std::vector<double> at, const effects::EffectInfo* e);

// Whether each cause of an explanation has the shape the data want (validation/diagnosis_shape.cpp):
// its strength fitted condition by condition, the others held, against the operating variables.
std::vector<ShapeFinding> shape_of(const Stage& s, const EffectFit& best);

// Every cause the data support beyond the best single (validation/diagnosis_causes.cpp): a forward
// search that adds, one at a time, the library candidate or the record at one condition whose joint
// fit lowers chi^2 most, while the fall is significant. `top`: the best single when it is
// significant and may be named, else null (then only records at one condition are tried first).
struct Causes {
  std::vector<EffectFit> chosen;      // each step's explanation, the largest (the chosen one) first
  std::optional<EffectFit> next;      // the best further cause, not significant: what the noise model
                                      // is judged on, so that it takes only scatter no candidate explains
  // Other causes in the chosen explanation's last place that fit about as well (within the tie margin
  // of chi^2, significant too): these data cannot tell them from the one named.
  std::vector<EffectFit> alternatives;
};
Causes more_causes(const Stage& s, const std::vector<EffectFit>& singles, const EffectFit* top,
                   const Progress& progress, int jobs);

// An explanation's BIC: chi^2 with the records' implausibility charged, plus ln n per strength.
double bic_of(const EffectFit& f, const Stage& s);

// The records wrong at reading i's condition alone that would explain that reading, left out as an
// outlier, with the condition's other readings (validation/diagnosis_causes.cpp): fitted there with
// the reading back in and `best`'s causes held, each bringing the reading inside the outlier limit
// and leaving the condition's readings as a whole within the noise. One reading cannot tell a wrong
// record there from a wrong reading; the best first, then those within the tie margin of it.
std::vector<EffectFit> records_for_reading(const Stage& s, const EffectFit* best, std::size_t i);

// The explanations under one noise model (validation/diagnosis_explain.cpp): every single inside its range, those at an edge also
// outside it, and every further cause the data support (validation/diagnosis_causes.cpp).
struct Explanations {
  std::vector<EffectFit> singles, pairs;  // pairs: explanations by more causes than the best single, largest first
  const EffectFit* outside = nullptr;  // in singles: the best fit outside a range that the data want
  // The leading explanation (lowest BIC among the significant ones, a fit outside a range included).
  Fx fx;
  std::vector<double> strengths;
  double chi2 = 0.0;
  bool any = false;
  // The leading explanation with the best further cause, significant or not: the noise model is
  // judged on what it leaves, so that it takes only scatter that no candidate explains.
  Fx full_fx;
  std::vector<double> full_strengths;
  std::optional<EffectFit> next;  // that further cause's explanation
  std::vector<EffectFit> alternatives;  // about as good in the last cause's place (Causes::alternatives)
};
// `confirm`: run an expensive model's leading candidates for real (`jobs` at a time).
Explanations explain(const Stage& s, const Progress& progress, int jobs, bool confirm);

// The explanations and the noise model that agree with each other: explain, take the leading
// explanation's residuals, leave out one outlier or re-assess the noise, until nothing changes.
struct Settled {
  NoiseModel nm;
  ScaleEstimate scale;
  int rounds = 0;
  bool settled = false;
  // The explanations fitted under the settled noise model, in its last round.
  std::optional<Explanations> last;
};
Settled settle(const Misfit& m, const DiagnoseOptions& opt, const Progress& progress);

// The best single when it is significant, else null; an explanation's residuals (none: the models
// as they are).
const EffectFit* leader(const std::vector<EffectFit>& singles);
std::vector<double> residuals_at(const Misfit& m, const EffectFit* f);

// What the diagnosis says about its recommended explanation (validation/diagnosis_findings.cpp).
// For a recommended record: one error for the rig, or one per condition (analytical models only).
std::optional<RecordScope> record_scope_of(const Stage& s, const EffectFit* best);
// The expensive model's own chi^2 at a few strengths around a single's estimate: the estimate and sd
// from its curvature, not from the linear signature.
void profile_best(EffectFit& f, const Stage& s, int jobs);
// The recommended explanation's residuals: from real runs where it was run, else the signatures.
std::vector<double> best_residuals(const Stage& s, const EffectFit* best);
std::vector<Outlier> name_outliers(const Stage& s, const EffectFit* best, const std::vector<EffectFit>& singles);
std::vector<Influence> influential(const Stage& s, const EffectFit& best);
// Each quantity's mean error before and after an explanation, in its own units. `exact`: its
// residuals from real runs, where there are some; `only`: one condition's readings.
std::vector<QuantityShift> shifts_of(const Stage& s, const Fx& fx, const std::vector<double>& strengths,
                                     const std::vector<double>& exact = {}, const std::string& only = "");
std::vector<Discrepancy> model_form_of(const Stage& s, const std::vector<QuantityShift>& shifts);
void fill_leftovers(std::vector<Leftover>& left, const std::vector<QuantityShift>& shifts);
std::vector<ResidualPattern> residual_patterns(const Misfit& m, const std::vector<double>& r);
// Which measurement tells two fitted explanations apart (with `unmeasured_only`, among the
// quantities this dataset lacks).
std::vector<Discriminator> discriminators(const Misfit& m, const EffectFit& a, const EffectFit& b, bool unmeasured_only);
// The causes these data cannot tell from the named ones: about as good, or moving every reading in
// proportion; and records at one condition beside a named one.
void ties_of(DiagnosisResult& out, const Stage& s, const std::vector<double>& r0);
// Two fits' chi^2 as made alike: where the expensive model was re-run for real at one's strength and
// the other has only its signature, the first one's chi^2 from its signature. A profiled real run
// against a signature's linear response favours whichever got the runs, whatever the data say: a
// belt-speed record that fits a DEM-made slip as well as the slip does was not said beside it.
// A measurement effect on the expensive model is exact already (its chi^2 is a real run's).
std::pair<double, double> chi2_alike(const EffectFit& a, const EffectFit& b);

}  // namespace chutelab::validation::detail
