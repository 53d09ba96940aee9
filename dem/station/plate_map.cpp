#include "dem/station/plate_map.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <map>

#include <fmt/format.h>

#include "core/csv_field.h"
#include "core/input_error.h"

namespace chutelab::dem::station {

namespace {
constexpr double kUmPerHour = 1e6 * 3600.0;  // m/s of depth -> um per hour of operation
constexpr double kStoreDoubles = 4e6;          // ~32 MB of blocks
}  // namespace

double MapCell::archard_rate(const WearInputs& w) const {
  return area > 0.0 ? wear::archard_volume(w.archard, load_slip) / area : 0.0;
}

double MapCell::finnie_rate(const WearInputs& w) const {
  return area > 0.0 ? wear::finnie_volume(w.finnie, finnie_measure) / area : 0.0;
}

namespace {
// sd / sqrt(n) of the block values, NaN with fewer than two.
double batch_se(const std::vector<double>& v) {
  const auto n = static_cast<double>(v.size());
  if (v.size() < 2) return std::numeric_limits<double>::quiet_NaN();
  double m = 0.0, q = 0.0;
  for (double x : v) m += x;
  m /= n;
  for (double x : v) q += (x - m) * (x - m);
  return std::sqrt(q / (n - 1.0) / n);
}
}  // namespace

double MapCell::pressure_se() const {
  if (!(area > 0.0)) return std::numeric_limits<double>::quiet_NaN();
  std::vector<double> p;
  for (double f : block_normal) p.push_back(f / area);
  return batch_se(p);
}

double MapCell::wear_rate_se(const WearInputs& w) const {
  if (!(area > 0.0) || block_load_slip.size() != block_finnie.size()) return std::numeric_limits<double>::quiet_NaN();
  std::vector<double> r;
  for (std::size_t b = 0; b < block_load_slip.size(); ++b)
    r.push_back((wear::archard_volume(w.archard, block_load_slip[b]) + wear::finnie_volume(w.finnie, block_finnie[b])) /
                area);
  return batch_se(r);
}

Vec3 PlateMap::total_force() const {
  Vec3 f = Vec3::Zero();
  for (const auto& c : cells) f += c.force;
  return f;
}

PlateMapRecorder::PlateMapRecorder(const Wall& wall, const wear::FinnieParams& finnie, std::size_t max_samples)
    : name_(wall.name), finnie_(finnie) {
  if (const auto* m = std::get_if<TriangleMesh>(&wall.current)) {
    for (const auto& t : m->triangles)
      corners_.push_back({m->vertices[static_cast<std::size_t>(t[0])], m->vertices[static_cast<std::size_t>(t[1])],
                          m->vertices[static_cast<std::size_t>(t[2])]});
  } else {
    throw InputError("", 0, fmt::format("wall '{}'", wall.name), "a pressure map needs a triangle-mesh wall");
  }
  const double per_sample = static_cast<double>(corners_.size() * kChannels);
  samples_per_block_ = std::max<std::size_t>(
      1, static_cast<std::size_t>(std::ceil(per_sample * static_cast<double>(max_samples) / kStoreDoubles)));
  for (const auto& c : corners_) {
    const Vec3 cr = (c[1] - c[0]).cross(c[2] - c[0]);
    normals_.push_back(cr.norm() > 0.0 ? Vec3(cr.normalized()) : Vec3::UnitX());
  }
  current_.assign(corners_.size() * kChannels, 0.0);
}

void PlateMapRecorder::observe(const WallContact& c) {
  double* a = current_.data() + static_cast<std::size_t>(c.element) * kChannels;
  const Vec3& n = c.normal;
  const double fn = c.force.dot(n);
  const Vec3 ft = c.force - fn * n;
  const double vn = c.velocity.dot(n);  // > 0: the sphere moves towards the wall
  const Vec3 vt = c.velocity - vn * n;
  const double slip = vt.norm();
  a[0] += c.force.x() * c.dt;
  a[1] += c.force.y() * c.dt;
  a[2] += c.force.z() * c.dt;
  a[4] += std::abs(ft.dot(vt)) * c.dt;
  a[5] += std::max(0.0, fn) * slip * c.dt;
  a[8] += n.dot(normals_[static_cast<std::size_t>(c.element)]) * c.dt;
  auto [it, fresh] = last_touch_.try_emplace(c.particle, c.step);
  // A new contact: the particle did not touch this wall in the previous step (several triangles
  // touched in one step are one contact).
  const bool impact = fresh || it->second < c.step - 1;
  it->second = c.step;
  last_step_ = c.step;
  if (impact && vn > 0.0) {
    a[3] += 0.5 * c.mass * vn * vn;
    const double alpha = std::atan2(vn, slip);
    a[6] += wear::finnie_impact_measure(finnie_, c.mass, c.velocity.norm(), alpha);
    a[7] += 1.0;
  }
}

void PlateMapRecorder::end_sample(double t) {
  if (++in_block_ < samples_per_block_) return;
  store_.insert(store_.end(), current_.begin(), current_.end());
  std::fill(current_.begin(), current_.end(), 0.0);
  block_t0_.push_back(block_start_);
  block_t1_.push_back(t);
  block_start_ = t;
  in_block_ = 0;
  // Particles that left the wall more than a step ago can be forgotten.
  for (auto it = last_touch_.begin(); it != last_touch_.end();)
    it = it->second < last_step_ - 1 ? last_touch_.erase(it) : std::next(it);
}

PlateMap PlateMapRecorder::reduce(double start, double end, double block) const {
  PlateMap m;
  m.wall = name_;
  const std::size_t nt = corners_.size();
  std::vector<double> sum(nt * kChannels, 0.0);
  constexpr double eps = 1e-9;
  const std::size_t nb = block > 0.0 ? static_cast<std::size_t>(std::floor((end - start) / block + eps)) : 0;
  std::vector<double> bsum(nb * nt * 3, 0.0), bdur(nb, 0.0);  // per mean block: normal N s, N m, Finnie
  for (std::size_t b = 0; b < block_t1_.size(); ++b) {
    // As the load cell's means (block_mean): a sample belongs to the window by its end time.
    if (block_t1_[b] <= start + eps || block_t1_[b] > end + eps) continue;
    m.duration += block_t1_[b] - block_t0_[b];
    const double* s = store_.data() + b * nt * kChannels;
    for (std::size_t k = 0; k < nt * kChannels; ++k) sum[k] += s[k];
    if (nb == 0) continue;  // no block means asked for (block 0): nothing to divide by
    // Counted back from `end` with the window's own tolerance in seconds, so that a sample the test
    // above puts in the window (ending up to eps after `end`) is in the last block, never at -1.
    const double back = std::floor((end + eps - block_t1_[b]) / block);
    if (back >= static_cast<double>(nb)) continue;
    const auto j = static_cast<std::size_t>(back);
    bdur[j] += block_t1_[b] - block_t0_[b];
    for (std::size_t t = 0; t < nt; ++t) {
      const double* c = s + t * kChannels;
      const Vec3 f(c[0], c[1], c[2]);
      bsum[(j * nt + t) * 3 + 0] += f.dot(normals_[t]);
      bsum[(j * nt + t) * 3 + 1] += c[5];
      bsum[(j * nt + t) * 3 + 2] += c[6];
    }
  }
  const double inv = m.duration > 0.0 ? 1.0 / m.duration : 0.0;
  for (std::size_t t = 0; t < nt; ++t) {
    const double* s = sum.data() + t * kChannels;
    MapCell c;
    c.corners = corners_[t];
    const Vec3 cr = (c.corners[1] - c.corners[0]).cross(c.corners[2] - c.corners[0]);
    c.area = 0.5 * cr.norm();
    c.force = Vec3(s[0], s[1], s[2]) * inv;
    // Oriented the way the particles approach the face (not by the force's sign: a damped contact
    // pulls for a moment as it parts, and a rarely touched triangle may net a pull).
    c.normal = s[8] < 0.0 ? Vec3(-normals_[t]) : normals_[t];
    c.impact_power = s[3] * inv;
    c.sliding_power = s[4] * inv;
    c.load_slip = s[5] * inv;
    c.finnie_measure = s[6] * inv;
    c.impacts = s[7] * inv;
    const double sign = s[8] < 0.0 ? -1.0 : 1.0;
    for (std::size_t j = 0; j < nb; ++j) {
      if (!(bdur[j] > 0.0)) continue;
      c.block_normal.push_back(sign * bsum[(j * nt + t) * 3 + 0] / bdur[j]);
      c.block_load_slip.push_back(bsum[(j * nt + t) * 3 + 1] / bdur[j]);
      c.block_finnie.push_back(bsum[(j * nt + t) * 3 + 2] / bdur[j]);
    }
    m.cells.push_back(c);
  }
  return m;
}

std::vector<std::pair<double, double>> pressure_profile(const PlateMap& m, double bin) {
  if (m.cells.empty()) return {};
  if (!(bin > 0.0)) {
    // The triangles' own height (median): a row of cells is one bin, not split in two.
    std::vector<double> h;
    for (const auto& c : m.cells) {
      const auto [lo, hi] = std::minmax({c.corners[0].y(), c.corners[1].y(), c.corners[2].y()});
      if (hi - lo > 1e-6) h.push_back(hi - lo);
    }
    if (h.empty()) return {};
    std::nth_element(h.begin(), h.begin() + static_cast<long>(h.size() / 2), h.end());
    bin = std::max(1e-3, h[h.size() / 2]);
  }
  double top = -std::numeric_limits<double>::infinity(), bottom = -top;
  for (const auto& c : m.cells)
    for (const auto& p : c.corners) top = std::max(top, p.y()), bottom = std::min(bottom, p.y());
  const auto nb = static_cast<std::size_t>(std::ceil((top - bottom) / bin - 1e-9)) + 1;
  std::vector<double> load(nb, 0.0), area(nb, 0.0);
  // Each triangle's load spread evenly over its height, so bins need not match the mesh's rows.
  for (const auto& c : m.cells) {
    const auto [lo, hi] = std::minmax({c.corners[0].y(), c.corners[1].y(), c.corners[2].y()});
    const double span = hi - lo;
    const double f = c.pressure() * c.area;
    const auto k0 = static_cast<std::size_t>(std::max(0.0, std::floor((top - hi) / bin)));
    for (std::size_t k = k0; k < nb; ++k) {
      const double b_hi = top - static_cast<double>(k) * bin, b_lo = b_hi - bin;
      if (b_hi <= lo) break;
      const double share = span > 0.0 ? (std::min(hi, b_hi) - std::max(lo, b_lo)) / span : (lo <= b_hi && lo > b_lo);
      if (share <= 0.0) continue;
      load[k] += share * f;
      area[k] += share * c.area;
    }
  }
  std::vector<std::pair<double, double>> out;
  for (std::size_t k = 0; k < nb; ++k)
    if (area[k] > 0.0) out.emplace_back(top - (static_cast<double>(k) + 0.5) * bin, load[k] / area[k]);
  return out;
}

double peak_pressure_y(const PlateMap& m, double bin) {
  const auto prof = pressure_profile(m, bin);
  std::size_t best = prof.size();
  for (std::size_t k = 0; k < prof.size(); ++k)
    if (prof[k].second > 0.0 && (best == prof.size() || prof[k].second > prof[best].second)) best = k;
  if (best == prof.size()) return std::numeric_limits<double>::quiet_NaN();
  // The vertex of the parabola through the peak bin and its neighbours: the peak between bin centres.
  if (best > 0 && best + 1 < prof.size()) {
    const double a = prof[best - 1].second, b = prof[best].second, c = prof[best + 1].second;
    const double den = a - 2.0 * b + c;
    const double h = prof[best].first - prof[best + 1].first;
    if (den < 0.0) return prof[best].first + 0.5 * h * (a - c) / den * -1.0;
  }
  return prof[best].first;
}

double pressure_centre_y(const PlateMap& m) {
  double pa = 0.0, pay = 0.0;
  for (const auto& c : m.cells) {
    const double f = c.pressure() * c.area;
    pa += f;
    pay += f * c.centroid().y();
  }
  return pa > 0.0 ? pay / pa : std::numeric_limits<double>::quiet_NaN();
}

void write_plate_map_csv(const std::string& path, const std::vector<PlateMap>& maps, const WearInputs& w,
                         const std::string& condition) {
  std::ofstream f(path);
  if (!f) throw InputError(path, 0, "--out", "cannot write this file");
  f << "condition,wall,triangle,x_mm,y_mm,z_mm,area_mm2,pressure_Pa,shear_stress_Pa,force_x_N,force_y_N,force_z_N,"
       "impact_energy_flux_Wm2,sliding_energy_flux_Wm2,impact_rate_per_s_m2,archard_wear_rate_um_per_h,"
       "finnie_wear_rate_um_per_h,wear_rate_um_per_h,window_s\n";
  for (const auto& m : maps)
    for (std::size_t t = 0; t < m.cells.size(); ++t) {
      const MapCell& c = m.cells[t];
      const Vec3 x = c.centroid();
      const double a = c.area > 0.0 ? c.area : 1.0;
      const double ar = c.archard_rate(w) * kUmPerHour, fr = c.finnie_rate(w) * kUmPerHour;
      // The dataset reader takes a plate_map.csv back (core/csv_field.h): quoted names, exact numbers.
      const auto n = [](double v) { return csv_number(v); };
      f << fmt::format("{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{}\n", csv_field(condition),
                       csv_field(m.wall), t, n(x.x() * 1e3), n(x.y() * 1e3), n(x.z() * 1e3), n(c.area * 1e6),
                       n(c.pressure()), n(c.shear_stress()), n(c.force.x()), n(c.force.y()), n(c.force.z()),
                       n(c.impact_power / a), n(c.sliding_power / a), n(c.impacts / a), n(ar), n(fr), n(ar + fr),
                       n(m.duration));
    }
}

void write_plate_map_vtk(const std::string& path, const std::vector<PlateMap>& maps, const WearInputs& w) {
  std::ofstream f(path);
  if (!f) throw InputError(path, 0, "--out", "cannot write this file");
  std::size_t n = 0;
  for (const auto& m : maps) n += m.cells.size();
  f << "# vtk DataFile Version 3.0\nchutelab plate pressure and wear maps (steady window means)\nASCII\n"
       "DATASET POLYDATA\n";
  f << fmt::format("POINTS {} double\n", 3 * n);
  for (const auto& m : maps)
    for (const auto& c : m.cells)
      for (const auto& p : c.corners) f << fmt::format("{:.6g} {:.6g} {:.6g}\n", p.x(), p.y(), p.z());
  f << fmt::format("POLYGONS {} {}\n", n, 4 * n);
  for (std::size_t k = 0; k < n; ++k) f << fmt::format("3 {} {} {}\n", 3 * k, 3 * k + 1, 3 * k + 2);
  f << fmt::format("CELL_DATA {}\n", n);
  auto field = [&](const char* name, auto fn) {
    f << fmt::format("SCALARS {} double 1\nLOOKUP_TABLE default\n", name);
    for (const auto& m : maps)
      for (const auto& c : m.cells) f << fmt::format("{:.6g}\n", fn(c));
  };
  auto per_area = [](const MapCell& c, double v) { return c.area > 0.0 ? v / c.area : 0.0; };
  field("pressure_Pa", [](const MapCell& c) { return c.pressure(); });
  field("shear_stress_Pa", [](const MapCell& c) { return c.shear_stress(); });
  field("impact_energy_flux_Wm2", [&](const MapCell& c) { return per_area(c, c.impact_power); });
  field("sliding_energy_flux_Wm2", [&](const MapCell& c) { return per_area(c, c.sliding_power); });
  field("archard_wear_rate_um_per_h", [&](const MapCell& c) { return c.archard_rate(w) * kUmPerHour; });
  field("finnie_wear_rate_um_per_h", [&](const MapCell& c) { return c.finnie_rate(w) * kUmPerHour; });
  field("wear_rate_um_per_h", [&](const MapCell& c) { return (c.archard_rate(w) + c.finnie_rate(w)) * kUmPerHour; });
}

}  // namespace chutelab::dem::station
