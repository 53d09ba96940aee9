// Run-time machinery: time-step estimates (Rayleigh, Hertz Eq 11) and the unsafe-dt warning, blow-up
// and lost-particle stops, insertion at a mass flow and deletion at a sink, body-force hook,
// checkpoint/restart (bit-identical continuation), VTK and CSV output, bad input.
#define BOOST_TEST_MODULE dem_runtime
#include <boost/test/unit_test.hpp>

#include <atomic>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>
#include <unistd.h>

#include <omp.h>

#include "core/input_error.h"
#include "dem/io/csv.h"
#include "dem/io/vtk.h"
#include "dem/team.h"
#include "dem/world.h"
#include "helpers.h"

using namespace chutelab::dem;
using namespace chutelab::dem::test;
namespace fs = std::filesystem;

namespace {

// Per process: sessions sharing the machine run the suite at the same time.
std::string tmp(const std::string& name) {
  return (fs::temp_directory_path() / ("chutelab_dem_" + std::to_string(::getpid()) + "_" + name)).string();
}

// The reference study's §3 material (polyethylene pellets, LIGGGHTS rig modulus) in a small open box.
World pellet_box(Settings s, int n = 0) {
  s.gravity = Vec3(0, 0, -9.81);
  if (s.domain.empty()) s.domain = Box{Vec3(-0.1, -0.1, -0.1), Vec3(0.2, 0.2, 0.5)};
  if (!s.on_warning) s.on_warning = [](const std::string&) {};
  World w(s);
  const int pe = w.materials().add({"pellet", 2.5e7, 0.38, 1000});
  const int steel = w.materials().add({"steel", 2e11, 0.3, 7800});
  Interaction pp, pw;
  pp.friction = 0.3;
  pp.rolling_friction = 0.1;
  pp.restitution = 0.7;
  pw.friction = 0.27;
  pw.rolling_friction = 0.1;
  pw.restitution = 0.66;
  w.materials().set_interaction(pe, pe, pp);
  w.materials().set_interaction(pe, steel, pw);
  w.add_wall(Wall::plane("floor", Vec3(0, 0, 0), Vec3::UnitZ(), steel));
  w.add_wall(Wall::plane("x0", Vec3(0, 0, 0), Vec3::UnitX(), steel));
  w.add_wall(Wall::plane("x1", Vec3(0.1, 0, 0), -Vec3::UnitX(), steel));
  w.add_wall(Wall::plane("y0", Vec3(0, 0, 0), Vec3::UnitY(), steel));
  w.add_wall(Wall::plane("y1", Vec3(0, 0.1, 0), -Vec3::UnitY(), steel));
  std::uint64_t seed = 99;
  for (int k = 0; k < n; ++k) {
    const Vec3 x(0.008 + 0.0105 * (k % 9), 0.008 + 0.0105 * ((k / 9) % 9), 0.006 + 0.0105 * (k / 81));
    w.add_particle({x, Vec3(uniform01(seed) - 0.5, uniform01(seed) - 0.5, -1.0), Vec3::Zero(), 4.5e-3, pe});
  }
  return w;
}

}  // namespace

// Rayleigh time and reference study Eq 11 against hand-computed values for the 9 mm pellets of the reference study's
// LIGGGHTS rig (E = 2.5e7 Pa, nu = 0.38, rho = 1000, 1 m/s); the default dt is 1/10 of the collision
// time or 0.2 of the Rayleigh time, whichever is smaller. Exact formulas: 1e-12 relative.
BOOST_AUTO_TEST_CASE(time_step_estimates) {
  const double R = 4.5e-3, E = 2.5e7, nu = 0.38, rho = 1000, G = E / (2 * (1 + nu));
  const double tr = pi * R * std::sqrt(rho / G) / (0.1631 * nu + 0.8766);
  BOOST_TEST(std::abs(rayleigh_time(R, rho, G, nu) / tr - 1) < 1e-12);
  const double m = sphere_mass(R, rho), es = E / (2 * (1 - nu * nu));
  const double tc = 2.87 * std::pow((m / 2) * (m / 2) / (R / 2 * es * es * 1.0), 0.2);
  BOOST_TEST(std::abs(hertz_collision_time(m / 2, R / 2, es, 1.0) / tc - 1) < 1e-12);
  BOOST_TEST(tc > 4e-4);  // ~0.43 ms: the reference study's dt = 3e-5 s is ~1/14 of it
  Settings s;
  s.characteristic_speed = 1.0;
  World w = pellet_box(s, 10);
  const TimeStepEstimate est = w.time_step_estimate();
  BOOST_TEST(std::abs(est.rayleigh / tr - 1) < 1e-12);
  BOOST_TEST(est.collision <= tc);  // the pellet-steel contact is shorter than pellet-pellet
  w.initialise();
  BOOST_TEST(w.dt() == std::min(0.1 * est.collision, 0.2 * est.rayleigh));
  BOOST_TEST(w.warnings().empty());
}

