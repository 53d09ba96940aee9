#pragma once
// The seed's Table 6 (Grima & Wypych 2010, §6.1) as data: the variants of one transfer-station DEM run
// (contact model, particle shape, time step, shear modulus, particle size), what each gave at the
// plate, the change against the base case, and the check of the seed's conclusion: "mean plate force
// changes little with contact model, shape, dt and G; its fluctuation grows with particle size".
// Independent of how a variant is run (the command plugs in the station DEM), so it can be tested on
// made-up numbers; the report reads the CSV back (reports/studies.h).
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "validation/seed_findings.h"

namespace chutelab::reports {

enum class VariantGroup { base, contact, shape, time_step, modulus, size };
std::string_view name(VariantGroup g);

struct SensitivityVariant {
  std::string key;     // "base", "lsd", "clump", "dt/20", "G*10", "G/10", "d=9mm", ...
  std::string label;   // what changes, for people
  VariantGroup group = VariantGroup::base;
  // Settings of the run (SI); 0 / empty = the base's.
  std::string contact = "hertz-mindlin";
  std::string shape = "sphere";
  double diameter = 0.0;        // m (sphere diameter, or the clump's element spheres)
  double dt_fraction = 0.1;     // of the Hertz collision time
  double rayleigh_fraction = 0.2;
  double modulus_scale = 1.0;   // multiplies the base run's modulus (G x10, /10)
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

// The verdict on the seed's conclusion, with the numbers it rests on.
struct Table6Verdict {
  bool mean_insensitive = false;    // every contact/shape/dt/G variant within the limit of the base
  double worst_change = 0.0;        // %, largest |change| among those
  std::string worst_variant;
  bool fluctuation_grows = false;   // fluctuation of R increases with particle diameter
  std::vector<std::pair<double, double>> size_fluctuation;  // (d in m, sd of R in N), ascending d
  double size_mean_spread = 0.0;    // %, largest |change| among the size variants
  bool mean_tested = false;         // at least one contact/shape/dt/G variant ran
  bool size_tested = false;         // at least two particle sizes ran
  bool reproduced() const { return mean_tested && size_tested && mean_insensitive && fluctuation_grows; }
  std::string text;                 // one paragraph, with the numbers
};

struct SensitivityStudy {
  std::string dataset, condition, quality;
  double belt_speed = 0.0, mass_flow = 0.0;   // SI
  std::vector<SensitivityRow> rows;            // rows[0] is the base
  Table6Verdict verdict;
  double wall_seconds = 0.0;
  double limit_percent = 10.0;                 // "changes little": |change| <= this
};

// The seed's variants around a base run of diameter `base_d`: LSD, a two-sphere clump whose spheres
// are base_d x 4.4/5.6 (the seed's 4.4 mm clump against its 5.6 mm spheres), dt = t_c/20, G x10, G/10,
// and two larger spheres, base_d x 9/5.6 and x 13.6/5.6 (the seed's 5.6 -> 9 and 13.6 mm scale-up).
std::vector<SensitivityVariant> table6_variants(double base_d);

// Fills change and the verdict from the rows.
void evaluate(SensitivityStudy& s);

// The seed's finding 6 (validation/seed_findings.h) from a study; not testable without one.
validation::SeedFinding sensitivity_finding(const SensitivityStudy* study);

std::string sensitivity_csv(const SensitivityStudy& s);
// Reads back what sensitivity_csv wrote (the report's "Sensitivity" section) and evaluates it again;
// bad or missing columns and values throw InputError naming the file, line and column.
SensitivityStudy read_sensitivity_csv(const std::filesystem::path& file);
// The chart of sensitivity_html: mean R with its standard error and the fluctuation, per variant.
std::string sensitivity_chart(const SensitivityStudy& s, std::string_view id);
std::string sensitivity_md(const SensitivityStudy& s);
std::string sensitivity_html(const SensitivityStudy& s);

}  // namespace chutelab::reports
