// Walls: STL reading (ASCII and binary, malformed files), mesh contacts at seams, per-wall and
// per-triangle loads, moving walls and surface velocities (conveyor belt, pulley).
#define BOOST_TEST_MODULE dem_walls
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <unistd.h>

#include "core/input_error.h"
#include "dem/walls/stl.h"
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

void write_text(const std::string& path, const std::string& text) { std::ofstream(path) << text; }

// A flat square [0,L]^2 at z = 0 split into two triangles along the diagonal.
TriangleMesh square(double L) {
  return TriangleMesh::from_soup({{Vec3(0, 0, 0), Vec3(L, 0, 0), Vec3(L, L, 0)}, {Vec3(0, 0, 0), Vec3(L, L, 0), Vec3(0, L, 0)}});
}

const char* kAsciiSquare = R"(solid square
  facet normal 0 0 1
    outer loop
      vertex 0 0 0
      vertex 1 0 0
      vertex 1 1 0
    endloop
  endfacet
  facet normal 0 0 1
    outer loop
      vertex 0 0 0
      vertex 1 1 0
      vertex 0 1 0
    endloop
  endfacet
endsolid square
)";

// Resting sphere on a wall: returns the world after settling (damped, e = 0.3).
struct Rest {
  double r = 0.01, rho = 1000, g = 9.81;
  double m() const { return sphere_mass(r, rho); }
};

World resting_world(Wall wall, const Vec3& pos, double mu = 0.5, Vec3 v0 = Vec3::Zero()) {
  Settings s = quiet_settings(0.0, 5.0);
  s.gravity = Vec3(0, 0, -9.81);
  s.characteristic_speed = 0.5;
  World w(s);
  const int ball = w.materials().add({"ball", 1e7, 0.3, 1000});
  const int steel = w.materials().add({"steel", 2e11, 0.3, 7800});
  Interaction in;
  in.friction = mu;
  in.restitution = 0.3;
  w.materials().set_interaction(ball, steel, in);
  wall.material = steel;
  w.add_wall(std::move(wall));
  w.add_particle({pos, v0, Vec3::Zero(), 0.01, ball});
  w.initialise();
  return w;
}

}  // namespace

// ASCII and binary STL give the same welded mesh (4 vertices, 2 triangles); scale converts units.
BOOST_AUTO_TEST_CASE(stl_ascii_and_binary_round_trip) {
  const std::string a = tmp("square_ascii.stl"), b = tmp("square_binary.stl");
  write_text(a, kAsciiSquare);
  const TriangleMesh ma = read_stl(a, 1e-3);
  BOOST_TEST(ma.triangles.size() == 2u);
  BOOST_TEST(ma.vertices.size() == 4u);  // shared corners welded
  BOOST_TEST(ma.bounds().hi.x() == 1e-3);
  write_stl_binary(b, ma);
  const TriangleMesh mb = read_stl(b);
  BOOST_TEST(mb.triangles.size() == 2u);
  BOOST_TEST(mb.vertices.size() == 4u);
  BOOST_TEST(std::abs(mb.bounds().hi.y() - 1e-3) < 1e-10);  // float storage
  // A binary file whose 80-byte header starts with "solid" must still be read as binary.
  {
    std::fstream f(b, std::ios::in | std::ios::out | std::ios::binary);
    f.write("solid trick", 11);
  }
  BOOST_TEST(read_stl(b).triangles.size() == 2u);
}