// An unsafe dt is accepted but warned about, naming the recommended value.
BOOST_AUTO_TEST_CASE(unsafe_time_step_warns) {
  std::vector<std::string> seen;
  Settings s;
  s.dt = 3e-4;  // ~0.7 of the collision time
  s.on_warning = [&](const std::string& m) { seen.push_back(m); };
  World w = pellet_box(s, 10);
  w.initialise();
  BOOST_TEST_REQUIRE(seen.size() == 1u);
  BOOST_TEST(seen[0].find("unsafe") != std::string::npos);
  BOOST_TEST(seen[0].find("recommended dt") != std::string::npos);
}

// A blow-up stops with a clear message instead of producing garbage: a bed run at 20x the safe step
// gains energy until a particle exceeds the physically possible speed (or goes non-finite).
BOOST_AUTO_TEST_CASE(blow_up_is_detected) {
  Settings s;
  s.dt = 2e-3;
  World w = pellet_box(s, 400);
  try {
    w.step(20000);
    BOOST_ERROR("no blow-up detected");
  } catch (const SimulationError& e) {
    const std::string what = e.what();
    BOOST_TEST_MESSAGE(what);
    BOOST_TEST(what.find("DEM stopped at step") != std::string::npos);
    BOOST_TEST((what.find("faster than physically possible") != std::string::npos ||
                what.find("non-finite") != std::string::npos || what.find("left the domain") != std::string::npos));
    BOOST_TEST(what.find("recommended dt") != std::string::npos);
  }
}

// A particle that leaves the domain (no floor under it, no sink) is reported as lost.
BOOST_AUTO_TEST_CASE(lost_particle_is_reported) {
  Settings s = quiet_settings(1e-4, 0.5);
  s.gravity = Vec3(0, 0, -9.81);
  World w(s);
  const int m = w.materials().add({"m", 1e7, 0.3, 1000});
  w.add_particle({Vec3::Zero(), Vec3::Zero(), Vec3::Zero(), 0.01, m});
  BOOST_CHECK_EXCEPTION(w.step(10000), SimulationError, [](const SimulationError& e) {
    return std::string(e.what()).find("left the domain") != std::string::npos;
  });
  BOOST_TEST(w.time() > 0.3);  // free fall of 0.5 m takes 0.32 s: stopped when it crossed, not before
}

