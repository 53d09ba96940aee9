#pragma once
// The reference study's simple calibration (Grima & Wypych 2010, §5, Table 3): slump tests over combinations of
// particle-particle rolling friction, solid density and particle shape, compared with the measured
// loose-poured bulk density and pile height; the closest combination is the calibrated material.
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "core/rig.h"
#include "dem/rigs/inclined_plane.h"
#include "dem/rigs/slump_tester.h"

namespace chutelab::dem::rigs {

struct CalibrationTargets {
  std::optional<double> bulk_density;  // kg/m^3
  std::optional<double> pile_height;   // m
  bool any() const { return bulk_density || pile_height; }
};

struct CalibrationRow {
  GrainKind shape = GrainKind::sphere;
  double rolling_friction = 0.0;
  double solid_density = 0.0;  // kg/m^3
  SlumpResult slump;
  double distance = 0.0;       // to the targets (NaN without targets)
};

// Relative distance to the targets: sqrt of the mean of ((value - target) / target)^2 over the
// targets given. Bulk density and pile height weigh equally, as in the reference study's choice "closest
// correlation ... in regards to the loose-poured bulk density, angle of repose and shape/height of
// the conical pile".
double target_distance(const SlumpResult& r, const CalibrationTargets& t);

struct CalibrationPlan {
  std::vector<double> rolling;     // particle-particle rolling friction coefficients
  std::vector<double> density;     // solid densities, kg/m^3
  std::vector<GrainKind> shapes;
  Grain sphere = Grain::sphere(5.6e-3);    // the reference study's scaled sphere (Fig. 4b)
  Grain clump = Grain::reference_clump(4.4e-3); // the reference study's 2 x 4.4 mm pellet (Fig. 4c)
  SlumpSettings settings;
  CalibrationTargets targets;
  // Particle-wall rolling friction by the inclined-plane rig: onset angle for each `rolling` value
  // on the plate material (sphere).
  bool incline = true;
  int jobs = 0;  // runs side by side in this process (campaign::Options::threads); 0 or 1: in order
};

struct InclineRow {
  double rolling_friction = 0.0;
  double wall_friction = 0.0;
  InclineResult result;
};

struct CalibrationStudy {
  CalibrationPlan plan;
  std::vector<CalibrationRow> rows;  // shape-major, then rolling friction, then density (Table 3 order)
  int closest = -1;                  // index into rows (-1: no targets)
  std::vector<InclineRow> incline;
  double wall_seconds = 0.0;
};

struct CalibrationProgress {
  int index = 0, count = 0;          // row being run (1-based) of count
  const CalibrationRow* done = nullptr;  // set when a row has finished
  SlumpProgress slump;
};

// Runs every combination. Throws InputError for an empty or impossible plan.
CalibrationStudy run_calibration(const chutelab::Material& m, const CalibrationPlan& plan,
                                 const std::function<void(const CalibrationProgress&)>& progress = {});

std::string_view name(GrainKind k);

}  // namespace chutelab::dem::rigs
