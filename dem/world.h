#pragma once
// The World owns a DEM scene: particles, walls, materials, contacts (neighbour list with contact
// history), sources and sinks, and advances it in time with velocity Verlet.
//
// Determinism: the rows of the pair list are cut into a fixed number of blocks (kForceBlocks, not the
// thread count). Each block scatters its pair forces, row by row, into its own partial-sum buffer; a
// particle's force is then the sum of the block buffers in block order, plus its wall contacts (in
// list order), gravity and the body-force hook. A wall's load (force, torque, element forces) is
// likewise the sum, in block order, of each block's sum over its particles' wall contacts. Which
// thread computes a block changes nothing, so 1 and N threads give bit-identical results.
#include <algorithm>
#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include "dem/clump_bodies.h"
#include "dem/contact/contact_model.h"
#include "dem/insertion.h"
#include "dem/material.h"
#include "dem/particles.h"
#include "dem/timestep.h"
#include "dem/types.h"
#include "dem/walls/wall.h"
#include "dem/walls/wall_contact.h"

namespace chutelab::dem {

struct Settings {
  double dt = 0.0;  // s; 0 picks TimeStepEstimate::recommended at the first step
  Vec3 gravity = Vec3(0.0, 0.0, -9.80665);
  NormalModel normal = NormalModel::hertz_mindlin;
  TangentialModel tangential = TangentialModel::coulomb_history;
  RollingModel rolling = RollingModel::constant_torque;
  double skin = 0.0;        // m, Verlet skin; 0 -> 0.25 of the largest radius
  Box domain;               // required: a particle outside it (and not removed by a sink) stops the run
  double max_speed = 0.0;   // m/s; 0 -> derived from gravity, domain size and boundary speeds
  double characteristic_speed = 0.0;  // m/s for Eq 11; 0 -> derived like max_speed
  int threads = 0;          // OpenMP threads; 0 -> omp_get_max_threads()
  bool sort_particles = true;  // spatially sort particles at every neighbour-list rebuild
  int check_every = 1;      // steps between blow-up/lost-particle checks
  std::function<void(const std::string&)> on_warning;  // default prints "chutelab dem warning: ..." to stderr
};

struct ParticleSpec {
  Vec3 position = Vec3::Zero();
  Vec3 velocity = Vec3::Zero();
  Vec3 omega = Vec3::Zero();
  double radius = 0.0;
  int material = 0;
  double density = 0.0;  // kg/m^3; 0 -> the material's density
};

// A rigid multi-sphere particle (dem/clump.h): a shape registered with World::add_clump_shape, placed
// with its centre of mass at `position` and its principal frame turned by `orientation`.
struct ClumpSpec {
  int shape = 0;
  Vec3 position = Vec3::Zero();
  Quat orientation = Quat::Identity();
  Vec3 velocity = Vec3::Zero();
  Vec3 omega = Vec3::Zero();
  int material = 0;
  double density = 0.0;  // kg/m^3; 0 -> the material's density
};

struct Energy {
  double translational = 0.0;
  double rotational = 0.0;
  double gravitational = 0.0;  // -m g . x
  double elastic = 0.0;        // normal springs (+ tangential springs)
  double total() const { return translational + rotational + gravitational + elastic; }
};

// Thrown when the simulation blows up or loses particles; the message says what, where and why.
class SimulationError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Extra force per particle, called once per step after contacts and gravity (air drag, fields).
// It is called for disjoint ranges [begin, end) that together cover all particles, concurrently
// from the force threads (each on the particles whose forces that thread just finished: a serial
// pass would pull every particle's state to one core each step). It must add to force[begin, end)
// only, depend on nothing but each particle's own state (so any split gives the same numbers), and
// not throw.
using BodyForceHook = std::function<void(const Particles& particles, double time, std::size_t begin,
                                         std::size_t end, std::vector<Vec3>& force)>;

// The pair loop's AVX-512 form screens the slots by their gap at the rebuild (NeighborList::gap);
// other builds test every slot and keep no gaps.
#if defined(__AVX512F__) && defined(__AVX512VL__) && defined(__AVX512BW__)
#define CHUTELAB_DEM_PAIR_GAPS 1
#else
#define CHUTELAB_DEM_PAIR_GAPS 0
#endif

// Pairs within cut-off (half list, j > i, ascending), with per-slot contact history.
struct NeighborList {
  std::vector<std::int32_t> row_begin;  // size N+1
  std::vector<std::int32_t> nbr;
  std::vector<Vec3> shear;
  std::vector<Vec3> roll;
  std::vector<std::uint8_t> touch;
  // Force blocks (derived from row_begin/nbr and the wall entries by layout_blocks): block b owns
  // rows [block_lo[b], block_lo[b+1]) (K + 1 entries, the last N) and a partial-sum buffer covering
  // particles [block_lo[b], block_hi[b]).
  std::vector<std::size_t> block_lo, block_hi, block_off;
  std::size_t blocks() const { return block_hi.size(); }
  std::vector<std::size_t> block_first;  // first block whose buffer reaches into block b
  std::vector<Vec3> block_f, block_t;
  std::vector<std::int32_t> slot_row;  // row (particle i) of each slot, so the pair loop is one flat loop
  // Per slot, a lower bound of the gap between the two surfaces at the reference positions (float,
  // rounded down, less gap_eps): while every particle is within d of its reference position, a slot
  // whose gap exceeds 2 d + gap_eps cannot touch (CHUTELAB_DEM_PAIR_GAPS builds only).
  std::vector<float> gap;
  double gap_eps = 0.0;
  // wall_begin: the wall entries' CSR by particle (WallCandidates::begin, n + 1 entries), for the
  // blocks' work.
  void layout_blocks(std::size_t n, std::size_t blocks, int threads, const std::vector<std::int32_t>& wall_begin);
  void measure_gaps(const Vec3* x_ref, const double* radius, std::size_t n, int threads);
};
inline constexpr std::size_t kForceBlocks = 16;

// Wall elements near each particle (CSR by particle, sorted by wall then element), with history.
struct WallCandidates {
  std::vector<std::int32_t> begin;  // size N+1
  std::vector<std::int32_t> wall, element;
  std::vector<Vec3> shear, roll;
  std::vector<Vec3> out_f, out_t, out_point;
  std::vector<Vec3> out_wall_torque;  // the wall's torque about its load point from each entry
  std::vector<std::uint8_t> touch;
  // For the wall observers, when a wall is observed (else empty): what the contact saw of its
  // particle, taken with the forces, since the particle moves on before the observers run.
  std::vector<Vec3> obs_normal, obs_velocity;
  std::vector<std::int32_t> owners;  // particles with at least one candidate, ascending (derived)
  std::vector<std::int32_t> owner;   // particle of each entry (derived)
  void index_owners() {
    owners.clear();
    owner.resize(wall.size());
    for (std::size_t i = 0; i + 1 < begin.size(); ++i) {
      if (begin[i] != begin[i + 1]) owners.push_back(static_cast<std::int32_t>(i));
      for (auto e = begin[i]; e < begin[i + 1]; ++e) owner[static_cast<std::size_t>(e)] = static_cast<std::int32_t>(i);
    }
  }
};

// The history of the contacts that touch, copied out of the lists at the start of a rebuild (CSR by
// the old particle index); kept between rebuilds only for its storage.
struct TouchingHistory {
  std::vector<std::int32_t> pair_begin, pair_other;
  std::vector<Vec3> pair_shear, pair_roll;
  std::vector<std::int32_t> wall_begin, wall_wall, wall_element;
  std::vector<Vec3> wall_shear, wall_roll;
};

class World {
 public:
  explicit World(Settings settings);

