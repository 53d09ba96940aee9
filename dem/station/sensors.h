#pragma once
// The station's instruments, defined as the LIGGGHTS virtual rig defined them
// (datasets/liggghts-rig/README.md "Quantities") so that the two DEMs are compared like with like:
//  - plate load cell: force and moment on the plate wall every step, averaged over sample intervals;
//    R_n = F . into, R_s = F . down (positive downward), impact point y from the moment about the
//    face point at y = 0 (centre of pressure of R_n);
//  - V_p: mean |v| of all particles with v_x > 0 whose centres lie 10-30 mm in front of the face
//    (this slab lies partly inside the slow layer that builds up on the plate, as the rig's README
//    warns); V_p,fast: the same for the free-stream particles only (v_x > V_b / 2);
//  - V_a: mean speed down the face of particles whose centres are within 1.5 d of the face, with a
//    normal velocity in (-0.5, 0.3) m/s, 30-150 mm (along the face) below the impact point;
//  - stream limits: 95th / 5th percentile (and mean, the "centre") of particle-centre y among
//    free-stream particles (v_x > V_b / 2) in slabs |x - x_q| < 5 mm, per snapshot;
//  - layer on the belt: mean speed along the belt 20-100 mm before the tangent point (does the layer
//    reach the pulley at belt speed?) and the stream thickness, the 95th percentile of the particle
//    tops above the belt at s in [-150, -50] mm;
//  - particles crossing planes, counted by identity between force samples: the mass flux of the
//    free stream through x = Z/2, and the x-momentum balance of the control volume in front of a
//    vertical plate (x > Z/2, above 50 mm below the plate): momentum carried in through its
//    face minus momentum carried out through its floor minus the growth of its content equals the
//    force on the plate in the mean (tests: R_n equals the momentum flux the stream brings).
// Differences from the rig's recipe are listed in README "DEM" (none in the definitions; the DEM's
// slabs for V_a scale with the DEM particle size d, the V_p slab is fixed in mm like the rig's).
#include <cstdint>
#include <vector>

#include "dem/station/scene.h"

namespace chutelab::dem::station {

// Plate load cell, one sample: averages over the sample interval ending at t.
struct ForceSample {
  double t = 0.0;
  double normal = 0.0;   // R_n, N
  double shear = 0.0;    // R_s, N
  double moment = 0.0;   // M_z about the reference point, N m
  // Plane crossings since the previous sample (see Sensors::count_crossings).
  double mass_through = 0.0;      // kg crossing x = Z/2 towards the plate
  double momentum_in = 0.0;       // N s, x-momentum carried into the control volume through its face
  double momentum_floor = 0.0;    // N s, x-momentum carried out through its floor
  double momentum_content = 0.0;  // N s, x-momentum inside the control volume at t
};

// What one particle snapshot shows (NaN / zero counts where nothing was there).
struct SnapshotStats {
  double t = 0.0;
  double vp_sum = 0.0;       // sum of |v| in the V_p slab (v_x > 0)
  int vp_n = 0;
  double vp_fast_sum = 0.0;  // the same for v_x > V_b / 2
  int vp_fast_n = 0;
  double layer_speed_sum = 0.0;
  int layer_n = 0;
  double layer_height_sum = 0.0;  // sum of particle-centre heights above the belt (layer_n particles)
  double stream_thickness = 0.0;  // m, NaN when no particles in the window
  std::vector<double> upper, lower, centre;  // m, per trajectory station (NaN: too few particles)
  std::size_t particles = 0;
};

// A particle near the face, kept until the impact point is known (V_a).
struct FaceParticle {
  float t;        // snapshot time, s
  float up;       // position along the face above the reference point, m
  float v_down;   // velocity down the face, m/s
  float v_into;   // velocity into the plate, m/s
};

// The particles the snapshot sensors read: a live World's, or a snapshot that another DEM code
// wrote (dem/liggghts reads LIGGGHTS dumps), so both are measured by the same code.
struct ParticleView {
  double t = 0.0;  // s
  std::size_t n = 0;
  const Vec3* x = nullptr;             // m
  const Vec3* v = nullptr;             // m/s
  const double* mass = nullptr;        // kg
  const std::int64_t* id = nullptr;    // persistent across snapshots, >= 0
  std::size_t size() const { return n; }
  static ParticleView of(const World& w);
};

// A particle of the side-view picture.
struct SidePoint {
  float x, y, z, speed;
};

class Sensors {
 public:
  Sensors(const Scene& scene, double momentum_plane_fraction);
  const std::vector<double>& stations() const { return xq_; }  // x of the trajectory slabs, m
  double vp_slab_near() const { return 0.010; }
  double vp_slab_far() const { return 0.030; }
  double mass_flux_x() const { return x_flux_; }
  double momentum_plane_x() const { return x_c_; }
  double momentum_floor_y() const { return y_s_; }

  SnapshotStats measure(const ParticleView& p, std::vector<FaceParticle>& face) const;
  SnapshotStats measure(const World& w, std::vector<FaceParticle>& face) const {
    return measure(ParticleView::of(w), face);
  }
  // Adds to `s` what crossed the planes since the previous call (particles matched by id).
  void count_crossings(const ParticleView& p, ForceSample& s);
  void count_crossings(const World& w, ForceSample& s) { count_crossings(ParticleView::of(w), s); }
  // Up to max_points particles of the rig downstream of the feed (deterministic subsample).
  std::vector<SidePoint> side_view(const ParticleView& p, std::size_t max_points) const;
  std::vector<SidePoint> side_view(const World& w, std::size_t max_points) const {
    return side_view(ParticleView::of(w), max_points);
  }

 private:
  const Scene* sc_;
  std::vector<double> xq_;
  double slab_half_ = 0.005;
  double x_flux_ = 0.0, x_c_ = 0.0, y_s_ = 0.0;
  std::vector<float> prev_x_, prev_y_;  // by particle id; NaN = not seen
};

}  // namespace chutelab::dem::station