// Malformed files throw InputError naming the file and what is wrong.
BOOST_AUTO_TEST_CASE(malformed_stl_is_reported_clearly) {
  auto expect = [](const std::string& name, const std::string& text, const std::string& needle) {
    const std::string p = tmp(name);
    write_text(p, text);
    try {
      read_stl(p);
      BOOST_ERROR("no exception for " << name);
    } catch (const chutelab::InputError& e) {
      const std::string what = e.what();
      BOOST_TEST(what.find(p) != std::string::npos, what);
      BOOST_TEST(what.find(needle) != std::string::npos, what);
    }
  };
  std::string s(kAsciiSquare);
  expect("truncated.stl", s.substr(0, s.find("endfacet")), "ends inside a facet");
  std::string two = s;
  two.replace(two.find("vertex 1 0 0"), 12, "vertex 1 zero 0");
  expect("badnumber.stl", two, ":5");  // line number of the bad vertex
  std::string degenerate = s;
  degenerate.replace(degenerate.find("vertex 1 1 0"), 12, "vertex 1 0 0");
  expect("degenerate.stl", degenerate, "degenerate triangle");
  expect("empty.stl", "", "empty");
  std::string bin(84 + 50, '\0');
  bin[80] = 5;  // claims 5 triangles, holds 1
  expect("short.stl", bin, "header says 5 triangles");
  BOOST_CHECK_THROW(read_stl(tmp("does_not_exist.stl")), chutelab::InputError);
}

// A sphere resting exactly on the shared diagonal of a two-triangle square, and on the shared corner
// of four triangles, makes one contact: the wall carries its weight once (within 0.1 %: residual
// bounce after 0.5 s of damped settling), not two or four times.
BOOST_AUTO_TEST_CASE(mesh_seams_carry_a_sphere_once) {
  Rest R;
  for (const Vec3& xy : {Vec3(0.05, 0.05, 0), Vec3(0.03, 0.07, 0)}) {  // on the diagonal; inside a face
    World w = resting_world(Wall::mesh("plate", square(0.1), 0), Vec3(xy.x(), xy.y(), R.r));
    w.step(std::llround(0.5 / w.dt()));
    BOOST_TEST(std::abs(w.walls()[0].force.z() / (-R.m() * R.g) - 1) < 1e-3);
    BOOST_TEST(std::abs(w.particles().x[0].x() - xy.x()) < 1e-6);  // no sideways push at the seam
  }
  // Four triangles meeting at the centre vertex (0.05, 0.05).
  const Vec3 c(0.05, 0.05, 0);
  const TriangleMesh fan = TriangleMesh::from_soup({{Vec3(0, 0, 0), Vec3(0.1, 0, 0), c}, {Vec3(0.1, 0, 0), Vec3(0.1, 0.1, 0), c},
                                                    {Vec3(0.1, 0.1, 0), Vec3(0, 0.1, 0), c}, {Vec3(0, 0.1, 0), Vec3(0, 0, 0), c}});
  World w = resting_world(Wall::mesh("fan", fan, 0), Vec3(0.05, 0.05, R.r));
  w.step(std::llround(0.5 / w.dt()));
  BOOST_TEST(std::abs(w.walls()[0].force.z() / (-R.m() * R.g) - 1) < 1e-3);
  // Per-triangle loads add up to the wall load.
  Vec3 sum = Vec3::Zero();
  for (const auto& f : w.walls()[0].element_force) sum += f;
  BOOST_TEST((sum - w.walls()[0].force).norm() < 1e-12);
}

// A convex edge (a ridge made of two triangles) contacts through the edge: a sphere dropped on it
// is pushed along the edge normal, not by both faces.
BOOST_AUTO_TEST_CASE(mesh_edge_contact_on_a_ridge) {
  Rest R;
  const TriangleMesh ridge = TriangleMesh::from_soup({{Vec3(-0.1, -0.1, -0.1), Vec3(0, -0.1, 0), Vec3(0, 0.1, 0)},
                                                      {Vec3(-0.1, -0.1, -0.1), Vec3(0, 0.1, 0), Vec3(-0.1, 0.1, -0.1)},
                                                      {Vec3(0, -0.1, 0), Vec3(0.1, -0.1, -0.1), Vec3(0.1, 0.1, -0.1)},
                                                      {Vec3(0, -0.1, 0), Vec3(0.1, 0.1, -0.1), Vec3(0, 0.1, 0)}});
  World w = resting_world(Wall::mesh("ridge", ridge, 0), Vec3(0, 0, R.r + 1e-4), 0.0);
  w.step(200);
  BOOST_TEST(w.wall_contact_count() == 1u);
  BOOST_TEST(std::abs(w.walls()[0].force.x()) < 1e-9);  // symmetric: no sideways force
}