  MaterialTable& materials() { return materials_; }
  const MaterialTable& materials() const { return materials_; }

  // Returns the particle's persistent id. Throws InputError for impossible values.
  std::int64_t add_particle(const ParticleSpec& spec);
  // Clumps: register a shape once, then add bodies; returns the body's persistent id. Its member spheres
  // become particles (ids of their own) that move rigidly with the body.
  int add_clump_shape(const ClumpShape& shape);
  std::int64_t add_clump(const ClumpSpec& spec);
  const ClumpBodies& clumps() const { return clumps_; }
  int add_wall(Wall wall);
  int add_inserter(Inserter inserter);
  int add_sink(Sink sink);
  void set_body_force(BodyForceHook hook) { body_force_ = std::move(hook); }
  // Calls `fn` for every contact on wall `wall` at the end of every step (dem/walls/wall_contact.h).
  void observe_wall(int wall, WallContactObserver fn);
  // Calls `fn` once per step when that step's wall loads (Wall::force, torque, element_force) are
  // final, after the wall observers. For sampling loads every step inside one step(n) call; the
  // particles have by then moved on (their closing kick, and the next step's drift, run with the
  // forces), so read loads only.
  void observe_wall_loads(std::function<void()> fn) { load_observer_ = std::move(fn); }
  // Removes particles for which pred(index) is true (e.g. by id or region); a clump goes as a whole
  // when any of its spheres is selected.
  void remove_particles_if(const std::function<bool(std::size_t)>& pred);

