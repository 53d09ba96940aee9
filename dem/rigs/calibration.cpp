#include "dem/rigs/calibration.h"

#include <chrono>
#include <cmath>
#include <limits>
#include <sstream>

#include <fmt/format.h>

#include "core/campaign.h"
#include "core/input_error.h"

namespace chutelab::dem::rigs {

std::string_view name(GrainKind k) { return k == GrainKind::sphere ? "sphere" : "clump"; }

double target_distance(const SlumpResult& r, const CalibrationTargets& t) {
  if (!t.any()) return std::numeric_limits<double>::quiet_NaN();
  double sum = 0.0;
  int n = 0;
  if (t.bulk_density) {
    const double e = (r.bulk_density - *t.bulk_density) / *t.bulk_density;
    sum += e * e;
    ++n;
  }
  if (t.pile_height) {
    const double e = (r.pile_height - *t.pile_height) / *t.pile_height;
    sum += e * e;
    ++n;
  }
  return std::sqrt(sum / n);
}

namespace {

// Results as text for the campaign's exchange: every number with 17 significant digits, so a
// result read back is the result that ran, to the last bit.
std::string g17(double v) { return fmt::format("{:.17g}", v); }

std::string slump_text(const SlumpResult& r) {
  std::string o = fmt::format("{} {} {} {}\n", r.particles, r.bed_grains, r.steps, r.settled ? 1 : 0);
  for (double v : {r.sample_mass, r.fill_height, r.surface_height, r.bulk_density, r.pile_height, r.repose_angle_deg,
                   r.pile_radius, r.peak_height, r.lost_mass, r.dt, r.settle_time, r.pile_time, r.wall_seconds})
    o += g17(v) + " ";
  o += fmt::format("\n{}\n", r.profile.size());
  for (const auto& p : r.profile) o += fmt::format("{} {} {}\n", g17(p.r), g17(p.h), p.cells);
  return o + r.grain;  // last: a label may hold anything
}

double read_double(std::istringstream& in) {
  std::string v;
  in >> v;
  return std::strtod(v.c_str(), nullptr);
}

SlumpResult slump_from_text(const std::string& text) {
  std::istringstream in(text);
  SlumpResult r;
  int settled = 0;
  in >> r.particles >> r.bed_grains >> r.steps >> settled;
  r.settled = settled != 0;
  for (double* v : {&r.sample_mass, &r.fill_height, &r.surface_height, &r.bulk_density, &r.pile_height,
                    &r.repose_angle_deg, &r.pile_radius, &r.peak_height, &r.lost_mass, &r.dt, &r.settle_time,
                    &r.pile_time, &r.wall_seconds})
    *v = read_double(in);
  std::size_t n = 0;
  in >> n;
  for (std::size_t k = 0; k < n; ++k) {
    ProfilePoint p;
    p.r = read_double(in);
    p.h = read_double(in);
    in >> p.cells;
    r.profile.push_back(p);
  }
  in.get();
  std::getline(in, r.grain, '\0');
  if (!in && !in.eof()) throw std::logic_error("a slump result text does not read back");
  return r;
}

std::string incline_text(const InclineResult& r) {
  return fmt::format("{} {} {} {} {}", g17(r.onset_deg), static_cast<int>(r.motion), g17(r.predicted.onset_deg),
                     static_cast<int>(r.predicted.motion), r.runs);
}

InclineResult incline_from_text(const std::string& text) {
  std::istringstream in(text);
  InclineResult r;
  int motion = 0, predicted = 0;
  r.onset_deg = read_double(in);
  in >> motion;
  r.predicted.onset_deg = read_double(in);
  in >> predicted >> r.runs;
  r.motion = static_cast<Motion>(motion);
  r.predicted.motion = static_cast<Motion>(predicted);
  return r;
}

}  // namespace

CalibrationStudy run_calibration(const chutelab::Material& m, const CalibrationPlan& plan,
                                 const std::function<void(const CalibrationProgress&)>& progress) {
  const auto start = std::chrono::steady_clock::now();
  if (plan.rolling.empty()) throw InputError("", 0, "rolling", "give at least one rolling friction coefficient");
  if (plan.density.empty()) throw InputError("", 0, "density", "give at least one solid density");
  if (plan.shapes.empty()) throw InputError("", 0, "shape", "give at least one shape (sphere, clump)");
  for (double r : plan.rolling)
    if (!(r >= 0.0) || !std::isfinite(r) || r > 10.0)
      throw InputError("", 0, "rolling", fmt::format("rolling friction must be in [0, 10], got {}", r));
  for (double d : plan.density)
    if (!(d > 0.0) || !std::isfinite(d) || d > 3e4)
      throw InputError("", 0, "density", fmt::format("solid density must be in (0, 30000] kg/m^3, got {}", d));
  if (plan.targets.bulk_density && !(*plan.targets.bulk_density > 0.0 && std::isfinite(*plan.targets.bulk_density)))
    throw InputError("", 0, "target_bulk_density", "must be a finite number > 0 kg/m^3");
  if (plan.targets.pile_height && !(*plan.targets.pile_height > 0.0 && std::isfinite(*plan.targets.pile_height)))
    throw InputError("", 0, "target_pile_height", "must be a finite number > 0 mm");

  CalibrationStudy st;
  st.plan = plan;
  const int count = static_cast<int>(plan.shapes.size() * plan.rolling.size() * plan.density.size());
  // Every slump test and every incline onset is an independent run: one campaign (core/campaign.h),
  // in order in one process, side by side with --jobs, or spread over the ranks of mpirun.
  std::vector<campaign::Job> jobs;
  for (GrainKind shape : plan.shapes)
    for (double mu_r : plan.rolling)
      for (double rho : plan.density) {
        CalibrationRow row;
        row.shape = shape;
        row.rolling_friction = mu_r;
        row.solid_density = rho;
        st.rows.push_back(row);
        const int index = static_cast<int>(st.rows.size());
        const Grain& g = shape == GrainKind::sphere ? plan.sphere : plan.clump;
        // A clump test has ~1.8x the spheres of a sphere test and a rigid-body update per step.
        jobs.push_back({fmt::format("{} mu_r {:g} rho_s {:g}", g.label(), mu_r, rho), shape == GrainKind::clump ? 4.7 : 1.0,
                        [&m, rho, mu_r, g, &plan, index, count, &progress](const campaign::JobContext& ctx) {
                          auto each = [&](const SlumpProgress& sp) {
                            if (progress && ctx.progress) progress({index, count, nullptr, sp});
                          };
                          return slump_text(run_slump_test(m, rho, mu_r, g, plan.settings, each));
                        }});
      }
  if (plan.incline)
    for (double mu_r : plan.rolling)
      jobs.push_back({fmt::format("incline mu_r {:g}", mu_r), 0.3, [&m, mu_r, &plan](const campaign::JobContext&) {
                        return incline_text(find_incline_onset(m, m.friction_plate, mu_r, plan.sphere));
                      }});
  campaign::Options co;
  co.label = "calibrate";
  co.threads = plan.jobs;
  const std::vector<std::string> texts = campaign::run_campaign(jobs, co);
  for (std::size_t k = 0; k < st.rows.size(); ++k) {
    CalibrationRow& row = st.rows[k];
    row.slump = slump_from_text(texts[k]);
    row.distance = target_distance(row.slump, plan.targets);
    if (progress) progress({static_cast<int>(k) + 1, count, &row, {}});
  }
  if (plan.targets.any()) {
    for (std::size_t k = 0; k < st.rows.size(); ++k)
      if (std::isfinite(st.rows[k].distance) &&
          (st.closest < 0 || st.rows[k].distance < st.rows[static_cast<std::size_t>(st.closest)].distance))
        st.closest = static_cast<int>(k);
  }
  if (plan.incline) {
    for (std::size_t k = 0; k < plan.rolling.size(); ++k) {
      InclineRow r;
      r.rolling_friction = plan.rolling[k];
      r.wall_friction = m.friction_plate;
      r.result = incline_from_text(texts[st.rows.size() + k]);
      st.incline.push_back(r);
    }
  }
  st.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return st;
}

}  // namespace chutelab::dem::rigs
