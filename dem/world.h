#pragma once
// The World owns a DEM scene: particles, walls, materials, contacts (neighbour list with contact
// history), sources and sinks, and advances it in time with velocity Verlet.
//
// Determinism: 1 and N threads give bit-identical results; the force blocks (dem/force_blocks.h) say
// how.
#include <algorithm>
#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include "dem/clump_bodies.h"
#include "dem/contact/contact_model.h"
#include "dem/contact_history.h"
#include "dem/force_blocks.h"
#include "dem/insertion.h"
#include "dem/integrator.h"
#include "dem/material.h"
#include "dem/neighbor_list.h"
#include "dem/particles.h"
#include "dem/timestep.h"
#include "dem/types.h"
#include "dem/wall_forces.h"
#include "dem/wall_loads.h"
#include "dem/walls/wall.h"
#include "dem/walls/wall_contact.h"
#include "dem/walls/wall_contact_list.h"

namespace chutelab::dem {

struct Settings {
  double dt = 0.0;  // s; 0 picks TimeStepEstimate::recommended at the first step
  Vec3 gravity = Vec3(0.0, 0.0, -9.80665);
  NormalLaw normal;  // the normal contact law (dem/contact/normal_laws.h); Hertz-Mindlin by default
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
  void set_body_force(BodyForceHook hook) { hooks_.body_force = std::move(hook); }
  // Calls `fn` for every contact on wall `wall` at the end of every step (dem/walls/wall_contact.h).
  void observe_wall(int wall, WallContactObserver fn);
  // Calls `fn` once per step when that step's wall loads (Wall::force, torque, element_force) are
  // final, after the wall observers. For sampling loads every step inside one step(n) call; the
  // particles have by then moved on (their closing kick, and the next step's drift, run with the
  // forces), so read loads only.
  void observe_wall_loads(std::function<void()> fn) { hooks_.load_observer = std::move(fn); }
  // Removes particles for which pred(index) is true (e.g. by id or region); a clump goes as a whole
  // when any of its spheres is selected.
  void remove_particles_if(const std::function<bool(std::size_t)>& pred);

  // Advances n steps. Throws SimulationError on blow-up or a lost particle.
  void step(std::int64_t n = 1);
  // Validates the scene, picks dt and computes the initial forces; step() calls it when needed.
  void initialise();

  double time() const { return clock_.time; }
  std::int64_t step_count() const { return clock_.step; }
  double dt() const { return clock_.dt; }
  const Settings& settings() const { return settings_; }
  // Results do not depend on the thread count, at any step: it may change between calls to step()
  // (a campaign's last runs take the cores its other workers free).
  int threads() const { return thread_count(); }
  void set_threads(int threads) { settings_.threads = threads; }
  const Particles& particles() const { return p_; }
  // Mutable access; call mark_changed() after editing positions or radii by hand.
  Particles& particles() { return p_; }
  void mark_changed() { contacts_.dirty = true; }
  // Forgets all tangential/rolling contact history (as when a state is imported without it).
  void reset_contact_history() {
    std::fill(contacts_.pairs.shear.begin(), contacts_.pairs.shear.end(), Vec3::Zero());
    std::fill(contacts_.pairs.roll.begin(), contacts_.pairs.roll.end(), Vec3::Zero());
    std::fill(contacts_.pairs.touch.begin(), contacts_.pairs.touch.end(), std::uint8_t{0});
    std::fill(contacts_.walls.shear.begin(), contacts_.walls.shear.end(), Vec3::Zero());
    std::fill(contacts_.walls.roll.begin(), contacts_.walls.roll.end(), Vec3::Zero());
    std::fill(contacts_.walls.touch.begin(), contacts_.walls.touch.end(), std::uint8_t{0});
  }
  const std::vector<Wall>& walls() const { return walls_; }
  Wall& wall(int i) { return walls_.at(static_cast<std::size_t>(i)); }
  const std::vector<Inserter>& inserters() const { return sources_.inserters; }
  const std::vector<Sink>& sinks() const { return sources_.sinks; }
  const std::vector<std::string>& warnings() const { return warnings_; }