  // Advances n steps. Throws SimulationError on blow-up or a lost particle.
  void step(std::int64_t n = 1);
  // Validates the scene, picks dt and computes the initial forces; step() calls it when needed.
  void initialise();

  double time() const { return time_; }
  std::int64_t step_count() const { return step_; }
  double dt() const { return dt_; }
  const Settings& settings() const { return settings_; }
  // Results do not depend on the thread count, at any step: it may change between calls to step()
  // (a campaign's last runs take the cores its other workers free).
  int threads() const { return thread_count(); }
  void set_threads(int threads) { settings_.threads = threads; }
  const Particles& particles() const { return p_; }
  // Mutable access; call mark_changed() after editing positions or radii by hand.
  Particles& particles() { return p_; }
  void mark_changed() { list_dirty_ = true; }
  // Forgets all tangential/rolling contact history (as when a state is imported without it).
  void reset_contact_history() {
    std::fill(nl_.shear.begin(), nl_.shear.end(), Vec3::Zero());
    std::fill(nl_.roll.begin(), nl_.roll.end(), Vec3::Zero());
    std::fill(nl_.touch.begin(), nl_.touch.end(), std::uint8_t{0});
    std::fill(wc_.shear.begin(), wc_.shear.end(), Vec3::Zero());
    std::fill(wc_.roll.begin(), wc_.roll.end(), Vec3::Zero());
    std::fill(wc_.touch.begin(), wc_.touch.end(), std::uint8_t{0});
  }
  const std::vector<Wall>& walls() const { return walls_; }
  Wall& wall(int i) { return walls_.at(static_cast<std::size_t>(i)); }
  const std::vector<Inserter>& inserters() const { return inserters_; }
  const std::vector<Sink>& sinks() const { return sinks_; }
  const std::vector<std::string>& warnings() const { return warnings_; }

  TimeStepEstimate time_step_estimate() const;
  Energy energy() const;
  std::int64_t rebuild_count() const { return rebuilds_; }
  std::size_t contact_count() const;      // particle-particle contacts touching now
  std::size_t neighbor_pair_count() const { return nl_.nbr.size(); }  // pairs in the Verlet list
  std::size_t wall_contact_count() const;
  double max_speed_limit() const { return max_speed_; }

  // Binary checkpoint of the dynamic state. Restore into a World built with the same scene
  // (materials, walls, inserters, sinks, settings): continuation is bit-identical.
  void save_checkpoint(const std::string& path) const;
  void load_checkpoint(const std::string& path);

 private:
  template <class Model>
  void compute_forces_impl();
  void compute_forces();
  void compute_forces_by_model();
  void index_held();  // held_ from p_.held_by
  // The held particles with index in [lo, hi) (held_ ascends).
  std::span<const std::int32_t> held_between(std::size_t lo, std::size_t hi) const {
    const auto a = std::lower_bound(held_.begin(), held_.end(), static_cast<std::int32_t>(lo));
    const auto b = std::lower_bound(a, held_.end(), static_cast<std::int32_t>(hi));
    return {a, b};
  }
  void rebuild();
  void save_touching_history(int nt);
  bool needs_rebuild() const;
  void insert_and_delete();
  void check_state() const;
  [[noreturn]] void report_bad(std::size_t i) const;
  // The integrator's passes over the particles (dem/world.cpp, step()).
  double kick_and_drift(double maxd2);
  std::size_t closing_pass(bool check, bool and_drift, double& maxd2);
  // closing_pass() on the particles [lo, hi); lowers first_bad, raises maxd2.
  void close_rows(std::size_t lo, std::size_t hi, bool check, bool and_drift, std::size_t& first_bad,
                  double& maxd2);
  // The closing pass run inside compute_forces(), block by block as each block's forces are final
  // (step() sets it when no clump needs the forces first): one parallel region a step fewer, the
  // particles' forces still in cache, and the time of the pass inside the cut's balance (ThreadCut).
  struct FusedClosing {
    bool on = false;
    bool check = false, and_drift = false;
    std::vector<std::size_t> first_bad;  // per thread
    std::vector<double> maxd2;           // per thread
  };
  FusedClosing closing_;
  // Clumps (dem/world_clumps.cpp): body half kick + drift + member placement (raises maxd2 to the
  // members' displacement since the last rebuild); gather + half kick + member velocities; removal of
  // whole bodies; insertion of one body by an inserter.
  void clumps_after_drift(double dt, double& maxd2);
  void clumps_after_forces(double dt);
  void remove_whole_clumps(std::vector<char>& gone);
  bool try_insert_clump(Inserter& in, std::vector<std::size_t>& near);
  void warn(const std::string& msg);
  void report_wall_contacts() const;  // dem/wall_observers.cpp
  int thread_count() const;
  double wall_displacement_since_rebuild(const Wall& w) const;

