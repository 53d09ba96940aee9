#pragma once
// Which physical effect is missing? For each candidate effect (and each pair), fit its strength to
// all measurements and trajectory points weighted by their uncertainties, judge whether the
// improvement is more than chance across all the candidates tried, and whether what the best
// explanation leaves is noise. The statistics do not take the data's assumptions on trust: readings
// no explanation reaches are named and left out, a quantity no model explains gets a discrepancy of
// its own, uncertainties that the scatter shows too small are widened, and a candidate the data want
// outside its physical range is fitted there too, so that a clipped true effect cannot hand the
// verdict to a mimic.
//
// Shape: diagnose() (this file's .cpp) runs the statistics on a cost function
// (validation/misfit.h) over a source of predictions that owns the runs
// (validation/prediction_source.h), with fits from validation/strength_fit.h and the noise
// assessment of validation/noise_model.h. Its result is numbers and codes; the sentences are
// rendered from it by validation/diagnosis_words.cpp.
#include <optional>
#include <string>
#include <vector>

#include "validation/dataset.h"
#include "validation/model.h"
#include "validation/strength_fit.h"

namespace chutelab::validation {

// How a model's normalised residuals of one quantity move with one operating variable.
struct ResidualPattern {
  std::string model;
  std::string quantity;          // boundary name
  std::string driver;            // "belt speed", "mass flow", "flight time", "drop height"
  int n = 0;
  double mean_normalised = 0.0;  // mean E/u over the conditions (bias)
  double rms_normalised = 0.0;
  double correlation = 0.0;      // Pearson r between E/u and the driver
  bool notable = false;          // bias or trend beyond what noise gives
};

// A candidate refitted over its extended range (effects/registry.h) when its fit inside the
// physical range sits at a bound: what strength the data want whatever physics allows.
struct UnboundedFit {
  double estimate = 0.0, uncertainty = 0.0;  // boundary units, one sd
  double chi2 = 0.0;
  // Outside the physical range by more than two sd, and significantly better than the bounded fit
  // (likelihood ratio at the family's alpha).
  bool wants_outside = false;
};

struct EffectFit {
  std::vector<std::string> effects;       // one name, or two for a pair
  std::vector<std::string> parameters;    // parameter names with units
  std::vector<double> estimate;           // boundary units of each parameter
  std::vector<double> uncertainty;        // one sd: from the fit's covariance under the noise model, or a profile
  double chi2_before = 0.0;               // of the models as they are, under the noise model
  double chi2_after = 0.0;
  double delta_bic = 0.0;                 // BIC(with effect) - BIC(baseline); < 0 is better
  // Share of the misfit beyond noise that the fit removes: (chi2_before - chi2_after) /
  // (chi2_before - min(chi2_after, dof)); 1 when what is left is no more than noise.
  double explained_fraction = 0.0;
  double p_value = 1.0;                   // likelihood-ratio (or F) test, before the look-elsewhere step
  double p_adjusted = 1.0;                // after controlling for the number of candidates tried
  bool significant = false;
  int rank = 0;                           // 1 = best single effect
  FitStatus status = FitStatus::converged;
  std::vector<bool> at_bound;             // per parameter: at an edge of its physical range
  std::optional<UnboundedFit> unbounded;  // singles at a bound only
  // Another candidate's fit outside its physical range explains the data clearly better (by the
  // tie margin in BIC): this one may not be named as the missing effect.
  std::string beaten_outside_range_by;
  // With an expensive baseline: where its response to the effect came from ("own runs", "analytical
  // only": it cannot represent the effect, "exact": a measurement effect applied to its output).
  std::string signature;
  // With an expensive baseline that runs with effects: chi^2 from the signatures, when a real run at
  // the fitted strength replaced it in chi2_after (and in what follows from it).
  std::optional<double> chi2_from_signatures;
  // The expensive model's own chi^2 at a few strengths around the estimate (the recommended single
  // fit): its minimum and curvature replace the estimate and sd of the linear signature.
  std::optional<ProfileFit> profile;
  // The profile's sd widened by this factor (> 1): the readings scatter around the real runs more
  // than their uncertainties say (the curvature-weighted Birge ratio of the quantities that fix the
  // strength, or the sandwich (HC3) estimate from the readings' leave-one-out pulls, the larger).
  double profile_widened = 1.0;
  // Recorded inputs (effects/registry.h, Kind::record): per parameter, the plausible error of the
  // record (one sd in its unit; 0 for physics), whether the dataset stated it (else the input's
  // documented default), and the charge for the fitted offsets' implausibility, 2 ln(1 + (x/w)^2)
  // summed (a Cauchy prior of width w: three widths off costs 4.6, thirty 13.6). It is added to
  // chi2_after where candidates are ranked and tested, never to the fit itself (a typo is fitted
  // at its size, not pulled towards the record).
  std::vector<double> prior_width;
  std::vector<bool> prior_stated;
  double prior_penalty = 0.0;
  bool is_record() const;                 // every effect of it is a recorded input
  // A record whose fitted error is within its plausible error at every input: the record is right
  // to within what it claims, whatever the test says (a refinement, not a wrong record).
  bool within_plausible_error() const;
  double ranked_chi2() const { return chi2_after + prior_penalty; }
  std::string label() const;              // "air_drag" or "air_drag + belt_slip"
};

// The verdict as a code (the sentences are rendered from the whole result).
enum class Verdict {
  no_data,              // no measured value has an uncertainty
  consistent,           // the models explain the data within the uncertainties
  missing_effect,       // a library effect (or pair) explains the misfit and leaves only noise
  partial_explanation,  // the best explanation is real but leaves a misfit that is not noise, or needs an edge of its range
  out_of_range,         // the data want an effect at a strength outside its physical range
  outside_library,      // the models miss the data and no library effect explains it
};

// A reading no explanation reaches: left out of every fit and named.
struct Outlier {
  std::string condition, quantity;        // quantity: boundary name
  SourceLine where;
  double measured = 0.0;                  // boundary units
  double predicted = 0.0;                 // by the recommended explanation (or the models as they are)
  double deviation = 0.0;                 // standardised: (measured - predicted) / (its scatter)
  double relative = 0.0;                  // (measured - predicted) / |predicted|
  double closest = 0.0;                   // smallest |deviation| under any candidate fitted
  // Records wrong at this reading's condition alone that would explain it with the condition's other
  // readings (the best first; analytical models only): the data cannot tell them from a wrong reading.
  std::vector<EffectFit> records;
};

// A reading that alone moves a fitted strength by more than one sd (leave-one-out refit).
struct Influence {
  std::string condition, quantity;
  SourceLine where;
  std::string parameter;                  // of the recommended explanation
  double shift_sd = 0.0;                  // signed: the strength without the reading minus with it, in sd
};

// A quantity (as one model predicts it) that no explanation reaches: a discrepancy variance
// tau^2 added to its points' u^2, so that it cannot hide an effect seen in the other quantities.
struct Discrepancy {
  std::string quantity, model;
  int n = 0;
  double tau = 0.0;                       // boundary units
  double mean_error = 0.0;                // mean E = S - D under the recommended explanation, boundary units
  double mean_relative = 0.0;             // mean E / |D| (forces and speeds)
};

// What the scatter left by the best explanation says about the stated uncertainties (outside
// quantities with a discrepancy and outliers).
struct ScaleFinding {
  double factor = 1.0;                    // sqrt(chi^2 / dof): the real scatter over the stated
  int dof = 0;
  double p_high = 1.0, p_low = 1.0;       // chance of a chi^2 this large / this small with honest uncertainties
  bool applied = false;                   // significantly too small: every u widened by `factor` (a Birge ratio)
  bool too_large = false;                 // significantly too large (the uncertainties are not narrowed)
};

// A quantity where what the best explanation leaves is not noise.
struct Leftover {
  std::string quantity, model;
  int n = 0;
  double mean_error = 0.0;                // boundary units
  double mean_relative = 0.0;
  double p = 1.0;                         // the smallest p of its bias, excess and trend tests (before Bonferroni)
  std::string pattern;                    // "bias", "scatter", or the driver it trends with
};

// One quantity's misfit in the engineer's units: the mean error of the models as they are and with
// the recommended explanation.
struct QuantityShift {
  std::string quantity, symbol, label, unit;
  int n = 0;
  double before = 0.0, after = 0.0;       // mean E = S - D, boundary units
  double before_relative = 0.0, after_relative = 0.0;  // mean E / |D|
  bool relative = false;                  // forces and speeds: said in %, positions in mm
};

// Two explanations and the measurement that separates them most.
struct Discriminator {
  std::string a, b;                       // labels
  std::string quantity, condition, model, unit;
  double value_a = 0.0, value_b = 0.0;    // boundary units
  double separation = 0.0;                // in uncertainties of such a measurement here
  bool measured_here = true;
};

// Where a named effect's evidence lies, when it lies in one quantity: a model-form error of that
// quantity would look the same.
struct Concentration {
  std::string effect, quantity, model;
  double share = 0.0;                     // of the effect's fall of chi^2
};

// Whether a named recorded input is off by the same at every condition (the rig's drawing) or
// differs between them (the rig changed between tests): each condition's error fitted on its own data.
struct RecordScope {
  std::string input;                       // effects/registry.h name
  std::string unit;
  std::vector<std::string> conditions;
  std::vector<double> estimate, uncertainty;
  double rig_wide_chi2 = 0.0, per_condition_chi2 = 0.0;
  double p = 1.0;                          // per condition against one error for the rig (chi^2, n - 1 dof)
  bool differs = false;                    // significant at the family's alpha
};

// A named cause whose strength the data want to change with an operating variable: the library's
// form of it holds the strength constant, so its fitted value is a compromise between conditions.
struct ShapeFinding {
  std::string effect;                      // the cause (a library name)
  std::string parameter, unit;             // its strength
  std::string driver;                      // "belt speed", "mass flow", "drop height"
  std::string driver_unit;
  // The strength the data want, fitted condition by condition with the other causes held: about
  // proportional to driver^exponent (a line in log(driver) through the conditions' strengths).
  double exponent = 0.0, exponent_uncertainty = 0.0;
  double low_driver = 0.0, high_driver = 0.0;      // the driver's range over the conditions (boundary units)
  double low_strength = 0.0, high_strength = 0.0;  // the line's strength at either end
  double p = 1.0;                          // Bonferroni over the causes and drivers tested
  // Where the effect declares how it grows (effects/registry.h, EffectInfo::growth): the power of
  // the driver its physics has, and what grows ("drag").
  std::string grows;
  double power = 0.0;
};

struct DiagnosisResult {
  std::string dataset;
  std::vector<std::string> models;
  int n_data = 0;                         // measurements + trajectory points with uncertainty
  int n_without_uncertainty = 0;          // left out of chi^2
  int n_conditions = 0, n_quantities = 0; // what the design spans
  double chi2_baseline = 0.0;             // as stated (before the noise model)
  double baseline_p_value = 1.0;          // chance of a chi^2 this large from noise alone
  // The same without the readings left out as outliers: what "within the stated uncertainties" rests on.
  double chi2_kept = 0.0;
  int n_kept = 0;
  double kept_p_value = 1.0;
  double alpha = 0.01;                    // the family-wise false-alarm rate the verdict was judged at
  std::vector<ResidualPattern> patterns;
  std::vector<EffectFit> singles;         // ranked, best first
  // Explanations by more causes than the best single, each cause significant given the others (a
  // forward search; validation/diagnosis_causes.cpp), largest first: best() is the first.
  std::vector<EffectFit> pairs;
  // The best explanation one cause larger than the one named, whose last cause was not significant:
  // the nearest rival on the side of more causes (the self-check draws replicas from it).
  std::optional<EffectFit> next_cause;
  bool any_significant = false;

