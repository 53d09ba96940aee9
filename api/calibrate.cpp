#include "api/calibrate.h"

#include <fmt/format.h>

#include "api/dem_options.h"
#include "core/input_error.h"
#include "core/message.h"
#include "core/option_check.h"
#include "core/progress.h"
#include "core/rig_needs.h"
#include "reports/calibration_page.h"
#include "validation/dataset.h"
#include "validation/dataset_output.h"

namespace chutelab::api {
namespace {

using namespace dem::rigs;

// What each list and number may be (core/option_check.h): physical ranges, wide enough for any
// bulk solid (the densest solid, osmium, is 22 600 kg/m^3).
constexpr options::NumberRule kRolling{"rolling", 0.0, 1.0, false, false, false, ""};
constexpr options::NumberRule kDensity{"density", 0.0, 25000.0, true, false, false, "kg/m^3"};
constexpr options::NumberRule kSphereDiameter{"sphere_diameter", 0.0, 100.0, true, false, false, "mm"};
constexpr options::NumberRule kClumpDiameter{"clump_diameter", 0.0, 100.0, true, false, false, "mm"};
constexpr options::NumberRule kTargetBulk{"target_bulk_density", 0.0, 25000.0, true, false, false, "kg/m^3"};
constexpr options::NumberRule kTargetPile{"target_pile_height", 0.0, 10000.0, true, false, false, "mm"};
constexpr options::NumberRule kRigThreads{"threads", 1.0, 256.0, false, false, true, ""};
constexpr options::NumberRule kJobs{"jobs", 0.0, 256.0, false, false, true, ""};
// A quick slump test takes ~20 s of one core, a standard one minutes (bench/CALIBRATION.md): beyond
// this many a command would run for hours; it is refused before the first one starts.
constexpr std::size_t kMaxSlumpTests = 100;

std::vector<GrainKind> grain_kinds(const std::vector<std::string>& shapes) {
  std::vector<GrainKind> kinds;
  for (const auto& s : shapes) {
    if (s == "sphere") kinds.push_back(GrainKind::sphere);
    else if (s == "clump") kinds.push_back(GrainKind::clump);
    else throw InputError("", 0, "shape", fmt::format("unknown shape {} (sphere, clump)", shown(s)));
  }
  return kinds;
}

}  // namespace

void check(const CalibrateOptions& o) {
  for (double r : o.rolling) kRolling.check(r);
  for (double d : o.density) kDensity.check(d);
  const std::vector<GrainKind> kinds = grain_kinds(o.shapes);
  const std::size_t count = kinds.size() * o.rolling.size() * o.density.size();
  if (count > kMaxSlumpTests)
    throw InputError("", 0, "rolling",
                     fmt::format("{} shapes x {} rolling frictions x {} densities = {} slump tests; at most {} run in one "
                                 "command (each takes ~20 s to minutes): shorten the lists or split them over runs",
                                 kinds.size(), o.rolling.size(), o.density.size(), count, kMaxSlumpTests));
  if (o.quality != "quick" && o.quality != "standard")
    throw InputError("", 0, "quality", fmt::format("unknown quality {} (quick, standard)", shown(o.quality)));
  kSphereDiameter.check(o.sphere_diameter_mm);
  kClumpDiameter.check(o.clump_diameter_mm);
  if (o.target_bulk_density) kTargetBulk.check(*o.target_bulk_density);
  if (o.target_pile_height_mm) kTargetPile.check(*o.target_pile_height_mm);
  kRigThreads.check(static_cast<double>(o.threads));
  kJobs.check(static_cast<double>(o.jobs));
}

std::vector<OutputFile> CalibrateResult::files() const {
  return {{"calibration.csv", studies::calibration_csv(context, study)},
          {"incline.csv", studies::incline_csv(study)},
          {"calibration.md", reports::calibration_md(context, study)},
          {"calibration.html", reports::calibration_html(context, study)},
          {"calibration.svg", reports::calibration_svg(study)},
          {"material.toml", studies::material_toml(context, study)},
          {"calibration-timing.csv", studies::calibration_timing_csv(study)}};
}

std::string CalibrateResult::table3() const { return reports::table3_md(study); }

CalibrateResult calibrate(const CalibrateOptions& o) {
  namespace fs = std::filesystem;
  check(o);
  CalibrationPlan plan;
  plan.rolling = o.rolling;
  plan.density = o.density;
  plan.shapes = grain_kinds(o.shapes);
  const fs::path dir = o.dataset.empty() ? o.default_dataset : o.dataset;
  CalibrateResult res;
  studies::CalibrationContext& ctx = res.context;
  ctx.dataset = dir.string();
  ctx.quality = o.quality;
  ctx.setup = validation::read_setup(dir / "setup.toml");
  {
    Station probe;  // the slump tests and the incline are the DEM's: every contact value is needed
    probe.material = ctx.setup.material;
    probe.belt = ctx.setup.belt;
    probe.plate = ctx.setup.plate;
    require_dem_keys(probe, (dir / "setup.toml").string(), "calibrate's DEM");
  }
  if (o.prepare_output) {  // before minutes of slump tests
    OutputPlan out;
    out.inputs = validation::dataset_files(dir);
    out.files = {"calibration.csv", "incline.csv", "calibration.md", "calibration.html", "calibration.svg",
                 "material.toml", "calibration-timing.csv"};
    o.prepare_output(out);
  }
  plan.sphere = Grain::sphere(o.sphere_diameter_mm * 1e-3);
  plan.clump = Grain::reference_clump(o.clump_diameter_mm * 1e-3);
  plan.settings = slump_preset(o.quality == "standard" ? RigQuality::standard : RigQuality::quick);
  plan.settings.threads = o.threads;
  plan.settings.seed = o.seed;
  if (o.target) {
    // Default target: the dataset's measured loose-poured bulk density.
    plan.targets.bulk_density = o.target_bulk_density ? *o.target_bulk_density : ctx.setup.material.bulk_density;
    if (o.target_pile_height_mm) plan.targets.pile_height = *o.target_pile_height_mm * 1e-3;
  }
  plan.incline = o.incline;
  plan.jobs = resolve_jobs(o.jobs);
  if (o.planned) o.planned(ctx, static_cast<int>(plan.shapes.size() * plan.rolling.size() * plan.density.size()));
  std::function<void(const CalibrationProgress&)> progress;
  if (o.progress)
    progress = [](const CalibrationProgress& p) {
      progress::status(p.done ? std::string()
                              : fmt::format("[{:>2}/{}] {} {:.2f}/{:.2f} s", p.index, p.count, p.slump.phase,
                                            p.slump.time, p.slump.max_time));
    };
  res.study = run_calibration(ctx.setup.material, plan, progress);
  return res;
}

}  // namespace chutelab::api