// Insertion at a mass flow and deletion at a sink: 0.5 kg/s for 0.2 s into a chute with no floor;
// inserted mass matches the flow within one particle mass, and every inserted particle is either
// present or counted by the sink.
BOOST_AUTO_TEST_CASE(insertion_at_mass_flow_and_sink_deletion) {
  Settings s = quiet_settings(2e-5, 2.0);
  s.gravity = Vec3(0, 0, -9.81);
  World w(s);
  const int pe = w.materials().add({"pellet", 2.5e7, 0.38, 1000});
  Interaction in;
  in.friction = 0.3;
  in.restitution = 0.7;
  w.materials().set_interaction(pe, pe, in);
  Inserter ins;
  ins.region = Box{Vec3(0, 0, 0.3), Vec3(0.1, 0.1, 0.4)};
  ins.mass_rate = 0.5;
  ins.radius_min = 4e-3;
  ins.radius_max = 5e-3;
  ins.material = pe;
  ins.velocity = Vec3(0, 0, -1);
  ins.end_time = 0.2;
  ins.interval = 0.01;
  w.add_inserter(ins);
  Sink sink;
  sink.point = Vec3(0, 0, 0);
  sink.normal = Vec3::UnitZ();
  w.add_sink(sink);
  w.initialise();
  // The sink takes a particle in the step its centre crosses (its scan looks only at the particles
  // listed near it at the last rebuild, or skips when none can have crossed): none is ever behind it.
  std::size_t behind = 0;
  for (auto k = std::llround(0.45 / w.dt()); k > 0; --k) {
    w.step(1);
    for (const auto& x : w.particles().x) behind += x.z() < 0.0 ? 1 : 0;
  }
  BOOST_TEST(behind == 0u);
  const Inserter& I = w.inserters()[0];
  const double m_max = sphere_mass(5e-3, 1000);
  BOOST_TEST_MESSAGE("inserted " << I.inserted_mass << " kg, removed " << w.sinks()[0].removed_mass << " kg, "
                                 << w.particles().size() << " present");
  BOOST_TEST(std::abs(I.inserted_mass - 0.5 * 0.2) < m_max);
  double present = 0;
  for (double m : w.particles().mass) present += m;
  BOOST_TEST(std::abs(present + w.sinks()[0].removed_mass - I.inserted_mass) < 1e-12);
  BOOST_TEST(w.sinks()[0].removed_count > 100);  // the 0.3 m drop takes 0.25 s: most have left
  for (const auto& x : w.particles().x) BOOST_TEST(x.z() >= 0.0);
}

// Stream insertion through a face (Inserter::hold_to_face, LIGGGHTS' insert/stream): sparse spheres
// are moved rigidly at the velocity's normal part, (0, 0, -1) m/s, exactly and without spin while
// their centre is above the face z = 0.3 m, and are released there with the full velocity (2, 0,
// -1) m/s. Below the face each is a free projectile: v_x stays 2 m/s and v_z^2 = 1 + 2 g (0.3 - z)
// within what one step's release position and the Verlet error allow.
BOOST_AUTO_TEST_CASE(stream_insertion_holds_then_releases_at_the_face) {
  Settings s = quiet_settings(2e-5, 2.0);
  s.gravity = Vec3(0, 0, -9.81);
  World w(s);
  const int pe = w.materials().add({"pellet", 2.5e7, 0.38, 1000});
  Inserter ins;
  ins.region = Box{Vec3(0, 0, 0.3), Vec3(0.5, 0.5, 0.4)};
  ins.mass_rate = 0.05;  // ~130 spheres/s in 0.25 m^2: they never touch
  ins.radius_min = ins.radius_max = 4e-3;
  ins.material = pe;
  ins.velocity = Vec3(2, 0, -1);
  ins.hold_to_face = true;
  ins.hold_axis = 2;
  ins.interval = 0.092;  // (box height - d) / 1 m/s
  w.add_inserter(ins);
  w.initialise();
  const double g = 9.81;
  int held = 0, free = 0;
  for (int k = 0; k < 20; ++k) {
    w.step(1000);
    const Particles& p = w.particles();
    for (std::size_t i = 0; i < p.size(); ++i) {
      if (p.x[i].z() > 0.3) {
        ++held;
        BOOST_TEST((p.v[i] == Vec3(0, 0, -1)));
        BOOST_TEST(p.w[i].isZero(0.0));
      } else {
        ++free;
        BOOST_TEST(std::abs(p.v[i].x() - 2.0) < 1e-12);
        BOOST_TEST(p.v[i].y() == 0.0);
        const double expect = 1.0 + 2.0 * g * (0.3 - p.x[i].z());
        BOOST_TEST(std::abs(p.v[i].z() * p.v[i].z() - expect) < 2.0 * g * 1.0 * 2e-5 + 1e-9);
      }
    }
  }
  BOOST_TEST(held > 100);
  BOOST_TEST(free > 100);
  // A velocity along the face is refused: nothing would ever cross it.
  Inserter bad = ins;
  bad.velocity = Vec3(2, 0, 0);
  BOOST_CHECK_THROW(w.add_inserter(bad), chutelab::InputError);
}

