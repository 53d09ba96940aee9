#pragma once
// Velocity Verlet for the spheres: a half kick of the velocities with the last forces, a drift of
// the positions, the new forces, the second half kick. Within one World::step(n) call the second
// half kick of a step and the first half kick and drift of the next use the same forces, so they
// can run as one pass over the particles (one read of the state instead of two): the same
// operations in the same order, so the same numbers. Without clumps that pass runs inside the force
// evaluation, on each force block as soon as its forces are final (BlockClosing, the callback
// World::compute_forces takes).
#include <cstddef>
#include <vector>

#include "dem/particles.h"
#include "dem/types.h"

namespace chutelab::dem {

// The arrays a pass reads and writes, taken once per pass.
struct VerletState {
  Vec3* x;
  Vec3* v;
  Vec3* w;
  const Vec3* f;
  const Vec3* t;
  const double* inv_mass;
  const double* inv_inertia;
  const Vec3* x_ref;  // positions at the last neighbour-list build: displacements are measured from them
  double dt;
  static VerletState of(Particles& p, const std::vector<Vec3>& x_ref, double dt) {
    return {p.x.data(), p.v.data(), p.w.data(), p.f.data(), p.t.data(), p.inv_mass.data(), p.inv_inertia.data(),
            x_ref.data(), dt};
  }
};

// What a pass does to each particle, in this order. close: the second half kick of the step whose
// forces were just computed; check: then the blow-up and lost-particle test (a particle that fails
// it is left after that kick, so the error describes the same state whichever pass found it);
// open: the next step's first half kick and its drift.
struct VerletPass {
  bool close = false;
  bool check = false;
  bool open = false;
};

// A state no particle may reach: faster than max_speed, or outside the domain.
struct StateLimits {
  double max_speed = 0.0;
  Box domain;
};

// One pass over the particles [lo, hi). Lowers first_bad to the lowest index that fails the check
// (min is exact, so the particle reported does not depend on the thread count) and raises maxd2 to
// the largest squared displacement from x_ref after an opening drift.
void verlet_rows(const VerletState& s, const VerletPass& pass, const StateLimits& limits, std::size_t lo,
                 std::size_t hi, std::size_t& first_bad, double& maxd2);

// The closing pass as the force evaluation's per-block callback: each thread closes the particles of
// its blocks as soon as their forces are final, while they are in its cache.
class BlockClosing {
 public:
  BlockClosing(const VerletState& s, const VerletPass& pass, const StateLimits& limits, std::size_t threads,
               std::size_t particles)
      : s_(s), pass_(pass), limits_(limits), first_bad_(threads, particles), maxd2_(threads, 0.0) {}
  void operator()(std::size_t thread, std::size_t lo, std::size_t hi) {
    verlet_rows(s_, pass_, limits_, lo, hi, first_bad_[thread], maxd2_[thread]);
  }
  std::size_t first_bad() const;  // over all threads; the particle count if none
  double maxd2() const;

 private:
  VerletState s_;
  VerletPass pass_;
  StateLimits limits_;
  std::vector<std::size_t> first_bad_;  // per thread
  std::vector<double> maxd2_;           // per thread
};

}  // namespace chutelab::dem
