#include "logs/provenance_csv.h"

#include <fmt/format.h>
#include <algorithm>
#include <cmath>
#include <set>
#include <sstream>

#include "core/csv_field.h"

namespace chutelab::logs {

namespace {

std::string num(double v) { return csv_number(v); }
// Times are sums of the sampling interval: to the microsecond, not to the last bit of the sum.
std::string secs(double v) { return csv_number(std::round(v * 1e6) / 1e6); }

double part(const QuantityReading& q, std::string_view name) {
  for (const auto& p : q.budget.parts)
    if (p.name == name) return p.u;
  return 0.0;
}

}  // namespace

std::string method_words(const ConditionReading& c, const QuantityReading& q) {
  std::string tare = c.segments.before.ok() && c.segments.after.ok() ? "tare before and after"
                     : c.segments.before.ok()                        ? "tare before"
                     : c.segments.after.ok()                         ? "tare after"
                                                                     : "the layout's zero";
  std::string s = fmt::format("mean of {} samples at {:.4g} Hz over the {} window; u: ", q.stats.n, 1.0 / c.dt,
                              c.segments.steady ? "steady" : "middle (not steady)");
  if (q.stats.blocks >= kMinBlocks)
    s += fmt::format("{} batch means of {:.2f} s", q.stats.blocks, q.stats.block);
  else
    s += "the autocorrelation time";
  s += fmt::format(" (tau {:.2f} s, {:.1f} independent samples), {}, calibration, resolution", q.stats.tau,
                   q.stats.n_eff, tare);
  if (q.creep) s += ", creep corrected to the load's start";
  if (q.budget.widening > 1.0005) s += fmt::format("; widened x{:.3f} for {:.1f} degrees of freedom", q.budget.widening, q.budget.dof);
  return s;
}

std::string measurements_csv(const validation::Dataset& d, const LogImport& logs) {
  std::ostringstream o;
  o << "condition,quantity,value,uncertainty,source_file,window_start_s,window_end_s,method\n";
  for (const auto& m : d.measurements) {
    bool from_log = false;
    for (const auto& c : logs.conditions) from_log = from_log || m.where.file == c.file.string();
    if (from_log) continue;
    const double k = info(m.quantity).to_boundary;
    o << csv_field(m.condition) << ',' << name(m.quantity) << ',' << num(m.value * k) << ','
      << (m.uncertainty ? num(*m.uncertainty * k) : std::string()) << ",,,,\n";
  }
  for (const auto& c : logs.conditions)
    for (const auto& q : c.quantities) {
      const double k = info(q.quantity).to_boundary;
      o << csv_field(c.condition) << ',' << name(q.quantity) << ',' << num(q.value * k) << ',' << num(q.budget.u * k)
        << ',' << csv_field("logs/" + c.file.filename().string()) << ',' << secs(c.segments.window.start) << ','
        << secs(c.segments.window.end) << ',' << csv_field(method_words(c, q)) << '\n';
    }
  return o.str();
}

std::string log_provenance_csv(const LogImport& logs) {
  std::ostringstream o;
  o << "condition,quantity,value,uncertainty,file,sample_interval_s,load_on_s,load_off_s,window_start_s,window_end_s,"
       "steady,tare_before_start_s,tare_before_end_s,tare_after_start_s,tare_after_end_s,samples,tau_s,n_eff,"
       "batches,batch_s,scatter,zero,calibration,resolution,creep,dof,widening,too_short,creep_change,"
       "creep_change_uncertainty,creep_flagged,creep_correction,zero_drift_N,zero_drift_uncertainty_N,"
       "zero_drift_flagged\n";
  for (const auto& c : logs.conditions) {
    // The largest zero drift of the plate's channels, in N.
    const ChannelZero* worst = nullptr;
    for (const auto& z : c.zeros)
      if (!worst || std::abs(z.drift) / std::max(z.u_drift, 1e-300) > std::abs(worst->drift) / std::max(worst->u_drift, 1e-300))
        worst = &z;
    for (const auto& q : c.quantities) {
      const double k = info(q.quantity).to_boundary;
      const auto& sg = c.segments;
      o << csv_field(c.condition) << ',' << name(q.quantity) << ',' << num(q.value * k) << ',' << num(q.budget.u * k)
        << ',' << csv_field("logs/" + c.file.filename().string()) << ',' << secs(c.dt) << ',' << secs(sg.load_on) << ','
        << secs(sg.load_off) << ',' << secs(sg.window.start) << ',' << secs(sg.window.end) << ','
        << (sg.steady ? "yes" : "no") << ',' << secs(sg.before.start) << ',' << secs(sg.before.end) << ','
        << secs(sg.after.start) << ',' << secs(sg.after.end) << ',' << q.stats.n << ',' << num(q.stats.tau) << ','
        << num(q.stats.n_eff) << ',' << q.stats.blocks << ',' << num(q.stats.block) << ','
        << num(part(q, "scatter") * k) << ',' << num(part(q, "zero") * k) << ',' << num(part(q, "calibration") * k)
        << ',' << num(part(q, "resolution") * k) << ',' << num(part(q, "creep") * k) << ',' << num(q.budget.dof)
        << ',' << num(q.budget.widening) << ',' << (q.budget.too_short ? "yes" : "no") << ','
        << num(q.creep_change * k) << ',' << num(q.creep_u * k) << ',' << (q.creep ? "yes" : "no") << ','
        << num(q.creep_correction * k) << ',' << (worst ? num(worst->drift) : "") << ','
        << (worst ? num(worst->u_drift) : "") << ',' << (c.drift_flagged() ? "yes" : "no") << '\n';
    }
  }
  return o.str();
}

std::string log_checks_csv(const LogImport& logs) {
  std::ostringstream o;
  o << "condition,channel,check,recorded,logged,logged_uncertainty,difference_percent,off\n";
  for (const auto& c : logs.conditions)
    for (const auto& k : c.checks) {
      const bool speed = k.role == Role::belt_speed;
      const double s = speed ? 1.0 : 3.6;  // SI -> m/s, t/h
      o << csv_field(c.condition) << ',' << csv_field(k.column) << ',' << (speed ? "belt_speed_mps" : "mass_flow_tph")
        << ',' << num(k.recorded * s) << ',' << num(k.logged * s) << ',' << num(k.u * s) << ','
        << num(100.0 * k.relative()) << ',' << (k.off ? "yes" : "no") << '\n';
    }
  return o.str();
}

}  // namespace chutelab::logs
