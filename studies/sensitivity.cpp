#include "studies/sensitivity.h"
#include "studies/csv_checks.h"
#include "core/csv_field.h"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include <fmt/format.h>

#include "core/input_error.h"
#include "core/number.h"
#include "dem/station/settings.h"
#include "validation/csv_table.h"
#include "validation/output_files.h"

namespace chutelab::studies {
namespace {

using validation::csv_number;

std::vector<std::string> split_cell(const std::string& cell, char sep) {
  std::vector<std::string> out;
  std::size_t a = 0;
  while (a < cell.size()) {
    const auto b = std::min(cell.find(sep, a), cell.size());
    if (b > a) out.push_back(cell.substr(a, b - a));
    a = b + 1;
  }
  return out;
}

// Diameters equal to 0.1 mm (how they are named) are one size.
bool same_size(double a, double b) { return std::round(a * 1e4) == std::round(b * 1e4); }

std::string fraction(double f) { return fmt::format("{:.3g}", f); }

// The modulus as run, against the dataset's: "the dataset's G", "the dataset's G / 3", "... x 3.33".
// The tolerance covers the 6 significant digits the CSV keeps.
std::string modulus_text(double scale) {
  if (!std::isfinite(scale)) return "G of the base run (its ratio to the dataset's was not recorded)";
  if (std::abs(scale - 1.0) < 1e-5) return "the dataset's G";
  const double inv = 1.0 / scale;
  if (scale < 1.0 && std::abs(inv - std::round(inv)) < 1e-5 * inv) return fmt::format("the dataset's G / {:g}", std::round(inv));
  return fmt::format("the dataset's G x {:.3g}", scale);
}

}  // namespace

const VariantColumns& variant_columns() {
  namespace st = dem::station;
  static const VariantColumns c{std::string(st::dem_field(&st::RunSettings::contact).option),
                                std::string(st::dem_field(&st::RunSettings::particle_shape).option),
                                std::string(st::dem_field(&st::RunSettings::particle_diameter).option),
                                std::string(st::dem_field(&st::RunSettings::dt_fraction).option)};
  return c;
}

std::string mm_text(double m) { return fmt::format("{:g}", std::round(m * 1e4) / 10.0); }

std::vector<std::string> run_notes(const SensitivityStudy& s) {
  std::vector<std::string> notes;
  // What the step really was: the Rayleigh cap, not dt_fraction t_c, sets it when it is tighter.
  std::vector<std::string> capped;
  for (const auto& r : s.rows) {
    const auto& o = r.outcome;
    if (!(o.collision_time > 0.0) || !(o.dt > 0.0)) continue;
    const double ratio = o.dt / o.collision_time;
    if (ratio < r.variant.dt_fraction * (1.0 - 1e-3))
      capped.push_back(fmt::format("{} {:.3f} t_c (not {:g})", r.variant.key, ratio, r.variant.dt_fraction));
  }
  if (!capped.empty())
    notes.push_back(fmt::format("dt as run: the cap at a fraction of the Rayleigh time was tighter than the fraction of "
                                "the collision time for {}", fmt::join(capped, ", ")));
  if (!s.sizes_left_out.empty()) {
    std::vector<std::string> d;
    for (double x : s.sizes_left_out) d.push_back(mm_text(x) + " mm");
    notes.push_back(fmt::format("not run: spheres of {}, of the reference study's sizes (at quick quality the default leaves 5.6 mm "
                                "out: that one run costs more than the rest of the study's ~10 min); give --sizes to run "
                                "them", fmt::join(d, ", ")));
  }
  if (!s.variants_left_out.empty())
    notes.push_back(fmt::format("not run (--only): {}", fmt::join(s.variants_left_out, ", ")));
  return notes;
}

std::string_view name(VariantGroup g) {
  switch (g) {
    case VariantGroup::base: return "base";
    case VariantGroup::contact: return "contact model";
    case VariantGroup::shape: return "particle shape";
    case VariantGroup::time_step: return "time step";
    case VariantGroup::modulus: return "shear modulus";
    case VariantGroup::size: return "particle size";
  }
  return "?";
}

std::vector<SensitivityVariant> table6_variants(const Table6Base& b) {
  const double base_d = b.diameter;
  std::vector<SensitivityVariant> v;
  SensitivityVariant base;
  base.key = "base";
  base.diameter = base_d;
  base.dt_fraction = b.dt_fraction;
  base.rayleigh_fraction = b.rayleigh_fraction;
  base.label = fmt::format("{}, spheres d = {} mm, dt = {} t_c (at most {} t_R), {}", dem::NormalLaw{}.title(),
                           mm_text(base_d), fraction(b.dt_fraction), fraction(b.rayleigh_fraction),
                           modulus_text(b.modulus_scale));
  v.push_back(base);
  auto variant = [&](std::string key, std::string label, VariantGroup g) {
    SensitivityVariant x = base;
    x.key = std::move(key);
    x.label = std::move(label);
    x.group = g;
    return x;
  };
  const auto lsd_law = dem::NormalLaw::of<dem::LinearSpringDashpot>();
  auto lsd = variant("LSD", fmt::format("{}, same collision time", lsd_law.title()), VariantGroup::contact);
  lsd.contact = lsd_law.key();
  v.push_back(lsd);
  // The reference study's two shaped rows: its 4.4 mm clump against its 5.6 mm spheres (about the pellet's
  // size), and a clump of 5.6 mm spheres ("d increased"). Relative to this base: 4.4/5.6 d and d.
  auto clump = variant("clump", "", VariantGroup::shape);
  clump.shape = "clump";
  clump.diameter = base_d * 4.4 / 5.6;
  clump.label = fmt::format("two-sphere clump (Fig. 4c), spheres d = {} mm (the reference study's 4.4 vs 5.6 mm)", mm_text(clump.diameter));
  v.push_back(clump);
  auto clump_d = variant("clump-d", "", VariantGroup::shape);
  clump_d.shape = "clump";
  clump_d.label = fmt::format("two-sphere clump, spheres d = {} mm = the base's (the reference study's \"shaped d = 5.6 mm, d "
                              "increased\")", mm_text(base_d));
  v.push_back(clump_d);
  auto dt = variant("dt/20", fmt::format("dt = {} t_c (at most {} t_R): half the base step", fraction(b.dt_fraction / 2),
                                         fraction(b.rayleigh_fraction / 2)),
                    VariantGroup::time_step);
  dt.dt_fraction = b.dt_fraction / 2;
  dt.rayleigh_fraction = b.rayleigh_fraction / 2;
  v.push_back(dt);
  auto g10 = variant("Gx10", fmt::format("G x 10 of the base (Young's modulus x 10): {}", modulus_text(10 * b.modulus_scale)),
                     VariantGroup::modulus);
  g10.modulus_scale = 10.0;
  v.push_back(g10);
  auto g01 = variant("G/10", fmt::format("G / 10 of the base: {}", modulus_text(0.1 * b.modulus_scale)), VariantGroup::modulus);
  g01.modulus_scale = 0.1;
  v.push_back(g01);
  // The reference study's sizes are absolute (5.6, 9, 13.6 mm): a size variant is a sphere of that diameter,
  // whatever the base. Scaling factors of the base instead would reach a different regime at a
  // coarse base (33 mm spheres are one grain deep in this stream).
  std::vector<double> sizes = b.sizes;
  std::sort(sizes.begin(), sizes.end());
  for (std::size_t k = 0; k < sizes.size(); ++k) {
    const double d = sizes[k];
    if (same_size(d, base_d) || (k > 0 && same_size(d, sizes[k - 1]))) continue;
    auto s = variant(fmt::format("d={}mm", mm_text(d)),
                     fmt::format("spheres d = {} mm ({:.2f} x the base's); mass flow kept: {} grains", mm_text(d), d / base_d,
                                 d > base_d ? "fewer, heavier" : "more, lighter"),
                     VariantGroup::size);
    s.diameter = d;
    v.push_back(s);
  }
  return v;
}

void evaluate(SensitivityStudy& s) {
  if (s.rows.empty()) return;
  const VariantOutcome& b = s.rows[0].outcome;
  for (auto& r : s.rows) {
    const VariantOutcome& o = r.outcome;
    if (!(b.resultant.value > 0.0) || !(o.resultant.value > 0.0)) {
      r.change = {std::nan(""), std::nan("")};
      continue;
    }
    const double q = o.resultant.value / b.resultant.value;
    r.change.value = 100.0 * (q - 1.0);
    r.change.se = &r == &s.rows[0] ? 0.0
                                   : 100.0 * q *
                                         std::hypot(o.resultant.se / o.resultant.value, b.resultant.se / b.resultant.value);
  }
  Table6Verdict v;
  v.mean_insensitive = true;
  for (const auto& r : s.rows) {
    const auto g = r.variant.group;
    if (g == VariantGroup::contact || g == VariantGroup::shape || g == VariantGroup::time_step ||
        g == VariantGroup::modulus) {
      v.mean_tested = true;
      if (!std::isfinite(r.change.value) || std::abs(r.change.value) > s.limit_percent) v.mean_insensitive = false;
      if (std::isfinite(r.change.value) && std::abs(r.change.value) >= std::abs(v.worst_change)) {
        v.worst_change = r.change.value;
        v.worst_variant = r.variant.key;
      }
    }
    if (g == VariantGroup::base || g == VariantGroup::size) {
      v.size_fluctuation.emplace_back(r.outcome.diameter, r.outcome.fluct_resultant);
      if (g == VariantGroup::size && std::isfinite(r.change.value))
        v.size_mean_spread = std::max(v.size_mean_spread, std::abs(r.change.value));
    }
  }
  // Increasing size: the claim is that every step up in d raises the fluctuation.
  std::sort(v.size_fluctuation.begin(), v.size_fluctuation.end());
  v.size_tested = v.size_fluctuation.size() >= 2;
  v.sizes_left_out = s.sizes_left_out;
  std::sort(v.sizes_left_out.begin(), v.sizes_left_out.end());
  v.variants_left_out = s.variants_left_out;
  v.fluctuation_grows = v.size_tested;
  for (std::size_t k = 1; k < v.size_fluctuation.size(); ++k)
    v.fluctuation_grows = v.fluctuation_grows && v.size_fluctuation[k].second > v.size_fluctuation[k - 1].second;
  std::vector<std::string> fl;
  for (const auto& [d, f] : v.size_fluctuation) fl.push_back(fmt::format("{:.1f} N at {} mm", f, mm_text(d)));
  std::string head;
  const std::string on_what_ran = v.mean_insensitive && v.fluctuation_grows ? "reproduced" : "NOT reproduced";
  if (!(v.mean_tested && v.size_tested)) {
    head = "The reference study's Table 6 conclusion NOT FULLY TESTED (a subset of the variants ran)";
  } else if (!v.variants_left_out.empty()) {
    head = fmt::format("The reference study's Table 6 conclusion NOT FULLY TESTED: {} not run (--only); on what ran it is {}",
                       fmt::join(v.variants_left_out, ", "), on_what_ran);
  } else if (!v.sizes_left_out.empty()) {
    // Judged on what ran, but never called reproduced: a left-out size is a claim not checked.
    std::vector<std::string> out, all;
    for (double d : v.sizes_left_out) out.push_back(mm_text(d) + " mm");
    for (const auto& [d, f] : v.size_fluctuation) all.push_back(mm_text(d));
    for (double d : v.sizes_left_out) all.push_back(mm_text(d));
    std::sort(all.begin(), all.end(), [](const std::string& a, const std::string& b) { return std::stod(a) < std::stod(b); });
    head = fmt::format("The reference study's Table 6 conclusion NOT FULLY TESTED: {} left out at {} quality (run with --sizes {}); on "
                       "what ran it is {}",
                       fmt::join(out, ", "), s.quality, fmt::join(all, ","), on_what_ran);
  } else {
    head = v.reproduced() ? "The reference study's Table 6 conclusion REPRODUCED" : "The reference study's Table 6 conclusion NOT reproduced";
  }
  const std::string mean_part =
      v.mean_tested ? fmt::format("contact model, shape, time step and shear modulus change it by at most {:+.1f} % ({}; "
                                  "limit ±{:g} %) — {}",
                                  v.worst_change, v.worst_variant, s.limit_percent,
                                  v.mean_insensitive ? "small, as in the reference study" : "larger than the reference study found")
                    : std::string("no contact/shape/dt/G variant ran");
  const std::string size_part =
      v.size_tested ? fmt::format("{} — {}", fmt::join(fl, ", "),
                                  v.fluctuation_grows ? "it grows with d, as in the reference study" : "it does not grow steadily with d")
                    : std::string("fewer than two sizes ran");
  v.text = fmt::format(
      "{}. Mean resultant plate force against the base: {}. Fluctuation (standard deviation of the sampled R) with "
      "particle size: {}. The size variants change the mean by up to {:.1f} %.",
      head, mean_part, size_part, v.size_mean_spread);
  s.verdict = v;
}

SensitivityStudy read_sensitivity_csv(const std::filesystem::path& file) {
  using validation::CsvTable;
  const VariantColumns& vc = variant_columns();
  const CsvTable t = CsvTable::read(
      file, {"variant", "group", vc.contact, vc.shape, vc.diameter, "dt_s", vc.dt_fraction, "collision_time_s",
             "modulus_scale", "normal_force_N", "normal_force_se_N", "shear_force_N", "shear_force_se_N",
             "resultant_force_N", "resultant_force_se_N", "fluctuation_normal_N", "fluctuation_shear_N",
             "fluctuation_resultant_N", "simulated_s", "steps", "peak_particles", "steady", "condition",
             "belt_speed_mps", "mass_flow_tph", "quality", "change_limit_pct"});
  const std::string f = file.string();
  if (t.rows().empty()) throw InputError(f, 0, "variant", "no variants in the file (a header only)");
  auto col = [&](std::string_view c) { return t.require(c); };
  auto num = [&](const validation::CsvRow& r, std::string_view c) { return t.number(r, col(c)); };
  // Empty = not measured (a run without a steady mean): NaN, as the command wrote it.
  auto opt = [&](const validation::CsvRow& r, std::string_view c) {
    return t.optional_number(r, col(c)).value_or(std::nan(""));
  };
  SensitivityStudy s;
  s.dataset = file.parent_path().string();
  const auto& first = t.rows().front();
  s.condition = t.text(first, col("condition"));
  s.quality = t.text(first, col("quality"));
  // Columns added later (provenance, the base as resolved): optional, so older studies still read.
  auto text_or = [&](const validation::CsvRow& r, std::string_view c) {
    const auto k = t.column(c);
    return k ? t.text(r, *k) : std::string();
  };
  auto number_or = [&](const validation::CsvRow& r, std::string_view c, double fallback) {
    const auto k = t.column(c);
    return k ? t.optional_number(r, *k).value_or(fallback) : fallback;
  };
  s.dataset_name = text_or(first, "dataset");
  for (const auto& item : split_cell(text_or(first, "sizes_left_out_mm"), ';')) {
    const double d = parse_number(item).value_or(0.0);
    if (!(d > 0.0) || !std::isfinite(d))
      throw InputError(f, first.line, "sizes_left_out_mm", fmt::format("'{}' is not a diameter in mm", item));
    s.sizes_left_out.push_back(d * 1e-3);
  }
  s.variants_left_out = split_cell(text_or(first, "variants_left_out"), ';');
  s.belt_speed = num(first, "belt_speed_mps");
  s.mass_flow = num(first, "mass_flow_tph") / 3.6;
  s.limit_percent = num(first, "change_limit_pct");
  for (const auto& r : t.rows()) {
    SensitivityRow row;
    SensitivityVariant& v = row.variant;
    v.key = t.text(r, col("variant"));
    const std::string g = t.text(r, col("group"));
    bool known = false;
    for (VariantGroup k : {VariantGroup::base, VariantGroup::contact, VariantGroup::shape, VariantGroup::time_step,
                           VariantGroup::modulus, VariantGroup::size})
      if (name(k) == g) {
        v.group = k;
        known = true;
      }
    if (!known)
      throw InputError(f, r.line, "group",
                       fmt::format("unknown group '{}' (base, contact model, particle shape, time step, shear modulus, "
                                   "particle size)", g));
    if ((&r == &first) != (v.group == VariantGroup::base))
      throw InputError(f, r.line, "group", "the first row, and only it, must be the base run");
    v.contact = t.text(r, col(vc.contact));
    v.shape = t.text(r, col(vc.shape));
    v.dt_fraction = num(r, vc.dt_fraction);
    v.rayleigh_fraction = number_or(r, "rayleigh_fraction", v.rayleigh_fraction);
    v.modulus_scale = num(r, "modulus_scale");
    VariantOutcome& o = row.outcome;
    o.diameter = num(r, vc.diameter) * 1e-3;
    v.diameter = o.diameter;
    if (!(o.diameter > 0.0)) throw InputError(f, r.line, vc.diameter, "must be > 0");
    o.dt = num(r, "dt_s");
    o.collision_time = num(r, "collision_time_s");
    auto se = [&](std::string_view c) { return t.optional_number(r, col(c)).value_or(0.0); };
    o.normal = {opt(r, "normal_force_N"), se("normal_force_se_N")};
    o.shear = {opt(r, "shear_force_N"), se("shear_force_se_N")};
    o.resultant = {opt(r, "resultant_force_N"), se("resultant_force_se_N")};
    o.fluct_normal = opt(r, "fluctuation_normal_N");
    o.fluct_shear = opt(r, "fluctuation_shear_N");
    o.fluct_resultant = opt(r, "fluctuation_resultant_N");
    o.wall_seconds = number_or(r, "run_seconds", std::nan(""));  // in files written before the timing file
    o.simulated = num(r, "simulated_s");
    o.steps = csv_count(t, r, col("steps"));
    o.particles = static_cast<std::size_t>(csv_count(t, r, col("peak_particles")));
    o.steady = csv_flag(t, r, col("steady"));
    s.rows.push_back(row);
  }
  // Wall-clock times live beside the study (sensitivity-timing.csv), so the study's own files are
  // the same bytes from one process or many.
  if (const auto timing = file.parent_path() / "sensitivity-timing.csv"; std::filesystem::exists(timing)) {
    const CsvTable tt = CsvTable::read(timing, {"variant", "run_seconds"});
    for (const auto& tr : tt.rows())
      for (auto& row : s.rows)
        if (row.variant.key == tt.text(tr, tt.require("variant")))
          row.outcome.wall_seconds = tt.number(tr, tt.require("run_seconds"));
  }
  s.wall_seconds = 0.0;
  for (const auto& row : s.rows) s.wall_seconds += row.outcome.wall_seconds;
  // Labels are not stored (they hold commas); the variants of the base as it ran give them back.
  const SensitivityRow& b = s.rows.front();
  s.base.diameter = b.outcome.diameter;
  s.base.dt_fraction = b.variant.dt_fraction;
  s.base.rayleigh_fraction = b.variant.rayleigh_fraction;
  s.base.modulus_scale = number_or(first, "modulus_scale_of_dataset", std::nan(""));
  s.base.sizes = s.sizes_left_out;
  for (const auto& row : s.rows)
    if (row.variant.group == VariantGroup::size) s.base.sizes.push_back(row.outcome.diameter);
  for (const auto& known : table6_variants(s.base))
    for (auto& row : s.rows)
      if (row.variant.key == known.key) row.variant.label = known.label;
  for (auto& row : s.rows)
    if (row.variant.label.empty()) row.variant.label = row.variant.key;
  evaluate(s);
  return s;
}

std::string sensitivity_csv(const SensitivityStudy& s) {
  const VariantColumns& vc = variant_columns();
  std::string out = fmt::format("variant,group,{},{},{},dt_s,{},collision_time_s,modulus_scale,", vc.contact, vc.shape,
                                vc.diameter, vc.dt_fraction) +
      "normal_force_N,normal_force_se_N,shear_force_N,shear_force_se_N,resultant_force_N,resultant_force_se_N,"
      "fluctuation_normal_N,fluctuation_shear_N,fluctuation_resultant_N,change_resultant_pct,change_se_pct,"
      "simulated_s,steps,peak_particles,steady,condition,belt_speed_mps,mass_flow_tph,quality,"
      "change_limit_pct,dataset,rayleigh_fraction,modulus_scale_of_dataset,sizes_left_out_mm,variants_left_out\n";
  std::vector<std::string> left_out;
  for (double d : s.sizes_left_out) left_out.push_back(mm_text(d));
  // One list in one cell: ';' keeps the CSV plain (no quoting).
  const std::string left = fmt::format("{}", fmt::join(left_out, ";"));
  for (const auto& r : s.rows) {
    const auto& v = r.variant;
    const auto& o = r.outcome;
    out += fmt::format("{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},",
                       v.key, name(v.group),
                       v.contact, v.shape, csv_number(o.diameter * 1e3), csv_number(o.dt), csv_number(v.dt_fraction),
                       csv_number(o.collision_time), csv_number(v.modulus_scale), csv_number(o.normal.value),
                       csv_number(o.normal.se), csv_number(o.shear.value), csv_number(o.shear.se),
                       csv_number(o.resultant.value), csv_number(o.resultant.se), csv_number(o.fluct_normal),
                       csv_number(o.fluct_shear), csv_number(o.fluct_resultant), csv_number(r.change.value),
                       csv_number(r.change.se), csv_number(o.simulated), o.steps, o.particles,
                       o.steady ? 1 : 0, csv_field(s.condition), csv_number(s.belt_speed), csv_number(s.mass_flow * 3.6), s.quality,
                       csv_number(s.limit_percent));
    out += fmt::format("{},{},{},{},{}\n", csv_field(s.dataset_name), csv_number(v.rayleigh_fraction),
                       std::isfinite(s.base.modulus_scale) ? csv_number(s.base.modulus_scale * v.modulus_scale) : std::string(),
                       left, fmt::join(s.variants_left_out, ";"));
  }
  return out;
}

std::string sensitivity_timing_csv(const SensitivityStudy& s) {
  std::string out = "variant,run_seconds\n";
  for (const auto& r : s.rows) out += fmt::format("{},{}\n", r.variant.key, csv_number(r.outcome.wall_seconds));
  return out;
}

// Finding 6's words, as the report's findings table shows them.
namespace {
const char* kTable6 =
    "Sensitivity (the reference study's Table 6): LSD vs Hertz-Mindlin, sphere vs two-sphere clump, dt = t_c/10 vs t_c/20 and "
    "shear modulus x10 or /10 change the mean plate force little; larger particles give a similar mean force "
    "with larger fluctuations.";
const char* kMeanClaim = "contact model, shape, time step and G change the mean R by no more than the limit";
const char* kSizeClaim = "the fluctuation of R grows with the particle diameter";
}  // namespace

validation::ReferenceFinding sensitivity_finding(const SensitivityStudy* s, std::string_view validated) {
  validation::ReferenceFinding f{6, kTable6};
  if (!s) {
    const std::string why = "no sensitivity study given: validate --studies takes the folder of a sensitivity run";
    f.claims = {{kMeanClaim, false, false, why}, {kSizeClaim, false, false, why}};
  } else {
    const auto& v = s->verdict;
    // Which rig the numbers are from: the main job validates one dataset with a study of another.
    const std::string where =
        s->dataset_name.empty()
            ? fmt::format("{} (dataset not recorded)", s->condition)
            : fmt::format("{} of {}{}", s->condition, s->dataset_name,
                          !validated.empty() && validated != s->dataset_name ? " (not this dataset)" : "");
    // Variants --only left out: sizes are keyed "d=...".
    std::vector<std::string> mean_out, size_out;
    for (const auto& k : v.variants_left_out) (k.rfind("d=", 0) == 0 ? size_out : mean_out).push_back(k);
    std::string not_run;
    if (!mean_out.empty()) not_run = fmt::format("; not run: {}", fmt::join(mean_out, ", "));
    f.claims.push_back({kMeanClaim, v.mean_tested, v.mean_tested && v.mean_insensitive && mean_out.empty(),
                        v.mean_tested ? fmt::format("{}, {} quality: largest change {:+.1f} % ({}), limit ±{:g} %{}", where,
                                                    s->quality, v.worst_change, v.worst_variant, s->limit_percent, not_run)
                                      : "no contact, shape, dt or G variant ran"});
    f.claims.back().undecided = v.mean_tested && v.mean_insensitive && !mean_out.empty();
    std::vector<std::string> fl;
    for (const auto& [d, sd] : v.size_fluctuation) fl.push_back(fmt::format("{:.1f} N at {:.1f} mm", sd, d * 1e3));
    std::vector<std::string> out = size_out;
    for (double d : v.sizes_left_out) out.push_back(fmt::format("{:g} mm", std::round(d * 1e4) / 10.0));
    // A size of the reference study's Table 6 that did not run leaves the claim unchecked there:
    // undecided if it holds on the sizes that ran (one that fails there fails anyway).
    const bool all_sizes = out.empty();
    f.claims.push_back({kSizeClaim, v.size_tested, v.size_tested && v.fluctuation_grows && all_sizes,
                        v.size_tested ? fmt::format("sd of R: {}; the sizes move the mean by up to {:.1f} %{}",
                                                    fmt::join(fl, ", "), v.size_mean_spread,
                                                    all_sizes ? std::string()
                                                              : fmt::format("; not run: {} (so not decided over the "
                                                                            "reference study's sizes)", fmt::join(out, ", ")))
                                      : "fewer than two particle sizes ran"});
    f.claims.back().undecided = v.size_tested && v.fluctuation_grows && !all_sizes;
  }
  f.status = validation::status_of(f.claims);
  return f;
}

}  // namespace chutelab::studies