// Per-triangle force: a sphere resting inside triangle 1 loads only triangle 1 with its weight.
BOOST_AUTO_TEST_CASE(per_triangle_force_map) {
  Rest R;
  World w = resting_world(Wall::mesh("plate", square(0.1), 0), Vec3(0.03, 0.07, R.r));
  w.step(std::llround(0.3 / w.dt()));
  const auto& ef = w.walls()[0].element_force;
  BOOST_TEST(ef[0].norm() == 0.0);
  BOOST_TEST(std::abs(ef[1].z() / (-R.m() * R.g) - 1) < 1e-3);
}

// Conveyor belt: a plane carrying a surface velocity U (it does not move). A sphere dropped on it slips
// until it rolls, then moves at 2U/7 (angular momentum about the contact point is conserved). The
// tolerance 1 % covers the tangential spring's residual oscillation.
BOOST_AUTO_TEST_CASE(belt_surface_velocity_drives_sphere_to_rolling) {
  Rest R;
  const double U = 2.0;
  Wall belt = Wall::plane("belt", Vec3::Zero(), Vec3::UnitZ(), 0);
  belt.surface.linear = Vec3(U, 0, 0);
  World w = resting_world(belt, Vec3(0, 0, R.r), 0.5);
  w.step(std::llround(1.0 / w.dt()));
  const auto& p = w.particles();
  BOOST_TEST_MESSAGE("belt: v " << p.v[0].x() << " (2U/7 = " << 2 * U / 7 << ")");
  BOOST_TEST(std::abs(p.v[0].x() / (2 * U / 7) - 1) < 0.01);
  BOOST_TEST(std::abs(p.x[0].z() - R.r) < 1e-3 * R.r);  // the wall did not move
  // The belt is pulled forward by the sphere while it slips, and by nothing once it rolls.
  BOOST_TEST(std::abs(w.walls()[0].force.x()) < 1e-3 * R.m() * R.g);
}

// Pulley: a cylinder with surface spin. A sphere held on top of the pulley (gravity towards the axis)
// is dragged tangentially: while slipping the friction force is mu F_n along the surface velocity
// omega x r; the velocity field of the pulley is checked directly.
BOOST_AUTO_TEST_CASE(pulley_surface_velocity) {
  Wall pulley = Wall::cylinder("pulley", Vec3::Zero(), Vec3::UnitY(), 0.2, 0);
  pulley.surface.omega = Vec3(0, 3.0, 0);  // rad/s about the axis
  const Vec3 top(0, 0, 0.2);
  BOOST_TEST((pulley.velocity_at(top) - Vec3(0.6, 0, 0)).norm() < 1e-12);  // omega x r = 3 * 0.2 in +x
  BOOST_TEST(pulley.angular_velocity().y() == 3.0);
  Rest R;
  World w = resting_world(pulley, Vec3(0, 0, 0.2 + R.r), 0.4);
  w.step(3);
  const Vec3 f = w.particles().f[0] - R.m() * Vec3(0, 0, -9.81);  // contact force only
  BOOST_TEST(f.x() > 0.0);
  BOOST_TEST(std::abs(f.x() / (0.4 * f.z()) - 1) < 1e-4);  // Coulomb limit (normal tilted by the 1e-8 m slide)
}

// A moving (translating) wall is a piston: a sphere resting on a floor that rises at 0.1 m/s rides
// with it, and the floor's load cell reads the weight (within 0.1 %).
BOOST_AUTO_TEST_CASE(moving_wall_carries_sphere_and_reads_load) {
  Rest R;
  Wall floor = Wall::plane("lift", Vec3::Zero(), Vec3::UnitZ(), 0);
  floor.motion.velocity = Vec3(0, 0, 0.1);
  World w = resting_world(floor, Vec3(0, 0, R.r));
  w.step(std::llround(1.0 / w.dt()));
  BOOST_TEST(std::abs(w.particles().v[0].z() - 0.1) < 1e-3);
  BOOST_TEST(std::abs(w.particles().x[0].z() - (0.1 * w.time() + R.r)) < 1e-3 * R.r + 1e-5);
  BOOST_TEST(std::abs(w.walls()[0].force.z() / (-R.m() * R.g) - 1) < 1e-3);
}

