#include "logs/virtual_rig.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <fmt/format.h>
#include <numbers>
#include <sstream>

#include "core/csv_field.h"
#include "core/input_error.h"
#include "dem/station/steady_state.h"
#include "validation/csv_table.h"
#include "validation/synthesize.h"

namespace chutelab::logs {

Fluctuation read_dem_series(const std::filesystem::path& file) {
  const validation::CsvTable tab =
      validation::CsvTable::read(file, {"t_s", "normal_force_N", "shear_force_N", "impact_point_y_mm"});
  const std::size_t ct = tab.require("t_s"), cn = tab.require("normal_force_N"), cs = tab.require("shear_force_N"),
                    cy = tab.require("impact_point_y_mm");
  std::vector<double> t, n, s, y;
  for (const auto& row : tab.rows()) {
    t.push_back(tab.number(row, ct));
    n.push_back(tab.number(row, cn));
    s.push_back(tab.number(row, cs));
    y.push_back(tab.optional_number(row, cy).value_or(std::nan("")));
  }
  if (t.size() < 10) throw InputError(tab.file(), 0, "t_s", "fewer than 10 samples: not a DEM run's series");
  const dem::station::SteadyWindow w = dem::station::detect_steady(t, n, dem::station::SteadyParams{});
  if (!w.found) throw InputError(tab.file(), 0, "normal_force_N", "the run never reaches a steady load");
  Fluctuation f;
  for (std::size_t k = 0; k < t.size(); ++k) {
    if (t[k] <= w.start || t[k] > w.end + 1e-9) continue;
    if (!std::isfinite(y[k])) continue;
    f.t.push_back(t[k]);
    f.normal.push_back(n[k]);
    f.shear.push_back(s[k]);
    f.impact_y.push_back(y[k] * 1e-3);
  }
  if (f.t.size() < 10) throw InputError(tab.file(), 0, "impact_point_y_mm", "too few samples in the steady window");
  return f;
}

Layout virtual_layout(const SensorModel& m, double y_upper, double y_lower) {
  Layout l;
  auto add = [&l](std::string column, std::string unit, Role r, double gain, double zero, double gain_u,
                  double resolution, std::optional<double> y) {
    Channel c;
    c.column = std::move(column);
    c.unit = std::move(unit);
    c.role = r;
    c.gain = gain;
    c.zero = zero;
    c.gain_u = gain_u;
    c.resolution = resolution;
    c.y = y;
    l.channels.push_back(std::move(c));
  };
  add("cell_upper_mV", "mV", Role::normal, 20.0, 0.05, m.gain_u, m.resolution_N / 20.0, y_upper);
  add("cell_lower_mV", "mV", Role::normal, 20.0, 0.05, m.gain_u, m.resolution_N / 20.0, y_lower);
  add("cell_shear_mV", "mV", Role::shear, 10.0, 0.05, m.gain_u, m.resolution_N / 10.0, std::nullopt);
  // 10 pulses a metre of belt; the belt scale in t/h.
  add("tacho_Hz", "Hz", Role::belt_speed, 0.1, 0.0, 0.002, 0.01, std::nullopt);
  add("belt_scale_tph", "tph", Role::mass_flow, 1.0, 0.0, 0.01, 0.01, std::nullopt);
  return l;
}

namespace {

// The load's envelope: 0 before the start, a first-order rise with a decaying surge, a first-order
// fall after the stop.
double envelope(double t, const SensorModel& m, double t_on, double t_off) {
  if (t < t_on) return 0.0;
  const double a = t - t_on;
  double e = (m.rise_s > 0.0 ? 1.0 - std::exp(-a / m.rise_s) : 1.0) * (1.0 + m.surge * std::exp(-a / m.surge_s));
  if (t > t_off) {
    const double b = t - t_off;
    const double at_off = (m.rise_s > 0.0 ? 1.0 - std::exp(-(t_off - t_on) / m.rise_s) : 1.0) *
                          (1.0 + m.surge * std::exp(-(t_off - t_on) / m.surge_s));
    e = m.fall_s > 0.0 ? at_off * std::exp(-b / m.fall_s) : 0.0;
  }
  return e;
}

// The fluctuation looped: its value at time a (s since the load's start), about its own mean.
struct Loop {
  const Fluctuation* f = nullptr;
  double mn = 0.0, ms = 0.0, mm = 0.0;  // means of normal, shear, moment
  void init() {
    if (!f) return;
    for (std::size_t k = 0; k < f->t.size(); ++k) {
      mn += f->normal[k];
      ms += f->shear[k];
      mm += f->normal[k] * f->impact_y[k];
    }
    const double n = static_cast<double>(f->t.size());
    mn /= n;
    ms /= n;
    mm /= n;
  }
  // Fluctuations of (normal, shear, moment) at a.
  std::array<double, 3> at(double a) const {
    if (!f) return {0.0, 0.0, 0.0};
    const double dt = f->t.size() > 1 ? f->t[1] - f->t[0] : 1.0;
    const double period = dt * static_cast<double>(f->t.size());
    double x = std::fmod(a, period) / dt;
    const std::size_t k = std::min(f->t.size() - 1, static_cast<std::size_t>(x));
    const std::size_t k1 = (k + 1) % f->t.size();
    x -= static_cast<double>(k);
    auto lerp = [&](double p, double q) { return p + (q - p) * x; };
    return {lerp(f->normal[k], f->normal[k1]) - mn, lerp(f->shear[k], f->shear[k1]) - ms,
            lerp(f->normal[k] * f->impact_y[k], f->normal[k1] * f->impact_y[k1]) - mm};
  }
};

}  // namespace

std::string virtual_log(const TrueCondition& truth, const SensorModel& m, const Layout& layout, std::uint64_t seed,
                        const Fluctuation* fluctuation) {
  validation::NormalStream rnd(seed);
  Loop loop{fluctuation};
  loop.init();
  // The two normal cells share R_n so that their moment puts it at impact_y.
  const Channel* up = &layout.channels[0];
  const Channel* lo = &layout.channels[1];
  const double y1 = *up->y, y2 = *lo->y;
  const double f_up = truth.normal * (truth.impact_y - y2) / (y1 - y2);
  const double f_lo = truth.normal - f_up;
  const double t_on = m.tare_s, t_off = m.tare_s + m.loaded_s;
  const double t_end = t_off + (m.fall_s * 5.0) + m.tare_s;
  const double dt = 1.0 / m.rate_hz;
  const int sub = std::max(1, static_cast<int>(std::ceil(500.0 / m.rate_hz)));
  const double h = dt / sub;
  const std::size_t nch = layout.channels.size();
  // Per channel: the calibration's error, the true zero.
  std::vector<double> gain_true(nch), zero_true(nch);
  for (std::size_t i = 0; i < nch; ++i) {
    const Channel& c = layout.channels[i];
    gain_true[i] = c.gain * (1.0 + c.gain_u * rnd.next());
    const bool plate = c.role == Role::normal || c.role == Role::shear;
    zero_true[i] = c.zero + (plate ? m.zero_offset_N * rnd.next() / c.gain : 0.0);
  }
  const double lp = m.lowpass_hz > 0.0 ? 1.0 - std::exp(-h * 2.0 * std::numbers::pi * m.lowpass_hz) : 1.0;
  const double ou_a = std::exp(-h / m.corr_s), ou_b = std::sqrt(1.0 - ou_a * ou_a);
  const double sc_a = std::exp(-h / 2.0), sc_b = std::sqrt(1.0 - sc_a * sc_a);
  std::vector<double> ou(nch, 0.0), filt(nch, 0.0);
  for (std::size_t i = 0; i < nch; ++i) ou[i] = rnd.next();
  std::ostringstream o;
  o << layout.time_column;
  for (const auto& c : layout.channels) o << ',' << c.column;
  o << '\n';
  const std::size_t n = static_cast<std::size_t>(std::floor(t_end / dt)) + 1;
  const double v_true = truth.belt_speed * (1.0 + m.belt_speed_error);
  const double flow_tph = truth.mass_flow * 3.6;
  double t = -dt;
  bool first = true;
  for (std::size_t k = 0; k < n; ++k) {
    for (int s = 0; s < sub; ++s) {
      t += h;
      const double env = envelope(t, m, t_on, t_off);
      const double creep = 1.0 + (t > t_on ? m.creep_per_s * (std::min(t, t_off) - t_on) : 0.0);
      const auto fl = loop.at(std::max(0.0, t - t_on));
      const double fl_up = (fl[2] - y2 * fl[0]) / (y1 - y2), fl_lo = fl[0] - fl_up;
      for (std::size_t i = 0; i < nch; ++i) {
        const Channel& c = layout.channels[i];
        // The belt scale's noise is correlated over 2 s, the plate's over corr_s.
        const bool slow = c.role == Role::mass_flow;
        ou[i] = (slow ? sc_a : ou_a) * ou[i] + (slow ? sc_b : ou_b) * rnd.next();
        double x = 0.0;
        switch (c.role) {
          case Role::normal: {
            const double share = (&c == up) ? f_up : f_lo;
            const double flc = (&c == up) ? fl_up : fl_lo;
            x = (share + flc) * env * creep + m.corr_fraction * std::abs(share) * env * ou[i];
            break;
          }
          case Role::shear:
            x = (truth.shear + fl[1]) * env * creep + m.corr_fraction * std::abs(truth.shear) * env * ou[i];
            break;
          case Role::belt_speed: x = v_true; break;
          case Role::mass_flow: x = flow_tph * std::min(env, 1.0) * (1.0 + m.scale_noise * ou[i]); break;
        }
        if (first) filt[i] = x;
        filt[i] += lp * (x - filt[i]);
      }
      first = false;
    }
    o << csv_number(static_cast<double>(k) * dt);
    for (std::size_t i = 0; i < nch; ++i) {
      const Channel& c = layout.channels[i];
      const bool plate = c.role == Role::normal || c.role == Role::shear;
      double reading = filt[i];
      if (plate) reading += m.white_N * rnd.next() + m.drift_N * (static_cast<double>(k) * dt) / t_end;
      if (c.role == Role::belt_speed) reading *= 1.0 + m.tacho_noise * rnd.next();
      double raw = reading / gain_true[i] + zero_true[i];
      if (c.resolution > 0.0) raw = std::round(raw / c.resolution) * c.resolution;
      o << ',' << fmt::format("{:.9g}", raw);
    }
    o << '\n';
  }
  return o.str();
}

}  // namespace chutelab::logs