  // The codes and numbers of the verdict.
  Verdict verdict_code = Verdict::no_data;
  bool convincing = false;                // verdict_code == missing_effect
  bool goodness_of_fit = true;            // what the recommended explanation leaves is noise
  std::vector<Outlier> outliers;
  std::vector<Influence> influential;
  std::vector<Discrepancy> model_form;
  ScaleFinding scale;
  std::vector<Leftover> leftovers;        // where the rest is not noise
  std::vector<QuantityShift> shifts;      // the recommended explanation in units
  // Where the explanation is a record wrong at one condition: that condition, and the shifts of its
  // readings alone (the words say these).
  std::string shifts_condition;
  std::vector<QuantityShift> shifts_there;
  std::vector<std::string> wants_outside; // candidates whose data want a strength outside the range
  bool thin_data = false;                 // too few conditions or quantities to tell candidates apart
  // Every condition at one belt speed (or one mass flow): effects that grow with it look alike.
  bool one_belt_speed = false, one_mass_flow = false;
  std::vector<ShapeFinding> shape;        // named causes the data want with another shape
  int noise_rounds = 0;                   // fits run before the noise model settled
  std::vector<Discriminator> ties;        // about as good as the best, and what would separate them
  std::optional<Concentration> concentrated;  // the recommended effect rests on one quantity
  std::optional<RecordScope> record_scope;  // analytical models only (a DEM would need runs per condition)

