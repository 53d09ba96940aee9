#include "dem/station/sensors.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace chutelab::dem::station {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Percentile with linear interpolation between order statistics (numpy's default), p in [0, 1].
double percentile(std::vector<double>& v, double p) {
  if (v.empty()) return kNaN;
  std::sort(v.begin(), v.end());
  const double pos = p * static_cast<double>(v.size() - 1);
  const auto i = static_cast<std::size_t>(std::floor(pos));
  const double f = pos - static_cast<double>(i);
  return i + 1 < v.size() ? v[i] + f * (v[i + 1] - v[i]) : v[i];
}

}  // namespace

Sensors::Sensors(const Scene& scene, double momentum_plane_fraction) : sc_(&scene) {
  const PlateFrame& pf = scene.plate;
  const double face_min = std::min(pf.top_edge.x(), pf.bottom_edge().x());
  // Trajectory slabs every 10 mm from the pulley to 20 mm before the face (the rig: x_q <= Z - 20 mm).
  for (double x = 0.01; x <= face_min - 0.02 + 1e-9; x += 0.01) xq_.push_back(std::round(x * 1e3) / 1e3);
  x_flux_ = 0.5 * face_min;
  x_c_ = momentum_plane_fraction * face_min;
  y_s_ = pf.bottom_edge().y() - 0.05;
}

ParticleView ParticleView::of(const World& w) {
  const Particles& p = w.particles();
  return {w.time(), p.size(), p.x.data(), p.v.data(), p.mass.data(), p.id.data()};
}

SnapshotStats Sensors::measure(const ParticleView& p, std::vector<FaceParticle>& face) const {
  const Scene& sc = *sc_;
  const PlateFrame& pf = sc.plate;
  const BeltFrame& bf = sc.belt;
  const double vb = sc.belt_speed;
  const double d = sc.diameter;
  SnapshotStats s;
  s.t = p.t;
  s.particles = p.size();
  const std::size_t nq = xq_.size();
  std::vector<std::vector<double>> bucket(nq);
  std::vector<double> tops;
  const double x0 = xq_.empty() ? 0.0 : xq_.front();
  for (std::size_t i = 0; i < p.size(); ++i) {
    const Vec3& x = p.x[i];
    const Vec3& v = p.v[i];
    const double sb = bf.s(x);
    // Layer on the belt.
    if (sb <= 0.0) {
      const double h = bf.h(x);
      if (sb >= -0.100 && sb <= -0.020 && h > 0.0 && h < 0.2) {
        s.layer_speed_sum += v.dot(bf.along);
        s.layer_height_sum += h;
        ++s.layer_n;
      }
      if (sb >= -0.150 && sb <= -0.050 && h > 0.0 && h < 0.2) tops.push_back(h + 0.5 * d);
      continue;  // upstream of the tangent point: on the belt
    }
    // V_p slab, 10-30 mm in front of the face.
    const double front = pf.in_front(x);
    if (front >= 0.010 && front <= 0.030 && v.x() > 0.0) {
      const double sp = v.norm();
      s.vp_sum += sp;
      ++s.vp_n;
      if (v.x() > 0.5 * vb) {
        s.vp_fast_sum += sp;
        ++s.vp_fast_n;
      }
    }
    // Near the face, for V_a once the impact point is known.
    if (front >= 0.0 && front <= 1.5 * d)
      face.push_back({static_cast<float>(s.t), static_cast<float>(pf.up_from_reference(x)),
                      static_cast<float>(v.dot(pf.down)), static_cast<float>(v.dot(pf.into))});
    // Stream limits.
    if (v.x() > 0.5 * vb && nq > 0) {
      const double k = std::round((x.x() - x0) / 0.01);
      if (k >= 0 && k < static_cast<double>(nq)) {
        const auto ki = static_cast<std::size_t>(k);
        if (std::abs(x.x() - xq_[ki]) < slab_half_) bucket[ki].push_back(x.y());
      }
    }
  }
  s.stream_thickness = tops.size() >= 5 ? percentile(tops, 0.95) : kNaN;
  s.upper.assign(nq, kNaN);
  s.lower.assign(nq, kNaN);
  s.centre.assign(nq, kNaN);
  for (std::size_t k = 0; k < nq; ++k) {
    auto& b = bucket[k];
    if (b.size() < 5) continue;  // a limit needs a stream, not a stray particle
    double sum = 0.0;
    for (double y : b) sum += y;
    s.centre[k] = sum / static_cast<double>(b.size());
    s.lower[k] = percentile(b, 0.05);
    s.upper[k] = percentile(b, 0.95);
  }
  return s;
}

void Sensors::count_crossings(const ParticleView& p, ForceSample& s) {
  for (std::size_t i = 0; i < p.size(); ++i) {
    const auto id = static_cast<std::size_t>(p.id[i]);
    if (id >= prev_x_.size()) {
      prev_x_.resize(std::max(2 * prev_x_.size(), id + 1), std::numeric_limits<float>::quiet_NaN());
      prev_y_.resize(prev_x_.size(), std::numeric_limits<float>::quiet_NaN());
    }
    const double x = p.x[i].x(), y = p.x[i].y();
    const double m = p.mass[i], vx = p.v[i].x();
    const double x0 = prev_x_[id], y0 = prev_y_[id];
    if (std::isfinite(x0)) {
      // Towards the plate only: particles that rebound off the plate and fall back past x_f are
      // part of the stream that arrived, not a reduction of it.
      if (x0 < x_flux_ && x >= x_flux_) s.mass_through += m;
      // The control volume: x >= x_c and y >= y_s.
      const bool was_in = x0 >= x_c_ && y0 >= y_s_, is_in = x >= x_c_ && y >= y_s_;
      if (!was_in && is_in && y0 >= y_s_) s.momentum_in += m * vx;    // in through the face
      if (was_in && !is_in && y >= y_s_) s.momentum_in -= m * vx;     // back out through the face
      if (was_in && !is_in && y < y_s_) s.momentum_floor += m * vx;   // out through the floor
    }
    if (x >= x_c_ && y >= y_s_) s.momentum_content += m * vx;
    prev_x_[id] = static_cast<float>(x);
    prev_y_[id] = static_cast<float>(y);
  }
}

std::vector<SidePoint> Sensors::side_view(const ParticleView& p, std::size_t max_points) const {
  const Scene& sc = *sc_;
  std::vector<std::size_t> pick;
  for (std::size_t i = 0; i < p.size(); ++i)
    if (sc.belt.s(p.x[i]) > -0.25) pick.push_back(i);
  // Deterministic subsample: every k-th by persistent id order.
  std::sort(pick.begin(), pick.end(), [&](std::size_t a, std::size_t b) { return p.id[a] < p.id[b]; });
  const std::size_t stride = pick.size() > max_points ? (pick.size() + max_points - 1) / max_points : 1;
  std::vector<SidePoint> out;
  for (std::size_t k = 0; k < pick.size(); k += stride) {
    const std::size_t i = pick[k];
    out.push_back({static_cast<float>(p.x[i].x()), static_cast<float>(p.x[i].y()), static_cast<float>(p.x[i].z()),
                   static_cast<float>(p.v[i].norm())});
  }
  return out;
}

}  // namespace chutelab::dem::station