// A held sphere pushes what it meets but is not pushed: moving down at 1 m/s onto a free sphere at
// rest (no gravity), it keeps (0, 0, -1) m/s exactly through the contact, while the free sphere is
// driven ahead of it, faster than the held one (a collision with a body that does not give way).
BOOST_AUTO_TEST_CASE(held_sphere_pushes_and_is_not_pushed) {
  Settings s = quiet_settings(2e-5, 2.0);
  s.gravity = Vec3::Zero();
  World w(s);
  const int pe = w.materials().add({"pellet", 2.5e7, 0.38, 1000});
  Interaction it;
  it.restitution = 0.7;
  w.materials().set_interaction(pe, pe, it);
  const double r = 4e-3;
  w.add_particle({Vec3(0.05, 0.05, 0.31), Vec3::Zero(), Vec3::Zero(), r, pe});
  Inserter ins;
  ins.region = Box{Vec3(0.05 - 1.02 * r, 0.05 - 1.02 * r, 0.3), Vec3(0.05 + 1.02 * r, 0.05 + 1.02 * r, 0.4)};
  const double m = 1000.0 * 4.0 / 3.0 * std::numbers::pi * r * r * r;
  ins.mass_rate = m / 0.01;
  ins.end_time = 0.01 - 1e-9;  // owes one sphere's mass in all
  ins.interval = 1.0;
  ins.radius_min = ins.radius_max = r;
  ins.material = pe;
  ins.velocity = Vec3(0, 0, -1);
  ins.hold_to_face = true;
  ins.hold_axis = 2;
  w.add_inserter(ins);
  w.initialise();
  bool touched = false;
  for (int k = 0; k < 5000 && w.particles().size() < 2; ++k) w.step(1);
  BOOST_TEST_REQUIRE(w.particles().size() == 2u);
  for (int k = 0; k < 5000; ++k) {
    w.step(1);
    const Particles& p = w.particles();
    const std::size_t h = p.id[0] == 1 ? 0 : 1;  // the inserted sphere has id 1
    if (p.x[h].z() <= 0.3) break;                 // released
    BOOST_TEST_REQUIRE((p.v[h] == Vec3(0, 0, -1)));
    if ((p.x[0] - p.x[1]).norm() < 2.0 * r) touched = true;
  }
  BOOST_TEST(touched);
  const Particles& p = w.particles();
  const std::size_t f = p.id[0] == 0 ? 0 : 1;
  BOOST_TEST_MESSAGE("free sphere after the push: v_z = " << p.v[f].z() << " m/s");
  BOOST_TEST(p.v[f].z() < -1.2);
}

// Body-force hook: a drag force -c v added per particle (what the air-drag effect will do) gives the
// terminal speed m g / c of a falling sphere within 0.1 %.
BOOST_AUTO_TEST_CASE(body_force_hook_gives_terminal_speed) {
  Settings s = quiet_settings(1e-4, 10.0);
  s.gravity = Vec3(0, 0, -9.81);
  World w(s);
  const int m = w.materials().add({"m", 1e7, 0.3, 1000});
  w.add_particle({Vec3(0, 0, 9), Vec3::Zero(), Vec3::Zero(), 0.01, m});
  const double c = 0.02;  // N s/m
  w.set_body_force([c](const Particles& p, double, std::size_t b, std::size_t e, std::vector<Vec3>& f) {
    for (std::size_t i = b; i < e; ++i) f[i] -= c * p.v[i];
  });
  w.step(20000);  // 2 s, ten time constants m/c
  const double vt = sphere_mass(0.01, 1000) * 9.81 / c;
  BOOST_TEST(std::abs(-w.particles().v[0].z() / vt - 1) < 1e-3);
}

