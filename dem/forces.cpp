// The force evaluation (World::compute_forces): the wall contacts of each thread's particles, the
// pair loop over its force blocks, then each block's reduction and finishing (dem/force_blocks.h).
// One instantiation per contact model (no virtual call and no branch on the model in the loops);
// compute_forces() picks it at run time.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include <omp.h>

#include "dem/pair_loop.h"
#include "dem/team.h"
#include "dem/wall_forces.h"
#include "dem/world.h"

namespace chutelab::dem {

template <class Model>
void World::compute_forces_impl(const BlockCallback& after_block) {
  const std::size_t n = p_.size();
  const int nt = thread_count();
  const auto& table = std::get<std::vector<typename Model::Coeffs>>(law_table_.pairs);
  const auto nmat = static_cast<std::size_t>(materials_.size());
  // Rounded up: a gap at or below the float limit goes to the full test.
  const double gap_limit = 2.0 * contacts_.max_disp + contacts_.pairs.gap_eps;
  float gap_limit_f = static_cast<float>(gap_limit);
  if (static_cast<double>(gap_limit_f) < gap_limit) gap_limit_f = std::nextafter(gap_limit_f, std::numeric_limits<float>::infinity());
  // Contact laws see a clump sphere's whole body mass (its damping and time scale are those of the
  // body); gravity uses each sphere's share (finish_block). For free spheres the two are the same.
  const pair_loop::PairArrays<typename Model::Coeffs> pairs{p_.x.data(), p_.v.data(), p_.w.data(), p_.radius.data(), p_.contact_mass.data(),
                                    p_.inv_inertia.data(), p_.material.data(), contacts_.pairs.row_begin.data(),
                                    contacts_.pairs.neighbor.data(), contacts_.pairs.slot_row.data(), contacts_.pairs.shear.data(),
                                    contacts_.pairs.roll.data(), contacts_.pairs.touch.data(), table.data(), nmat, clock_.dt, contacts_.pairs.gap.data(), gap_limit_f,
                                    pair_loop::gather_in_law()};
  wall_frames_.resize(walls_.size());
  hooks_.wall_observed.assign(walls_.size(), 0);
  for (std::size_t k = 0; k < walls_.size(); ++k) {
    wall_frames_[k] = WallFrame::of(walls_[k]);
    hooks_.wall_observed[k] = k < hooks_.wall_observers.size() && hooks_.wall_observers[k] ? 1 : 0;
  }
  if (!hooks_.wall_observers.empty()) {
    contacts_.walls.observed_normal.resize(contacts_.walls.size());
    contacts_.walls.observed_velocity.resize(contacts_.walls.size());
  }
  const WallForceArrays<typename Model::Coeffs> wall_arrays{p_.x.data(), p_.v.data(), p_.w.data(), p_.radius.data(), p_.contact_mass.data(),
                                    p_.inv_inertia.data(), p_.material.data(), walls_.data(), wall_frames_.data(),
                                    hooks_.wall_observed.data(), table.data(), nmat, clock_.dt,
                                    &contacts_.walls};
  const std::int32_t* owners = contacts_.walls.owners.data();
  const std::size_t n_owners = contacts_.walls.owners.size();
  const std::size_t nblocks = blocks_.count();
  wall_loads_.prepare(walls_, nblocks, static_cast<std::size_t>(nt));
  // Each thread takes the blocks of its share (dem/force_blocks.h) in every phase: the wall contacts
  // of its particles, its pair blocks, their finishing, and the integrator's passes. So it works on
  // the particles whose state it wrote: with dynamic schedules the wall entries and pair blocks
  // change hands every step and their particles' state crosses between the cores (bench bed,
  // 2 threads: 1.30 s dynamic, 0.84-0.89 s static; bench/log/RESULTS.md), and a serial sum of the wall
  // loads or wall contacts split by count would make a thread read what the other has just written.
  using Clock = std::chrono::steady_clock;
  ThreadCut& cut = blocks_.cut();
  cut.fit(static_cast<std::size_t>(nt), nblocks);
  const bool timed = nt > 1;
  on_team(nt, [&] {
    const auto thread = static_cast<std::size_t>(omp_get_thread_num());
    const auto [b0, b1] = blocks_.thread_blocks();
    const auto [r0, r1] = blocks_.thread_rows(n);
    const Clock::time_point c0 = timed ? Clock::now() : Clock::time_point{};
    WallContactChunks<Model> chunks(wall_arrays);
    for (const std::int32_t* o = std::lower_bound(owners, owners + n_owners, static_cast<std::int32_t>(r0));
         o < owners + n_owners && static_cast<std::size_t>(*o) < r1; ++o)
      particle_wall_forces<Model>(chunks, wall_arrays, static_cast<std::size_t>(*o));
    chunks.finish();
    for (std::size_t b = b0; b < b1; ++b)
      pair_loop::block_pairs<Model>(pairs, blocks_.first_row(b), blocks_.first_row(b + 1), blocks_.forces(b),
                                    blocks_.torques(b));
    const Clock::time_point c1 = timed ? Clock::now() : Clock::time_point{};
#pragma omp barrier
    // After the barrier no thread reads another's particles.
    const Clock::time_point c2 = timed ? Clock::now() : Clock::time_point{};
    for (std::size_t b = b0; b < b1; ++b) finish_block(b, thread, after_block);
    if (timed) cut.busy[thread] += std::chrono::duration<double>(c1 - c0 + (Clock::now() - c2)).count();
  });
  if (timed) cut.step();
  wall_loads_.sum_into(walls_);
}

void World::finish_block(std::size_t b, std::size_t thread, const BlockCallback& after_block) {
  const std::size_t lo = blocks_.first_row(b), hi = blocks_.first_row(b + 1);
  Vec3* f = p_.f.data();
  Vec3* t = p_.t.data();
  // Per particle the sum is, as always, zero, then the block buffers in block order, then its wall
  // contacts and its weight; here it runs buffer by buffer over the particles of a block, as flat
  // loops. The body force and the held particles follow on the same particles while their forces
  // are in cache (each is per particle, so the split does not change a number).
  blocks_.reduce(b, f, t);
  wall_loads_.finish_block(b, thread, lo, hi, contacts_.walls, p_.mass.data(), settings_.gravity, f, t);
  if (hooks_.body_force) hooks_.body_force(p_, clock_.time, lo, hi, p_.f);
  // A held particle (Inserter::hold_to_face) feels nothing: with no force the kicks leave its
  // velocity as set, so the drift moves it rigidly. Its partners still feel it.
  for (const std::int32_t h : held_between(lo, hi)) {
    f[static_cast<std::size_t>(h)] = Vec3::Zero();
    t[static_cast<std::size_t>(h)] = Vec3::Zero();
  }
  if (after_block) after_block(thread, lo, hi);
}



void World::compute_forces(const BlockCallback& after_block) {
  derive_pair_table();
  with_contact_model(settings_.normal, settings_.tangential, settings_.rolling, law_table_.cohesive,
                     [&]<class Model>() { compute_forces_impl<Model>(after_block); });
}

}  // namespace chutelab::dem
