// The LIGGGHTS deck writer and output readers (dem/liggghts), without running LIGGGHTS: the deck
// carries the scene's walls, materials, feed and relaxation in LIGGGHTS' syntax; the readers take
// LIGGGHTS' file layouts and reject malformed files naming the file and line.
#define BOOST_TEST_MODULE liggghts_deck
#include <boost/test/unit_test.hpp>

#include <filesystem>
#include <fstream>
#include <unistd.h>

#include <fmt/format.h>

#include "core/input_error.h"
#include "dem/liggghts/output.h"
#include "dem/liggghts/run.h"
#include "dem/station/scene.h"
#include "../dem_station/tiny_station.h"

using namespace chutelab;
using namespace chutelab::dem;

namespace {

liggghts::Deck tiny_deck(dem::station::RunSettings s = test::tiny_settings()) {
  liggghts::Options o;
  o.settings = s;
  return liggghts::deck_for(test::tiny_station(), o);
}

bool has(const std::string& text, const std::string& what) { return text.find(what) != std::string::npos; }

std::string temp_file(const std::string& name, const std::string& text) {
  // Per process: sessions sharing the machine run the suite at the same time.
  const auto p =
      std::filesystem::temp_directory_path() / ("chutelab-liggghts-" + std::to_string(::getpid()) + "-" + name);
  std::ofstream(p) << text;
  return p.string();
}

}  // namespace

// The station's parts in LIGGGHTS terms (tiny station: V_b = 3 m/s, R_b = 0.13 m, plate at 0.35 m,
// 2.5 kg/s): the belt slides at V_b, the pulley turns at V_b / R_b about its axis, the plate is a
// stress mesh with the load-cell point on its face at y = 0, one type per material.
BOOST_AUTO_TEST_CASE(deck_has_the_station) {
  const auto d = tiny_deck();
  const std::string& in = d.input;
  BOOST_TEST_MESSAGE(in);
  BOOST_TEST(has(in, "pair_style gran model hertz tangential history rolling_friction cdt"));
  BOOST_TEST(has(in, "fix walls all wall/gran model hertz tangential history rolling_friction cdt mesh n_meshes 5"));
  BOOST_TEST(has(in, "create_box 4 domain"));
  BOOST_TEST(has(in, "surface_vel 3 0 0"));
  BOOST_TEST(has(in, "surface_ang_vel origin 0 0 0 axis 0 0 -1 omega 23.07692308"));  // 3 / 0.13
  BOOST_TEST(has(in, "mesh/surface/stress file meshes/w2_plate.stl type 2 reference_point 0.35 0 0"));
  BOOST_TEST(has(in, "massrate 2.5 "));
  BOOST_TEST(has(in, "vel constant 3 -1 0 insertion_face feed_face"));
  BOOST_TEST(has(in, "fix feeder all addforce v_fr_fx v_fr_fy v_fr_fz"));
  // Particle-plate 0.66 / 0.27, particle-belt 0.4 / 0.7 (types 1-2 and 1-3).
  BOOST_TEST(has(in, "coefficientRestitution peratomtypepair 4 0.7 0.66 0.4 0.66"));
  BOOST_TEST(has(in, "coefficientFriction peratomtypepair 4 0.3 0.27 0.7 0.27"));
  BOOST_TEST(d.files.size() == 6u);  // belt, pulley, plate, two side panels, feed face
  // The pulley: 72 facets per half turn, two triangles each, as the LIGGGHTS rig.
  const std::string& pulley = d.files.at("meshes/w1_pulley.stl");
  std::size_t facets = 0;
  for (std::size_t p = pulley.find("facet normal"); p != std::string::npos; p = pulley.find("facet normal", p + 1)) ++facets;
  BOOST_TEST(facets == 144u);
  // Samples every 3 ms, snapshots every third: the built-in run's cadence.
  BOOST_TEST(d.steps_per_sample == std::llround(0.003 / d.dt));
  BOOST_TEST(d.samples_per_snapshot == 3);
}