// dem/team.h: a pass of one thread runs on the caller without entering an OpenMP region (libgomp's
// futex wake at the end of each region and barrier is what it saves); a pass of two runs on a team
// of two, whose barrier holds; and inside a region someone else opened, a pass of one keeps a region
// of its own, so that an orphaned barrier in it cannot bind to the enclosing team.
BOOST_AUTO_TEST_CASE(a_team_of_one_runs_outside_openmp) {
  int calls = 0, level = -1, thread = -1, threads = 0;
  on_team(1, [&] {
    ++calls;
    level = omp_get_level();
    thread = omp_get_thread_num();
    threads = omp_get_num_threads();
#pragma omp barrier
  });
  BOOST_TEST(calls == 1);
  BOOST_TEST(level == 0);
  BOOST_TEST(thread == 0);
  BOOST_TEST(threads == 1);

  std::atomic<int> arrived{0}, seen_after_barrier{0};
  on_team(2, [&] {
    arrived.fetch_add(1);
#pragma omp barrier
    seen_after_barrier.fetch_add(arrived.load());
  });
  BOOST_TEST(arrived.load() == 2);
  BOOST_TEST(seen_after_barrier.load() == 4);  // each thread saw both arrive before the barrier let it go

  // The pass is written outside the enclosing region: a barrier lexically inside `single` is refused
  // by clang (it would bind to the outer team); orphaned, it binds to the team the pass opens.
  int inner_level = -1;
  const auto inner = [&] {
    inner_level = omp_get_level();
#pragma omp barrier
  };
#pragma omp parallel num_threads(2)
  {
#pragma omp single
    on_team(1, inner);
  }
  BOOST_TEST(inner_level == 2);
}

// Checkpoint/restart: a run interrupted by a checkpoint and restored in a freshly built scene continues
// bit-identically (positions, velocities, spins, forces, wall loads, inserted mass), including the
// neighbour list, contact history and insertion RNG.
BOOST_AUTO_TEST_CASE(restart_continues_bit_identically) {
  auto make = [] {
    Settings s;
    s.threads = 2;
    World w = pellet_box(s, 200);
    Inserter ins;
    ins.region = Box{Vec3(0.01, 0.01, 0.3), Vec3(0.09, 0.09, 0.4)};
    ins.mass_rate = 0.2;
    ins.radius_min = 4e-3;
    ins.radius_max = 5e-3;
    ins.material = 0;
    ins.interval = 0.005;
    w.add_inserter(ins);
    return w;
  };
  const std::string ck = tmp("restart.ckpt");
  World a = make();
  a.step(1500);
  a.save_checkpoint(ck);
  a.step(1500);
  World b = make();
  b.load_checkpoint(ck);
  BOOST_TEST(b.step_count() == 1500);
  b.step(1500);
  const auto& pa = a.particles();
  const auto& pb = b.particles();
  BOOST_TEST_REQUIRE(pa.size() == pb.size());
  BOOST_TEST(pa.size() > 200u);  // insertion happened
  BOOST_TEST(std::memcmp(pa.x.data(), pb.x.data(), pa.size() * sizeof(Vec3)) == 0);
  BOOST_TEST(std::memcmp(pa.v.data(), pb.v.data(), pa.size() * sizeof(Vec3)) == 0);
  BOOST_TEST(std::memcmp(pa.w.data(), pb.w.data(), pa.size() * sizeof(Vec3)) == 0);
  BOOST_TEST(std::memcmp(pa.f.data(), pb.f.data(), pa.size() * sizeof(Vec3)) == 0);
  BOOST_TEST(std::memcmp(a.walls()[0].force.data(), b.walls()[0].force.data(), sizeof(Vec3)) == 0);
  BOOST_TEST(a.inserters()[0].inserted_mass == b.inserters()[0].inserted_mass);
  // A checkpoint from a different scene is refused.
  Settings s;
  World c(s);
  c.materials().add({"m", 1e7, 0.3, 1000});
  BOOST_CHECK_THROW(c.load_checkpoint(ck), chutelab::InputError);
  std::ofstream(tmp("garbage.ckpt")) << "not a checkpoint";
  BOOST_CHECK_THROW(b.load_checkpoint(tmp("garbage.ckpt")), chutelab::InputError);
}