  TimeStepEstimate time_step_estimate() const;
  Energy energy() const;
  std::int64_t rebuild_count() const { return contacts_.rebuilds; }
  std::size_t contact_count() const;      // particle-particle contacts touching now
  std::size_t neighbor_pair_count() const { return contacts_.pairs.neighbor.size(); }  // pairs in the Verlet list
  std::size_t wall_contact_count() const;
  double max_speed_limit() const { return max_speed_; }

  // Binary checkpoint of the dynamic state. Restore into a World built with the same scene
  // (materials, walls, inserters, sinks, settings): continuation is bit-identical.
  void save_checkpoint(const std::string& path) const;
  // Particles removed since the last step leave the contact lists stale until the next step rebuilds
  // them; this does that rebuild now (what the next step would do first), so that a checkpoint holds
  // consistent lists. The continuation is unchanged.
  void refresh_lists();
  void load_checkpoint(const std::string& path);

 private:
  // Called on each force block's particles [lo, hi) by the thread that finished their forces.
  using BlockCallback = std::function<void(std::size_t thread, std::size_t lo, std::size_t hi)>;
  // The forces of the current state (dem/forces.cpp); after_block runs on each block as soon as its
  // particles' forces are final (the integrator's closing pass, dem/integrator.h).
  void compute_forces(const BlockCallback& after_block = nullptr);
  template <class Model>
  void compute_forces_impl(const BlockCallback& after_block);
  // Block b's particles once its pair loop is done: the block buffers, wall contacts and weight, the
  // body force, held particles, then after_block.
  void finish_block(std::size_t b, std::size_t thread, const BlockCallback& after_block);
  void index_held();  // sources_.held from p_.held_by
  // The held particles with index in [lo, hi) (sources_.held ascends).
  std::span<const std::int32_t> held_between(std::size_t lo, std::size_t hi) const {
    const auto a = std::lower_bound(sources_.held.begin(), sources_.held.end(), static_cast<std::int32_t>(lo));
    const auto b = std::lower_bound(a, sources_.held.end(), static_cast<std::int32_t>(hi));
    // Pointer and length: the designer's WebAssembly build (its libc++) has no iterator-pair span.
    return {sources_.held.data() + (a - sources_.held.begin()), static_cast<std::size_t>(b - a)};
  }
  // Contact detection (dem/contact_detection.cpp): whether the lists must be rebuilt, and the rebuild.
  bool needs_rebuild() const;
  void rebuild();
  void sort_by_cell(CellGrid& grid, const std::vector<std::int32_t>& order, std::vector<std::int32_t>& map);
  void take_reference(int threads);  // contacts_.reference and the pair gaps from the current state
  void scan_sinks();                 // sources_.sink_scan from the current state (dem/sources_and_sinks.cpp)
  // Sources and sinks (dem/sources_and_sinks.cpp), once per step after the drift.
  void insert_and_delete();
  bool anything_behind_sinks() const;
  void remove_behind_sinks();
  void release_held();
  void insert_from(std::size_t inserter);
  bool try_insert_sphere(std::size_t inserter, double radius, std::vector<std::size_t>& near);
  void check_state() const;
  // The contact law (dem/contact/normal_laws.h): the parameters the interactions give it and the
  // pairs it will meet; its coefficients of every material pair, derived again when the materials
  // change; the energy of its springs.
  void check_contact_law() const;
  void derive_pair_table();
  double elastic_energy() const;
  // The fastest initial, feed or boundary speed, and the speed of a free fall across the domain: what
  // the time step's impact speed and the blow-up check's speed limit are made of.
  double source_speed() const;
  double fall_speed() const;
  [[noreturn]] void report_bad(std::size_t i) const;
  // A Verlet pass over all particles in a parallel region of its own, each thread on the rows of its
  // force blocks; returns the first bad particle (size() if none) and maxd2 raised by the drift.
  std::pair<std::size_t, double> verlet_pass(const VerletPass& pass, double maxd2);
  VerletState verlet_state() { return VerletState::of(p_, contacts_.reference.x, clock_.dt); }
  StateLimits state_limits() const { return {max_speed_, settings_.domain}; }
  void advance_time();  // to the end of the step being taken: clock_.time and the moving walls' poses
  // Clumps (dem/world_clumps.cpp): body half kick + drift + member placement (raises maxd2 to the
  // members' displacement since the last rebuild); gather + half kick + member velocities; removal of
  // whole bodies; insertion of one body by an inserter.
  void clumps_after_drift(double dt, double& maxd2);
  void clumps_after_forces(double dt);
  void remove_whole_clumps(std::vector<char>& gone);
  bool try_insert_clump(Inserter& in, std::vector<std::size_t>& near);
  double wall_displacement_since_rebuild(const Wall& w) const;
  void warn(const std::string& msg);
  void report_wall_contacts() const;  // dem/wall_observers.cpp
  int thread_count() const;