// cdt's lever between equal spheres is R/2, the built-in's R (or, with rolling_lever = "effective",
// the built-in halves the coefficient instead): the deck doubles the scene's particle-particle
// coefficient, so both give the same torque; against walls both levers are R.
BOOST_AUTO_TEST_CASE(deck_rolling_friction_matches_the_builtin_torque) {
  auto s = test::tiny_settings();
  BOOST_TEST(has(tiny_deck(s).input, "coefficientRollingFriction peratomtypepair 4 0.2 0.1 0.1 0.1"));
  s.rolling_lever_effective = true;  // the scene holds 0.05: LIGGGHTS gets the dataset's 0.1
  BOOST_TEST(has(tiny_deck(s).input, "coefficientRollingFriction peratomtypepair 4 0.1 0.1 0.1 0.1"));
}

// A feeder that relaxed every component (datasets/liggghts-rig [dem.feed]) relaxes the fall too.
BOOST_AUTO_TEST_CASE(deck_relaxes_the_fall_when_the_feeder_did) {
  auto s = test::tiny_settings();
  BOOST_TEST(has(tiny_deck(s).input, "variable fr_fall atom v_fr_vn*(v_fr_vn<0)"));
  s.relax_all = true;
  BOOST_TEST(has(tiny_deck(s).input, "variable fr_fall atom 0\n"));
}

BOOST_AUTO_TEST_CASE(deck_refuses_what_liggghts_cannot_run) {
  auto s = test::tiny_settings();
  s.particle_shape = dem::station::ParticleShape::clump;
  BOOST_CHECK_THROW(tiny_deck(s), InputError);
  s = test::tiny_settings();
  s.contact = dem::NormalLaw::of<dem::LinearSpringDashpot>();
  BOOST_CHECK_THROW(tiny_deck(s), InputError);
}

// A law's LIGGGHTS model and its own per-pair numbers come from the law's file (its liggghts and
// liggghts_pair_properties): Hooke's deck runs hooke/stiffness, between particles and against the
// walls, with the kn, kt, gamman and gammat the built-in engine uses (the particle pair's kn: the
// stiffness its matched_parameters give the scene).
BOOST_AUTO_TEST_CASE(deck_takes_the_laws_own_model_and_numbers) {
  auto s = test::tiny_settings();
  BOOST_TEST(!has(tiny_deck(s).input, "property/global kn "));
  s.contact = dem::NormalLaw::of<dem::Hooke>();
  const std::string deck = tiny_deck(s).input;
  BOOST_TEST(has(deck, "pair_style gran model hooke/stiffness tangential history"));
  BOOST_TEST(has(deck, "wall/gran model hooke/stiffness tangential history"));
  for (const char* p : {"kn", "kt", "gamman", "gammat"})
    BOOST_TEST(has(deck, fmt::format("all property/global {} peratomtypepair", p)), p);
  const auto sc = dem::station::build_scene(test::tiny_station(), s, {}, {});
  const auto& in = sc.world->materials().interaction(0, 0);
  const double kn = in.law.get("normal_stiffness").value_or(0.0);
  BOOST_TEST(kn > 0.0);
  BOOST_TEST(has(deck, fmt::format("property/global kn peratomtypepair {} {:.10g}", sc.world->materials().size(), kn)));
}

// The deck is a function of its inputs (the cache key contains it): equal inputs, equal text; a
// different seed, a different insertion stream.
BOOST_AUTO_TEST_CASE(deck_is_deterministic) {
  BOOST_TEST(tiny_deck().input == tiny_deck().input);
  auto s = test::tiny_settings();
  s.seed = 2;
  BOOST_TEST(tiny_deck(s).input != tiny_deck().input);
}