// A run with a stream inserter restarts bit-identically too: the held particles stay held (they
// are saved with their inserter) and are released on the same steps.
BOOST_AUTO_TEST_CASE(restart_keeps_held_particles) {
  auto make = [] {
    Settings s;
    s.threads = 1;
    World w = pellet_box(s, 100);
    Inserter ins;
    ins.region = Box{Vec3(0.01, 0.01, 0.3), Vec3(0.09, 0.09, 0.4)};
    ins.mass_rate = 0.2;
    ins.radius_min = ins.radius_max = 4.5e-3;
    ins.material = 0;
    ins.velocity = Vec3(0.3, 0, -1);
    ins.hold_to_face = true;
    ins.hold_axis = 2;
    ins.interval = 0.091;
    w.add_inserter(ins);
    return w;
  };
  const std::string ck = tmp("restart-held.ckpt");
  World a = make();
  std::size_t held = 0;
  for (int k = 0; k < 200 && held < 5; ++k) {  // until a batch is held
    a.step(100);
    held = 0;
    for (auto h : a.particles().held_by) held += h >= 0 ? 1 : 0;
  }
  BOOST_TEST_REQUIRE(held >= 5u);  // the checkpoint is taken while some are held
  a.save_checkpoint(ck);
  a.step(3000);
  World b = make();
  b.load_checkpoint(ck);
  b.step(3000);
  const auto& pa = a.particles();
  const auto& pb = b.particles();
  BOOST_TEST_REQUIRE(pa.size() == pb.size());
  BOOST_TEST(std::memcmp(pa.x.data(), pb.x.data(), pa.size() * sizeof(Vec3)) == 0);
  BOOST_TEST(std::memcmp(pa.v.data(), pb.v.data(), pa.size() * sizeof(Vec3)) == 0);
  BOOST_TEST(pa.held_by == pb.held_by);
}

// VTK legacy files ParaView reads: header, point count, the data arrays; CSV time series with one row
// per record and per-wall load columns.
BOOST_AUTO_TEST_CASE(vtk_and_csv_output) {
  Settings s;
  World w = pellet_box(s, 50);
  w.step(100);
  const std::string pv = tmp("particles.vtk"), wv = tmp("walls.vtk"), csv = tmp("series.csv");
  write_vtk_particles(pv, w.particles());
  write_vtk_walls(wv, w.walls());
  std::ifstream f(pv);
  std::stringstream ss;
  ss << f.rdbuf();
  const std::string text = ss.str();
  BOOST_TEST(text.rfind("# vtk DataFile Version 3.0", 0) == 0u);
  BOOST_TEST(text.find("POINTS 50 double") != std::string::npos);
  for (const char* key : {"SCALARS radius_mm", "VECTORS velocity_mps", "VECTORS force_N", "VECTORS angular_velocity_radps",
                          "SCALARS id"})
    BOOST_TEST(text.find(key) != std::string::npos, key);
  // Lengths in mm, as every chutelab file, and the title line says so: the first radius as written.
  BOOST_TEST(text.find("\nchutelab DEM particles; lengths in mm, velocities in m/s, forces in N\n") != std::string::npos);
  {
    const auto at = text.find("SCALARS radius_mm double 1\nLOOKUP_TABLE default\n");
    BOOST_TEST_REQUIRE(at != std::string::npos);
    const double r = std::stod(text.substr(at + std::string("SCALARS radius_mm double 1\nLOOKUP_TABLE default\n").size()));
    BOOST_TEST(r == w.particles().radius[0] * 1e3, boost::test_tools::tolerance(1e-8));
  }
  std::ifstream fw(wv);
  std::string first;
  std::getline(fw, first);
  BOOST_TEST(first == "# vtk DataFile Version 3.0");
  {
    TimeSeriesCsv ts(csv, w);
    for (int k = 0; k < 3; ++k) {
      w.step(10);
      ts.record(w);
    }
  }
  std::ifstream fc(csv);
  std::string header, line;
  std::getline(fc, header);
  BOOST_TEST(header.find("floor_Fz_N") != std::string::npos);
  int rows = 0;
  while (std::getline(fc, line)) ++rows;
  BOOST_TEST(rows == 3);
}

// Particles added or removed between steps join the contact search at once: a sphere added on the
// floor of a running scene is held up by it (contact force = weight within 1 %) at the next step.
BOOST_AUTO_TEST_CASE(particles_added_between_steps_take_part) {
  Settings s;
  World w = pellet_box(s, 30);
  w.step(200);
  const double r = 4.5e-3;
  const double m = sphere_mass(r, 1000);
  // Equilibrium Hertz overlap on steel: m g = 4/3 E* sqrt(R) delta^{3/2}.
  const double es = 1.0 / ((1 - 0.38 * 0.38) / 2.5e7 + (1 - 0.3 * 0.3) / 2e11);
  const double delta = std::pow(m * 9.81 / (4.0 / 3.0 * es * std::sqrt(r)), 2.0 / 3.0);
  const std::int64_t id = w.add_particle({Vec3(0.09, 0.09, r - delta), Vec3::Zero(), Vec3::Zero(), r, 0});
  w.remove_particles_if([&](std::size_t i) { return w.particles().id[i] == 3; });
  w.step(1);
  const auto& p = w.particles();
  std::size_t k = 0;
  while (p.id[k] != id) ++k;
  BOOST_TEST(std::abs(p.f[k].z()) < 0.01 * m * 9.81);  // floor force balances gravity
  BOOST_TEST(p.size() == 30u);
}