  Settings settings_;
  MaterialTable materials_;
  Particles p_;
  std::vector<Wall> walls_;
  ClumpBodies clumps_;
  std::int64_t next_id_ = 0;        // the next particle's persistent id
  std::int64_t next_clump_id_ = 0;  // the next clump body's

  // The time: the end of the last step taken, the step, their count.
  struct Clock {
    double time = 0.0;
    double dt = 0.0;
    std::int64_t step = 0;
  };
  Clock clock_;

  // Sources and sinks (dem/sources_and_sinks.cpp).
  struct SourcesAndSinks {
    std::vector<Inserter> inserters;
    std::vector<Sink> sinks;
    // Per sink, from the last rebuild: the least (x - point) . normal, one skin in those units, and
    // the particles within that skin.
    struct SinkScan {
      std::vector<double> clearance, reach;
      std::vector<std::vector<std::int32_t>> near;
    } sink_scan;
    // The particles held by a stream inserter (Inserter::hold_to_face), ascending: a few hundred of
    // thousands, which the force and release passes visit without scanning every particle.
    std::vector<std::int32_t> held;
  };
  SourcesAndSinks sources_;

  // The contact law (dem/contact/normal_laws.h): its coefficients per material pair, row-major,
  // derived again when the materials change, and whether the cohesion part runs.
  struct ContactLawTable {
    NormalLaws::PairTables pairs;
    std::uint64_t revision = ~std::uint64_t{0};  // materials_.revision() it was derived at
    bool cohesive = false;                       // some pair has cohesion
  };
  ContactLawTable law_table_;

  // Contact detection (dem/contact_detection.cpp): the pair and wall lists, rebuilt together, and
  // what they were built from (needs_rebuild() measures the displacements since against it).
  struct ContactLists {
    NeighborList pairs;
    WallContactList walls;
    TouchingHistory history;  // scratch of rebuild()
    struct Reference {
      std::vector<Vec3> x;                  // positions at the last rebuild
      std::vector<std::int32_t> index_map;  // index at the last rebuild -> current index (-1 removed)
      std::vector<double> wall_time;        // wall pose times at the last rebuild
      std::vector<std::uint8_t> wall_listed_moving;  // per wall: listed with the whole skin (it moved then)
    } reference;
    double skin = 0.0;
    double max_disp = 0.0;  // largest particle displacement since the rebuild
    std::int64_t rebuilds = 0;
    bool dirty = true;      // rebuild at the next step whatever the displacements
  };
  ContactLists contacts_;

  // The force evaluation (dem/forces.cpp): the blocks and their thread cut, each block's share of
  // the wall loads, each wall's frame.
  ForceBlocks blocks_;
  WallLoads wall_loads_;
  std::vector<WallFrame> wall_frames_;  // per wall, each force evaluation (dem/wall_forces.h)

  // What the scene adds to a step: the body force, and who reads the walls' contacts and loads.
  struct Hooks {
    BodyForceHook body_force;
    std::function<void()> load_observer;
    std::vector<WallContactObserver> wall_observers;  // by wall; empty = none observed
    std::vector<std::uint8_t> wall_observed;          // per wall, each force evaluation: has an observer
  };
  Hooks hooks_;

  double max_speed_ = 0.0;  // m/s, the blow-up check's limit
  bool initialised_ = false;
  std::vector<std::string> warnings_;
};

}  // namespace chutelab::dem
