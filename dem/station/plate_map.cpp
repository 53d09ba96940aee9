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

MapGrid MapGrid::on_face(const Vec3& top_edge, const Vec3& down, double height, double width, double cell) {
  MapGrid g;
  g.origin = top_edge - 0.5 * width * Vec3::UnitZ();
  g.down = down;
  g.across = Vec3::UnitZ();
  g.height = height;
  g.width = width;
  // Whole cells across the face, as near `cell` as the face allows; capped so that a very large face
  // keeps a map of bounded size (its cells then grow).
  g.rows = std::clamp(static_cast<int>(std::lround(height / cell)), 1, 400);
  g.cols = std::clamp(static_cast<int>(std::lround(width / cell)), 1, 400);
  return g;
}

std::vector<std::array<Vec3, 3>> MapGrid::triangles() const {
  auto at = [&](int r, int c) { return Vec3(origin + (height * r / rows) * down + (width * c / cols) * across); };
  std::vector<std::array<Vec3, 3>> t;
  // The triangles a mesh of these cells would have (dem/station/scene.cpp's plate_cells), so that
  // a grid map and a meshed plate's map read alike.
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < cols; ++c) {
      t.push_back({at(r, c), at(r + 1, c), at(r + 1, c + 1)});
      t.push_back({at(r, c), at(r + 1, c + 1), at(r, c + 1)});
    }
  return t;
}

MapCell empty_cell(const std::array<Vec3, 3>& corners, bool flip, std::size_t blocks) {
  MapCell c;
  c.corners = corners;
  const Vec3 cr = (corners[1] - corners[0]).cross(corners[2] - corners[0]);
  c.area = 0.5 * cr.norm();
  const Vec3 n = cr.norm() > 0.0 ? Vec3(cr.normalized()) : Vec3::UnitX();
  c.normal = flip ? Vec3(-n) : n;
  c.block_normal.assign(blocks, 0.0);
  c.block_load_slip.assign(blocks, 0.0);
  c.block_finnie.assign(blocks, 0.0);
  return c;
}

PlateMapRecorder::PlateMapRecorder(const Wall& wall, const wear::FinnieParams& finnie, std::size_t max_samples,
                                   const MapGrid* grid)
    : name_(wall.name), finnie_(finnie) {
  if (!std::holds_alternative<TriangleMesh>(wall.current))
    throw InputError("", 0, fmt::format("wall '{}'", wall.name), "a pressure map needs a triangle-mesh wall");
  if (grid) {
    grid_ = *grid;
    corners_ = grid->triangles();
    triangles_per_bin_ = 2;
  } else {
    const auto& m = std::get<TriangleMesh>(wall.current);
    for (const auto& t : m.triangles)
      corners_.push_back({m.vertices[static_cast<std::size_t>(t[0])], m.vertices[static_cast<std::size_t>(t[1])],
                          m.vertices[static_cast<std::size_t>(t[2])]});
  }
  bins_ = corners_.size() / triangles_per_bin_;
  (void)max_samples;  // the store grows with what is touched (end_sample), not with the run's length
  for (const auto& c : corners_) {
    const Vec3 cr = (c[1] - c[0]).cross(c[2] - c[0]);
    normals_.push_back(cr.norm() > 0.0 ? Vec3(cr.normalized()) : Vec3::UnitX());
  }
  current_.assign(bins_ * kChannels, 0.0);
  touched_flag_.assign(bins_, 0);
  block_begin_.push_back(0);
}

std::size_t PlateMapRecorder::bin_of(const WallContact& c) const {
  if (!grid_) return static_cast<std::size_t>(c.element);
  const MapGrid& g = *grid_;
  const Vec3 d = c.point - g.origin;
  // A contact on the face's rim (a sphere over its edge) counts in the nearest cell.
  const int r = std::clamp(static_cast<int>(std::floor(d.dot(g.down) / g.height * g.rows)), 0, g.rows - 1);
  const int k = std::clamp(static_cast<int>(std::floor(d.dot(g.across) / g.width * g.cols)), 0, g.cols - 1);
  return static_cast<std::size_t>(r) * static_cast<std::size_t>(g.cols) + static_cast<std::size_t>(k);
}