  Settings settings_;
  MaterialTable materials_;
  Particles p_;
  std::vector<Wall> walls_;
  std::vector<Inserter> inserters_;
  std::vector<Sink> sinks_;
  BodyForceHook body_force_;
  std::function<void()> load_observer_;
  // The force blocks' shares of the wall loads (forces.cpp): per block and wall, force and torque;
  // per block, the elements it touched with their force (found by slot element_base_[wall] + element).
  struct ElementShare {
    std::int32_t wall, element;
    Vec3 f;
  };
  std::vector<Vec3> wall_part_f_, wall_part_t_;
  std::vector<std::vector<ElementShare>> wall_part_e_;
  std::vector<std::int32_t> element_base_;
  std::vector<std::vector<std::int32_t>> element_slot_;  // per thread: slot -> index in its block's list, or -1
  // Which force blocks each thread takes: a contiguous run, [at[t], at[t+1]). Every pass over the
  // particles follows it (compute_forces, kick_and_drift, closing_pass), so a thread reads the state
  // it wrote. The cut starts even and moves by a block when one thread's share took longer over the
  // last kWindow steps (the rows' work differs, and on a VM so does the speed of the cores). Only
  // which thread does the work moves: no number depends on it.
  struct ThreadCut {
    static constexpr int kWindow = 32;
    std::vector<std::size_t> at;  // nt + 1 block indices
    std::vector<double> busy;     // per thread: seconds in its blocks over the window
    int steps = 0;
    void fit(std::size_t nt, std::size_t blocks);  // even, when the thread or block count changed
    std::pair<std::size_t, std::size_t> blocks(std::size_t t, std::size_t nt, std::size_t nblocks) const;
    void step();
  };
  ThreadCut cut_;
  // Inside a parallel region, the particles [first, second) of n that the calling thread takes: the
  // rows of its blocks.
  std::pair<std::size_t, std::size_t> thread_rows(std::size_t n) const;
  struct WallFrame {  // a wall's motion at the current time, for the contacts (compute_forces)
    Vec3 ww, surf_lin, surf_omega, surf_centre, load_point;
    bool still, surface;
  };
  std::vector<WallFrame> wall_frames_;
  std::vector<WallContactObserver> wall_observers_;  // by wall; empty = none observed
  ClumpBodies clumps_;
  std::int64_t next_clump_id_ = 0;
  NeighborList nl_;
  WallCandidates wc_;
  TouchingHistory history_;              // scratch of rebuild()
  std::vector<Vec3> x_ref_;              // positions at the last rebuild
  std::vector<double> wall_time_ref_;    // wall pose times at the last rebuild
  std::vector<std::uint8_t> wall_listed_moving_;  // per wall: listed with the whole skin (it moved then)
  std::vector<double> sink_clearance_;   // per sink: the least (x - point) . normal at the last rebuild
  std::vector<double> sink_reach_;       // per sink: one skin, in units of (x - point) . normal
  std::vector<std::vector<std::int32_t>> sink_near_;  // per sink: particles within sink_reach_ then
  std::vector<std::int32_t> index_map_;  // index at last rebuild -> current index (-1 removed)
  std::vector<std::int32_t> scratch_;
  std::vector<std::vector<std::int32_t>> search_buf_;  // rebuild(): each thread's rows of the pair list
  double time_ = 0.0;
  double dt_ = 0.0;
  double skin_ = 0.0;
  double max_speed_ = 0.0;
  double max_disp_ = 0.0;                // largest particle displacement since the rebuild
  std::int64_t step_ = 0;
  // The particles held by a stream inserter (Inserter::hold_to_face), ascending: a few hundred of
  // thousands, which the force and release passes visit without scanning every particle.
  std::vector<std::int32_t> held_;
  std::int64_t next_id_ = 0;
  std::int64_t rebuilds_ = 0;
  bool initialised_ = false;
  bool list_dirty_ = true;
  std::vector<std::string> warnings_;
};

}  // namespace chutelab::dem