// A rotating mesh: vertices follow the exact rigid rotation, the wall velocity is omega x r, and a
// resting sphere at the axis end is carried round (tilting plate throws it off in the right direction).
BOOST_AUTO_TEST_CASE(rotating_mesh_wall) {
  Wall plate = Wall::mesh("plate", square(0.2), 0);
  plate.motion.pivot = Vec3(0, 0, 0);
  plate.motion.omega = Vec3(0, 0, 2.0);  // spin about z through the corner
  plate.set_time(pi / 4);                // quarter turn
  const auto& m = std::get<TriangleMesh>(plate.current);
  BOOST_TEST((m.vertices[1] - Vec3(0, 0.2, 0)).norm() < 1e-12);  // (0.2,0,0) turned 90 degrees
  BOOST_TEST((plate.velocity_at(Vec3(0, 0.2, 0)) - Vec3(-0.4, 0, 0)).norm() < 1e-12);
  // Torque on a load cell: a sphere resting at (0.15, 0.05) on the plate loads it off the load point.
  Rest R;
  World w = resting_world(Wall::mesh("plate", square(0.2), 0), Vec3(0.15, 0.05, R.r));
  w.wall(0).load_point = Vec3::Zero();
  w.step(std::llround(0.3 / w.dt()));
  const Vec3 torque = w.walls()[0].torque;
  const double W = R.m() * R.g;
  BOOST_TEST(std::abs(torque.x() / (0.05 * -W) - 1) < 1e-3);  // (r x F).x = y F_z
  BOOST_TEST(std::abs(torque.y() / (-0.15 * -W) - 1) < 1e-3);
}

// Rotating an unbounded plane is refused with a clear message.
BOOST_AUTO_TEST_CASE(impossible_wall_motion_is_rejected) {
  Settings s = quiet_settings(1e-5);
  World w(s);
  const int m = w.materials().add({"m", 1e7, 0.3, 1000});
  Wall p = Wall::plane("spin", Vec3::Zero(), Vec3::UnitZ(), m);
  p.motion.omega = Vec3(1, 0, 0);
  BOOST_CHECK_THROW(w.add_wall(p), chutelab::InputError);
  BOOST_CHECK_THROW(Wall::cylinder("c", Vec3::Zero(), Vec3::UnitY(), -1.0, m), chutelab::InputError);
}

// A still wall's elements are listed only within R + skin/2 (no particle moves farther before the
// next rebuild). A wall set moving after a rebuild (without mark_changed) must still be seen by the
// sphere it reaches: the list is rebuilt with the whole skin as soon as it moves, so the contact
// starts when the overlap starts, not once the wall has crossed the skin.
BOOST_AUTO_TEST_CASE(wall_set_moving_after_rebuild_is_listed_with_whole_skin) {
  Settings s = quiet_settings(0.0, 5.0);
  const double r = 0.01, skin = 0.4 * r;
  s.skin = skin;
  World w(s);
  const int ball = w.materials().add({"ball", 1e7, 0.3, 1000});
  w.add_wall(Wall::plane("floor", Vec3::Zero(), Vec3::UnitZ(), ball));
  // 0.75 skin above the floor: beyond a still wall's R + skin/2, within R + skin.
  w.add_particle({Vec3(0, 0, r + 0.75 * skin), Vec3::Zero(), Vec3::Zero(), r, ball});
  w.initialise();
  w.step(1);
  const double speed = 0.1, t0 = w.time();
  Wall& floor = w.wall(0);
  floor.motion.velocity = Vec3(0, 0, speed);
  floor.motion.pivot -= floor.motion.velocity * t0;  // start the motion now
  floor.set_time(t0);
  // Step until the floor has risen 0.8 skin: an overlap of 0.05 skin, which must push the sphere.
  const auto steps = static_cast<std::int64_t>(std::ceil(0.8 * skin / speed / w.dt()));
  w.step(steps);
  BOOST_TEST(w.particles().f[0].z() > 0.0);
  BOOST_TEST(w.walls()[0].force.z() < 0.0);
}