void PlateMapRecorder::observe(const WallContact& c) {
  const std::size_t bin = bin_of(c);
  if (!touched_flag_[bin]) {
    touched_flag_[bin] = 1;
    touched_.push_back(static_cast<std::uint32_t>(bin));
  }
  double* a = current_.data() + bin * kChannels;
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
  a[8] += n.dot(normals_[bin * triangles_per_bin_]) * c.dt;
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
  // The block's touched cells only (a stream loads a band of the plate: most cells of a fine map are
  // empty in any one sample), in cell order.
  std::sort(touched_.begin(), touched_.end());
  for (std::uint32_t bin : touched_) {
    double* a = current_.data() + static_cast<std::size_t>(bin) * kChannels;
    store_bins_.push_back(bin);
    store_.insert(store_.end(), a, a + kChannels);
    std::fill(a, a + kChannels, 0.0);
    touched_flag_[bin] = 0;
  }
  touched_.clear();
  block_begin_.push_back(store_bins_.size());
  block_t0_.push_back(block_start_);
  block_t1_.push_back(t);
  block_start_ = t;
  in_block_ = 0;
  // Particles that left the wall more than a step ago can be forgotten.
  for (auto it = last_touch_.begin(); it != last_touch_.end();)
    it = it->second < last_step_ - 1 ? last_touch_.erase(it) : std::next(it);
  if (static_cast<double>(store_.size()) > kStoreDoubles) merge_blocks();
}

// Past the store's budget: neighbouring blocks merged in pairs and later blocks twice as long. A
// window edge inside a merged block then drops it (the map averages over a few ms less than the
// load cell); below the budget every block is one force sample and the map's window is the load
// cell's.
void PlateMapRecorder::merge_blocks() {
  std::vector<std::uint32_t> bins;
  std::vector<double> values, t0, t1;
  std::vector<std::size_t> begin = {0};
  std::vector<double> dense(bins_ * kChannels, 0.0);
  std::vector<std::uint32_t> used;
  std::vector<std::uint8_t> flag(bins_, 0);
  const std::size_t blocks = block_t1_.size();
  for (std::size_t b = 0; b < blocks; b += 2) {
    const std::size_t last = std::min(b + 1, blocks - 1);
    for (std::size_t k = block_begin_[b]; k < block_begin_[last + 1]; ++k) {
      double* a = dense.data() + static_cast<std::size_t>(store_bins_[k]) * kChannels;
      if (!flag[store_bins_[k]]) {
        flag[store_bins_[k]] = 1;
        used.push_back(store_bins_[k]);
      }
      for (std::size_t c = 0; c < kChannels; ++c) a[c] += store_[k * kChannels + c];
    }
    std::sort(used.begin(), used.end());
    for (std::uint32_t bin : used) {
      double* a = dense.data() + static_cast<std::size_t>(bin) * kChannels;
      bins.push_back(bin);
      values.insert(values.end(), a, a + kChannels);
      std::fill(a, a + kChannels, 0.0);
      flag[bin] = 0;
    }
    used.clear();
    begin.push_back(bins.size());
    t0.push_back(block_t0_[b]);
    t1.push_back(block_t1_[last]);
  }
  store_bins_ = std::move(bins);
  store_ = std::move(values);
  block_begin_ = std::move(begin);
  block_t0_ = std::move(t0);
  block_t1_ = std::move(t1);
  samples_per_block_ *= 2;
}