BOOST_AUTO_TEST_CASE(dump_reader_takes_frames_in_any_column_order) {
  const auto path = temp_file("ok.dump",
                              "ITEM: TIMESTEP\n100\nITEM: NUMBER OF ATOMS\n2\nITEM: BOX BOUNDS ff ff ff\n-1 1\n-1 1\n-1 1\n"
                              "ITEM: ATOMS x y z id vx vy vz mass\n0.1 0.2 0.3 7 1 2 3 0.5\n-0.1 0 0 9 0 0 -1 0.25\n"
                              "ITEM: TIMESTEP\n200\nITEM: NUMBER OF ATOMS\n0\nITEM: BOX BOUNDS ff ff ff\n-1 1\n-1 1\n-1 1\n"
                              "ITEM: ATOMS x y z id vx vy vz mass\n");
  liggghts::DumpReader r(path);
  liggghts::Frame f;
  BOOST_REQUIRE(r.next(f));
  BOOST_TEST(f.step == 100);
  BOOST_REQUIRE(f.id.size() == 2u);
  BOOST_TEST(f.id[0] == 7);
  BOOST_TEST(f.x[0].z() == 0.3);
  BOOST_TEST(f.v[1].z() == -1.0);
  BOOST_TEST(f.mass[1] == 0.25);
  BOOST_REQUIRE(r.next(f));
  BOOST_TEST(f.step == 200);
  BOOST_TEST(f.id.empty());
  BOOST_TEST(!r.next(f));
}

BOOST_AUTO_TEST_CASE(malformed_outputs_name_file_and_line) {
  {
    const auto path = temp_file("bad.dump",
                                "ITEM: TIMESTEP\n100\nITEM: NUMBER OF ATOMS\n2\nITEM: BOX BOUNDS ff ff ff\n-1 1\n-1 1\n-1 1\n"
                                "ITEM: ATOMS id x y z vx vy vz mass\n1 0 0 0 0 0 0 1\n2 0 0 zero 0 0 0 1\n");
    liggghts::DumpReader r(path);
    liggghts::Frame f;
    try {
      r.next(f);
      BOOST_FAIL("no error");
    } catch (const InputError& e) {
      BOOST_TEST(has(e.what(), path));
      BOOST_TEST(has(e.what(), ":11"));
    }
  }
  {
    const auto path = temp_file("bad_plate.txt", "# Time-averaged data\n# TimeStep f1 f2 f3 f4 f5 f6\n100 1 2 3 4 5 6\n200 1 2 3\n");
    try {
      liggghts::read_plate_file(path);
      BOOST_FAIL("no error");
    } catch (const InputError& e) {
      BOOST_TEST(has(e.what(), ":4"));
    }
  }
}

BOOST_AUTO_TEST_CASE(launcher_and_program) {
  liggghts::Options o;
  o.ranks = 4;
  BOOST_TEST(liggghts::launcher(o) == "mpirun -n 4 liggghts");
  o.command = "srun --mpi=pmix /opt/liggghts/bin/lmp_auto";
  BOOST_TEST(liggghts::launcher(o) == o.command);
  BOOST_TEST(liggghts::program_of(o.command) == "/opt/liggghts/bin/lmp_auto");
  BOOST_TEST(liggghts::version("/nonexistent/liggghts").empty());
}

// A missing program is a clear error before anything runs, not a crash.
BOOST_AUTO_TEST_CASE(missing_liggghts_is_a_clear_error) {
  liggghts::Options o;
  o.settings = test::tiny_settings();
  o.command = "/nonexistent/liggghts";
  o.work_dir =
      (std::filesystem::temp_directory_path() / ("chutelab-liggghts-missing-" + std::to_string(::getpid()))).string();
  try {
    liggghts::run_station(test::tiny_station(), o);
    BOOST_FAIL("no error");
  } catch (const InputError& e) {
    BOOST_TEST(has(e.what(), "/nonexistent/liggghts"));
    BOOST_TEST(has(e.what(), "liggghts"));
  }
}