  // Sentences for an engineer, rendered from the above (validation/diagnosis_words.cpp).
  std::string verdict;                    // the headline, in the quantities' units and %: no statistics
  // How sure the verdict is, for whoever asks: chi^2 before and after, the share of the misfit beyond
  // noise removed, delta BIC and the adjusted p (the report's "How sure is this?").
  std::string evidence;
  std::vector<std::string> failure_summary;    // where the models as they are fail
  std::vector<std::string> findings;           // readings to check, quantities no model explains, the uncertainties
  std::vector<std::string> indistinguishable;  // effects about as good as the best
  std::vector<std::string> discriminators;     // which measurement would tell them apart
  std::vector<std::string> proportional;       // candidates that move the data in proportion to the best
  std::vector<std::string> caveats;
  // The baseline's conditions whose steady means came from a window some load still moved through
  // (ModelPrediction::unsteady), as "V5-44 (R_s, impact point)".
  std::vector<std::string> unsteady_baseline;
  // With an expensive model (DEM) the ranking uses the cheap models' signatures as differences
  // (DESIGN.md §5); the recommended fit is then re-run with the expensive model for real.
  bool used_surrogate = false;
  // Expensive models that cannot be re-run with an effect (another code's exported results): name, description.
  std::vector<std::pair<std::string, std::string>> exported_models;
  std::optional<double> confirmed_chi2;   // chi^2 of the recommended fit from real runs
  const EffectFit* best() const;          // the recommended fit (single or pair), if significant and not beaten
};

struct DiagnoseOptions {
  double alpha = 0.01;           // family-wise false-alarm rate over all candidates
  bool pairs = true;
  double pair_margin_bic = 6.0;  // a pair must beat the best single by this much ("strong", Kass & Raftery 1995)
  double tie_margin_bic = 2.0;   // within this of the best: indistinguishable
  // Pairs fitted for real: the ones whose two singles' fitted changes, combined linearly, leave the
  // least chi^2 (validation/diagnosis.cpp, screen_pairs); 0 fits every pair. The screen keeps the
  // pair fits' cost fixed as candidates are added (153 pairs of 18 took 92 % of a diagnosis).
  int screened_pairs = 10;
  // Two candidates whose fitted changes of the normalised residuals are this parallel (|cos|) move
  // the measured quantities in proportion: these data cannot tell them apart.
  double proportional_cosine = 0.98;
  // Readings left out as outliers, at most this share of the data (more is not a few bad readings
  // but a misfit).
  double max_outlier_share = 0.05;
  // Expensive runs side by side, and threads predicting the conditions of the analytical fits
  // (0 = one per core, shared among MPI ranks).
  int jobs = 0;
  // With an expensive baseline: how many of the leading significant single candidates are re-run
  // at their fitted strengths before the ranking is final (the best pair is always re-run).
  int confirm = 3;
  // With an expensive baseline that runs with effects: real runs at up to this many strengths
  // around the recommended single fit give its estimate and sd (0: keep the signature's).
  int profile_runs = 6;
  // One line per fit on stderr (which, of how many, time so far) for datasets of 500 conditions or more.
  bool progress = false;
  // Applied to every model before any candidate: corrected records (`diagnose --input`). The
  // candidates are then what the corrected rig still misses.
  analytical::EffectList fixed = {};
};

// Throws InputError (field = the option's name) for an option out of its range, before any work.
void check(const DiagnoseOptions& options);

DiagnosisResult diagnose(const Dataset& d, const std::vector<ModelPtr>& models,
                         const DiagnoseOptions& options = {});

// validation/diagnosis_words.cpp: the sentences of a result (fills its verdict, summaries and
// caveats), and its files.
void describe(DiagnosisResult& r, const DiagnoseOptions& options);
std::string diagnosis_csv(const DiagnosisResult& r);
std::string diagnosis_markdown(const DiagnosisResult& r);

}  // namespace chutelab::validation