PlateMap PlateMapRecorder::reduce(double start, double end, double block) const {
  PlateMap m;
  m.wall = name_;
  m.grid = grid_;
  const std::size_t nt = bins_;
  std::vector<double> sum(nt * kChannels, 0.0);
  constexpr double eps = 1e-9;
  const std::size_t nb = block > 0.0 ? static_cast<std::size_t>(std::floor((end - start) / block + eps)) : 0;
  std::vector<double> bsum(nb * nt * 3, 0.0), bdur(nb, 0.0);  // per mean block: normal N s, N m, Finnie
  for (std::size_t b = 0; b < block_t1_.size(); ++b) {
    // As the load cell's means (block_mean): a sample belongs to the window by its end time.
    if (block_t1_[b] <= start + eps || block_t1_[b] > end + eps) continue;
    m.duration += block_t1_[b] - block_t0_[b];
    for (std::size_t e = block_begin_[b]; e < block_begin_[b + 1]; ++e) {
      const double* v = store_.data() + e * kChannels;
      double* to = sum.data() + static_cast<std::size_t>(store_bins_[e]) * kChannels;
      for (std::size_t k = 0; k < kChannels; ++k) to[k] += v[k];
    }
    if (nb == 0) continue;  // no block means asked for (block 0): nothing to divide by
    // Counted back from `end` with the window's own tolerance in seconds, so that a sample the test
    // above puts in the window (ending up to eps after `end`) is in the last block, never at -1.
    const double back = std::floor((end + eps - block_t1_[b]) / block);
    if (back >= static_cast<double>(nb)) continue;
    const auto j = static_cast<std::size_t>(back);
    bdur[j] += block_t1_[b] - block_t0_[b];
    for (std::size_t e = block_begin_[b]; e < block_begin_[b + 1]; ++e) {
      const double* c = store_.data() + e * kChannels;
      const std::size_t t = store_bins_[e];
      const Vec3 f(c[0], c[1], c[2]);
      bsum[(j * nt + t) * 3 + 0] += f.dot(normals_[t * triangles_per_bin_]);
      bsum[(j * nt + t) * 3 + 1] += c[5];
      bsum[(j * nt + t) * 3 + 2] += c[6];
    }
  }
  const double inv = m.duration > 0.0 ? 1.0 / m.duration : 0.0;
  const double share = 1.0 / static_cast<double>(triangles_per_bin_);
  for (std::size_t t = 0; t < nt * triangles_per_bin_; ++t) {
    const std::size_t bin = t / triangles_per_bin_;
    const double* s = sum.data() + bin * kChannels;
    const double w = inv * share;
    MapCell c;
    c.corners = corners_[t];
    const Vec3 cr = (c.corners[1] - c.corners[0]).cross(c.corners[2] - c.corners[0]);
    c.area = 0.5 * cr.norm();
    c.force = Vec3(s[0], s[1], s[2]) * w;
    // Oriented the way the particles approach the face (not by the force's sign: a damped contact
    // pulls for a moment as it parts, and a rarely touched triangle may net a pull).
    c.normal = s[8] < 0.0 ? Vec3(-normals_[t]) : normals_[t];
    c.impact_power = s[3] * w;
    c.sliding_power = s[4] * w;
    c.load_slip = s[5] * w;
    c.finnie_measure = s[6] * w;
    c.impacts = s[7] * w;
    const double sign = s[8] < 0.0 ? -1.0 : 1.0;
    for (std::size_t j = 0; j < nb; ++j) {
      if (!(bdur[j] > 0.0)) continue;
      c.block_normal.push_back(sign * share * bsum[(j * nt + bin) * 3 + 0] / bdur[j]);
      c.block_load_slip.push_back(share * bsum[(j * nt + bin) * 3 + 1] / bdur[j]);
      c.block_finnie.push_back(share * bsum[(j * nt + bin) * 3 + 2] / bdur[j]);
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
  if (!f) throw InputError(path, 0, "out", "cannot write this file");
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
  if (!f) throw InputError(path, 0, "out", "cannot write this file");
  std::size_t n = 0;
  for (const auto& m : maps) n += m.cells.size();
  f << "# vtk DataFile Version 3.0\nchutelab plate pressure and wear maps (steady window means); lengths in mm\n"
       "ASCII\nDATASET POLYDATA\n";
  f << fmt::format("POINTS {} double\n", 3 * n);
  for (const auto& m : maps)
    for (const auto& c : m.cells)
      for (const auto& p : c.corners) f << fmt::format("{:.6g} {:.6g} {:.6g}\n", p.x() * 1e3, p.y() * 1e3, p.z() * 1e3);
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
