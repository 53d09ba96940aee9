#pragma once
// Discretisation uncertainty from a ladder of runs at refinement parameters h1 < h2 < h3 (for the
// DEM: the particle diameter), by Richardson extrapolation and Roache's Grid Convergence Index.
//
// Three levels (Celik et al. 2008, J. Fluids Eng. 130:078001, "Procedure for estimation and
// reporting of uncertainty due to discretization in CFD applications"):
//   r21 = h2/h1, r32 = h3/h2, e21 = f2 - f1, e32 = f3 - f2, s = sign(e32/e21);
//   p = [ln(e32/e21) + q(p)] / ln r21,  q(p) = ln[(r21^p - s)/(r32^p - s)]  (fixed-point iteration;
//   q = 0 for a constant ratio); f_ext = (r21^p f1 - f2)/(r21^p - 1);
//   GCI_fine = Fs |e21| / (r21^p - 1) with Roache's Fs = 1.25 for three levels.
// Two levels: the same GCI with an assumed order and Fs = 3 (Roache).
//
// What DEM data do, and what this module does about it (chutelab's choices, stated):
// - Every level is a time average with a statistical standard error. A level-to-level difference is
//   *resolved* when |e| > k sqrt(se_a^2 + se_b^2), k = 2 (about 95 % for Gaussian means).
// - Order bounds: the observed order is used when it lies in [min_order, max_order] (default
//   [0.5, 2]). Outside them the ladder is not in the asymptotic range: p is clamped to the nearer
//   bound and Fs = 3, so the GCI is a bound rather than an estimate. Clamping a high p down and a
//   low p up: the first is conservative; the second is not, which is why Fs goes to 3 as well.
// - A difference not resolved against the noise (noise dominated): the ladder saw no error larger
//   than its own scatter. The estimate is then statistical, not a band: the error estimate of the
//   widest pair, e / (r^p - 1), and its standard error, se_e / (r^p - 1), in quadrature, with the
//   assumed order. That is a standard uncertainty as it stands, so no Fs and no coverage factor
//   (a safety factor on a bound of 2 standard errors would count the noise six times over).
// - Differences of opposite sign (oscillatory) or growing with refinement (diverging): the
//   two-level GCI of the finest pair with the assumed order and Fs = 3. For oscillation the result
//   is at least Fs times half the range of the three values (the half-range is the oscillation's
//   own amplitude, a spread no power law describes). No extrapolated value is given in these cases.
// - The assumed order for two levels and fallbacks defaults to 1: a granular flow resolves its
//   walls and free surfaces to about one particle diameter, so errors in layer thickness, stream
//   limits and the point of application scale with d (chutelab's choice; callers may set it).
// - u_disc = GCI_fine / 1.15: the GCI band read as covering about 95 % and converted to one
//   standard uncertainty with the factor that ASME V&V 20-2009 §5 is commonly quoted as giving for
//   a GCI with Fs = 1.25. The standard's text was not available to check, so take the factor as
//   chutelab's choice; it is applied to the Fs = 3 bounds too (conservative: a bound divided by
//   1.15 rather than by sqrt(3) for a rectangular band).
#include <array>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "validation/model.h"

namespace chutelab::validation {

struct LadderLevel {
  double h = 0.0;               // refinement parameter (e.g. particle diameter, m), > 0
  double value = 0.0;           // the quantity at this level
  double standard_error = 0.0;  // statistical standard error of `value` (0 = exact)
};

struct GciOptions {
  double assumed_order = 1.0;   // two levels and fallbacks
  double min_order = 0.5;       // bounds on the observed order
  double max_order = 2.0;
  double resolution_k = 2.0;    // a difference is resolved when |e| > k * its standard error
  double coverage_k = 1.15;     // u_disc = GCI_fine / coverage_k
};

enum class GciCase {
  three_level,          // observed order within bounds, Fs = 1.25
  order_bounded,        // observed order outside the bounds, clamped, Fs = 3
  two_level,            // two levels, assumed order, Fs = 3
  noise_dominated,      // a difference not resolved against the statistical errors: statistical estimate
  oscillatory,          // differences of opposite sign: bound
  diverging,            // differences grow with refinement: bound
};

struct GciEstimate {
  GciCase kind = GciCase::two_level;
  std::optional<double> observed_order;  // from three levels when it could be computed
  double order = 0.0;                    // p used in the GCI
  double safety_factor = 0.0;            // Fs
  double fine_value = 0.0;               // f1
  std::optional<double> extrapolated;    // f_ext, when the ladder supports one
  double gci_fine = 0.0;                 // absolute, unit of the values
  std::optional<double> gci_fine_relative;  // gci_fine / |f1|, absent when f1 = 0
  double u_disc = 0.0;                   // standard uncertainty, unit of the values
  std::string method;                    // one line for notes and reports
};

// `levels`: two or three runs in any order (sorted here by h; with more than three, the three
// finest are used). Throws std::invalid_argument on fewer than two levels, a non-positive or
// repeated h, a non-finite value or a negative standard error.
GciEstimate gci_estimate(std::span<const LadderLevel> levels, const GciOptions& options = {});

std::string_view name(GciCase c);

// A model's predictions along a ladder (e.g. the DEM at 13.6, 9 and 5.6 mm spheres), all asked the
// same trajectory queries. Each run's `uncertainty` / `trajectory_uncertainty` is its standard error.
struct LadderRun {
  double h = 0.0;                             // refinement parameter of the run
  const ModelPrediction* prediction = nullptr;
};

struct LadderUncertainty {
  QuantityValues u_disc;                                    // SI, per quantity; absent = not estimated
  std::vector<std::optional<double>> trajectory;            // m per query
  std::array<std::optional<GciEstimate>, kQuantityCount> estimate{};  // per quantity, for notes
  std::vector<std::optional<GciEstimate>> trajectory_estimate;
  std::array<std::vector<std::string>, kQuantityCount> methods;  // per quantity, one line per ladder
};

// The GCI of every value that at least two runs predict (the finest run is the one the estimate
// is for: u_disc belongs to the prediction at the smallest h).
LadderUncertainty ladder_uncertainty(std::span<const LadderRun> runs, const GciOptions& options = {});

// Several one-factor ladders of the same run (e.g. time step and particle size): per value the
// root sum of squares of the parts that estimate it; their methods are kept for the notes.
LadderUncertainty combine_ladders(std::span<const LadderUncertainty> parts);

// Sets `fine.discretisation` and `fine.trajectory_discretisation` from `u`, and adds one note per
// quantity with the method used.
void apply_discretisation(ModelPrediction& fine, const LadderUncertainty& u);

}  // namespace chutelab::validation
