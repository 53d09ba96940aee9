#pragma once
// The reference study's Table 6 (Grima & Wypych 2010, §6.1) as data: the variants of one transfer-station DEM run
// (contact model, particle shape, time step, shear modulus, particle size), what each gave at the
// plate, the change against the base case, and the check of the reference study's conclusion: "mean plate force
// changes little with contact model, shape, dt and G; its fluctuation grows with particle size".
// Independent of how a variant is run (the command plugs in the station DEM), so it can be tested on
// made-up numbers. This is the study as data and its CSV files; the pages and the report's section
// that draw it are the report's (reports/sensitivity_page.h, reports/studies.h).
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "dem/contact/normal_laws.h"
#include "validation/reference_findings.h"

namespace chutelab::studies {

enum class VariantGroup { base, contact, shape, time_step, modulus, size };
std::string_view name(VariantGroup g);

struct SensitivityVariant {
  std::string key;     // "base", "LSD", "clump", "clump-d", "dt/20", "Gx10", "G/10", "d=9mm", ...
  std::string label;   // what changes, for people
  VariantGroup group = VariantGroup::base;
  // Settings of the run (SI); 0 / empty = the base's.
  std::string contact{dem::NormalLaw{}.key()};  // a registered law's key
  std::string shape = "sphere";
  double diameter = 0.0;        // m (sphere diameter, or the clump's element spheres)
  double dt_fraction = 0.1;     // of the Hertz collision time
  double rayleigh_fraction = 0.2;
  double modulus_scale = 1.0;   // multiplies the base run's modulus (G x10, /10)
};

// The base run as resolved (quality preset < the dataset's [dem] table < flags), so that the labels
// say what ran rather than what the reference study ran: at quick quality the modulus is a third of the
// dataset's, and the Rayleigh cap can make the step shorter than dt_fraction t_c.
struct Table6Base {
  double diameter = 13.6e-3;           // m, the base spheres
  double modulus_scale = 1.0;          // the base's E (and G) over the dataset's; NaN = not known
  double dt_fraction = 0.1;            // of the Hertz collision time
  double rayleigh_fraction = 0.2;      // cap, of the Rayleigh time
  // Sphere diameters of the size variants, m. Those that differ from the base diameter become
  // variants; the one equal to it is the base itself.
  std::vector<double> sizes = reference_sizes();
  static std::vector<double> reference_sizes() { return {5.6e-3, 9.0e-3, 13.6e-3}; }  // reference study Table 6, absolute
};

struct Stat {
  double value = 0.0, se = 0.0;  // mean and its standard error
};

struct VariantOutcome {
  Stat normal, shear, resultant;              // N, steady means
  double fluct_normal = 0.0, fluct_shear = 0.0, fluct_resultant = 0.0;  // N, sd of the sampled series
  double diameter = 0.0;                      // m, as run
  double dt = 0.0, collision_time = 0.0;      // s
  double simulated = 0.0, wall_seconds = 0.0; // s
  long long steps = 0;
  std::size_t particles = 0;                  // peak number of spheres
  bool steady = true;
  std::vector<std::string> notes;
};

struct SensitivityRow {
  SensitivityVariant variant;
  VariantOutcome outcome;
  Stat change;  // % change of the mean resultant against the base, with its standard error
};

// The verdict on the reference study's conclusion, with the numbers it rests on.
struct Table6Verdict {
  bool mean_insensitive = false;    // every contact/shape/dt/G variant within the limit of the base
  double worst_change = 0.0;        // %, largest |change| among those
  std::string worst_variant;
  bool fluctuation_grows = false;   // fluctuation of R increases with particle diameter
  std::vector<std::pair<double, double>> size_fluctuation;  // (d in m, sd of R in N), ascending d
  double size_mean_spread = 0.0;    // %, largest |change| among the size variants
  bool mean_tested = false;         // at least one contact/shape/dt/G variant ran
  bool size_tested = false;         // at least two particle sizes ran
  std::vector<double> sizes_left_out;  // m, the reference study's sizes that did not run
  std::vector<std::string> variants_left_out;  // keys of other variants that did not run (--only)
  bool complete() const { return mean_tested && size_tested && sizes_left_out.empty() && variants_left_out.empty(); }
  bool reproduced() const { return complete() && mean_insensitive && fluctuation_grows; }
  std::string text;                 // one paragraph, with the numbers
};

struct SensitivityStudy {
  std::string dataset;        // where it came from (folder), for people
  std::string dataset_name;   // setup.toml `name`: which rig the study is about ("" = not recorded)
  std::string condition, quality;
  // The reference study's sizes not run (m, e.g. 5.6 mm at quick quality, to stay within the time budget): the
  // verdict then says "not fully tested" and how to run them.
  std::vector<double> sizes_left_out;
  std::vector<std::string> variants_left_out;  // keys not run (--only)
  double belt_speed = 0.0, mass_flow = 0.0;   // SI
  Table6Base base;                             // the base run as resolved
  std::vector<SensitivityRow> rows;            // rows[0] is the base
  Table6Verdict verdict;
  double wall_seconds = 0.0;
  double limit_percent = 10.0;                 // "changes little": |change| <= this
};

// The reference study's variants around a base run: LSD, a two-sphere clump whose spheres are d_base x 4.4/5.6
// (the reference study's 4.4 mm clump against its 5.6 mm spheres), the same clump of spheres of d_base (the
// reference study's "shaped d = 5.6 mm, d increased"), half the time step, G x10, G/10, and spheres of every
// size in base.sizes other than d_base, in increasing size.
std::vector<SensitivityVariant> table6_variants(const Table6Base& base);

// Fills change and the verdict from the rows.
void evaluate(SensitivityStudy& s);

// The reference study's finding 6 (validation/reference_findings.h) from a study; not testable without one. The
// evidence names the study's dataset, and says so when it is not `validated` (the report's dataset).
validation::ReferenceFinding sensitivity_finding(const SensitivityStudy* study, std::string_view validated = {});

// The columns of sensitivity.csv that hold a variant's settings: the options of those [dem]
// settings (dem/station/settings.h), "contact", "shape", "diameter_mm" (the particle diameter as
// run) and "dt_fraction".
struct VariantColumns {
  std::string contact, shape, diameter, dt_fraction;
};
const VariantColumns& variant_columns();

// A diameter (m) as the study names it: in mm to 0.1 mm, "13.6"; the variants' keys and every
// output use it, so that one size has one name.
std::string mm_text(double m);
// Notes on what really ran that a label cannot say: a step set by the Rayleigh cap, sizes left out.
std::vector<std::string> run_notes(const SensitivityStudy& s);

// The study's numbers: no wall-clock time, so one process and an MPI run write the same bytes.
std::string sensitivity_csv(const SensitivityStudy& s);
// sensitivity-timing.csv: variant,run_seconds (wall clock of each DEM run; differs run to run).
// read_sensitivity_csv takes the times from it when it lies beside the study.
std::string sensitivity_timing_csv(const SensitivityStudy& s);
// Reads back what sensitivity_csv wrote (the report's "Sensitivity" section) and evaluates it again;
// bad or missing columns and values throw InputError naming the file, line and column.
SensitivityStudy read_sensitivity_csv(const std::filesystem::path& file);

}  // namespace chutelab::studies