// Impossible parameters are refused with InputError naming the field.
BOOST_AUTO_TEST_CASE(bad_input_is_reported) {
  Settings s;
  World w(s);
  BOOST_CHECK_THROW(w.materials().add({"neg", -1.0, 0.3, 1000}), chutelab::InputError);
  BOOST_CHECK_THROW(w.materials().add({"nu", 1e7, 0.6, 1000}), chutelab::InputError);
  const int m = w.materials().add({"ok", 1e7, 0.3, 1000});
  Interaction bad;
  bad.restitution = 1.5;
  BOOST_CHECK_THROW(w.materials().set_interaction(m, m, bad), chutelab::InputError);
  BOOST_CHECK_THROW(w.add_particle({Vec3::Zero(), Vec3::Zero(), Vec3::Zero(), -0.01, m}), chutelab::InputError);
  BOOST_CHECK_THROW(w.add_particle({Vec3::Zero(), Vec3::Zero(), Vec3::Zero(), 0.01, 7}), chutelab::InputError);
  w.add_particle({Vec3::Zero(), Vec3::Zero(), Vec3::Zero(), 0.01, m});
  try {
    w.initialise();  // no domain
    BOOST_ERROR("missing domain accepted");
  } catch (const chutelab::InputError& e) {
    BOOST_TEST(std::string(e.what()).find("domain") != std::string::npos);
  }
  Settings lsd = quiet_settings(1e-5);
  lsd.normal = NormalLaw::of<LinearSpringDashpot>();
  World l(lsd);
  const int lm = l.materials().add({"m", 1e7, 0.3, 1000});
  l.add_particle({Vec3::Zero(), Vec3::Zero(), Vec3::Zero(), 0.01, lm});
  BOOST_CHECK_THROW(l.initialise(), chutelab::InputError);  // linear model without a stiffness
}

// A law reads only the parameters it declares (dem/contact/normal_laws.h): a name it does not know,
// here the linear law's stiffness given to Hertz-Mindlin, is an error that names it, not a number
// silently ignored; the same interaction runs under the law that declares it.
BOOST_AUTO_TEST_CASE(a_law_rejects_parameters_it_does_not_declare) {
  for (const NormalLaw law : {NormalLaw::of<HertzMindlin>(), NormalLaw::of<LinearSpringDashpot>()}) {
    Settings s = quiet_settings(1e-5);
    s.normal = law;
    s.domain = Box{Vec3(-1, -1, -1), Vec3(1, 1, 1)};
    World w(s);
    const int m = w.materials().add({"m", 1e7, 0.3, 1000});
    Interaction in;
    in.law.set("normal_stiffness", 1e4);
    w.materials().set_interaction(m, m, in);
    w.add_particle({Vec3::Zero(), Vec3::Zero(), Vec3::Zero(), 0.01, m});
    if (law == NormalLaw::of<LinearSpringDashpot>()) {
      BOOST_CHECK_NO_THROW(w.initialise());
      continue;
    }
    try {
      w.initialise();
      BOOST_ERROR("an undeclared law parameter was accepted");
    } catch (const chutelab::InputError& e) {
      BOOST_TEST(std::string(e.what()).find("normal_stiffness") != std::string::npos, e.what());
      BOOST_TEST(std::string(e.what()).find("hertz-mindlin") != std::string::npos, e.what());
    }
  }
  BOOST_TEST(NormalLaw::named("lsd").has_value());
  BOOST_TEST(!NormalLaw::named("no-such-law").has_value());
  BOOST_TEST(NormalLaw::keys().find("\"hertz-mindlin\"") != std::string::npos);
}
