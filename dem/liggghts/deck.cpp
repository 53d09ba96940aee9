#include "dem/liggghts/deck.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>

#include <fmt/format.h>

#include "core/input_error.h"

namespace chutelab::dem::liggghts {
namespace {

// Full enough for the geometry (0.1 nm at 1 m); -0 printed as 0.
std::string num(double v) { return fmt::format("{:.10g}", v == 0.0 ? 0.0 : v); }

std::string vec(const Vec3& v) { return fmt::format("{} {} {}", num(v.x()), num(v.y()), num(v.z())); }

// ASCII STL (LIGGGHTS 3.x reads ASCII only), metres, with each facet's normal.
std::string ascii_stl(const TriangleMesh& m, const std::string& name) {
  std::string o = "solid " + name + "\n";
  for (const auto& t : m.triangles) {
    const Vec3 &a = m.vertices[static_cast<std::size_t>(t[0])], &b = m.vertices[static_cast<std::size_t>(t[1])],
               &c = m.vertices[static_cast<std::size_t>(t[2])];
    Vec3 n = (b - a).cross(c - a);
    if (n.norm() > 0.0) n.normalize();
    o += fmt::format("  facet normal {}\n    outer loop\n      vertex {}\n      vertex {}\n      vertex {}\n"
                     "    endloop\n  endfacet\n", vec(n), vec(a), vec(b), vec(c));
  }
  return o + "endsolid " + name + "\n";
}

bool is_prime(std::uint64_t n) {
  if (n < 2) return false;
  for (std::uint64_t d = 2; d * d <= n; ++d)
    if (n % d == 0) return false;
  return true;
}

// LIGGGHTS wants prime seeds above 10000; distinct streams for the templates and the insertion.
std::uint64_t prime_seed(std::uint64_t seed, int stream) {
  std::uint64_t n = 15485863ULL + (seed % 1000003ULL) * 1009ULL + static_cast<std::uint64_t>(stream) * 7919ULL;
  while (!is_prime(n)) ++n;
  return n;
}

// Fixes and variables are named after the walls; LIGGGHTS IDs allow letters, digits, underscores.
std::string ident(const std::string& s) {
  std::string o;
  for (char c : s) o += (std::isalnum(static_cast<unsigned char>(c)) ? c : '_');
  return o;
}

// The setup.toml key of the [dem] setting of `m`, "dem.KEY".
template <class T>
std::string dem_key(T station::RunSettings::*m) {
  return "dem." + std::string(station::dem_field(m).key);
}

// What the deck cannot write, refused before anything is written.
void check_scene(const station::Scene& sc, const station::RunSettings& s) {
  if (sc.shape != station::ParticleShape::sphere)
    throw InputError("", 0, dem_key(&station::RunSettings::particle_shape), "the LIGGGHTS engine runs spheres only (no clumps)");
  if (s.contact.liggghts().empty())
    throw InputError("", 0, dem_key(&station::RunSettings::contact),
                     fmt::format("the LIGGGHTS engine has no counterpart of the {} contact law", s.contact.title()));
  const World& w = *sc.world;
  const MaterialTable& mt = w.materials();
  const auto& ins = w.inserters().at(static_cast<std::size_t>(sc.inserter));
  if (!(ins.velocity.y() < 0.0))
    throw InputError("", 0, "insert_speed_down", "LIGGGHTS' insert/stream needs a downward insertion velocity");
  if (ins.material != 0) throw InputError("", 0, "dem", "the particles must be the scene's first material");
  for (int a = 0; a < mt.size(); ++a)
    if (a != ins.material && mt.material(a).density > 0.0)
      throw InputError("", 0, "dem", "the LIGGGHTS deck expects one particle material");
}

// The run's length and its sampling, in steps of the scene's dt; the part of the box the dump covers.
void schedule(const station::Scene& sc, const station::RunSettings& s, double sim_time, Deck& d) {
  d.dt = sc.dt;
  d.steps_per_sample = std::max<long long>(1, std::llround(s.sample_interval / sc.dt));
  const double sample_dt = static_cast<double>(d.steps_per_sample) * sc.dt;
  d.samples_per_snapshot = std::max<long long>(1, std::llround(s.snapshot_interval / sample_dt));
  const long long samples = static_cast<long long>(std::ceil(sim_time / sample_dt - 1e-9));
  d.steps = samples * d.steps_per_sample;
  // The sensors read the belt from 0.25 m before the tangent point on (the layer at s >= -0.15 m,
  // the side view at s > -0.25 m): the dump holds nothing upstream of that.
  const Vec3 p = sc.belt.tangent_point - 0.26 * sc.belt.along;
  d.dump_x_min = std::min(p.x(), -sc.belt.radius);
}

// The header, the box (its floor the discharge: particles below it have left the rig, scene.h
// sink_y) and the neighbour list.
void write_box(const Station& st, const station::Scene& sc, const Deck& d, std::string& o) {
  const World& w = *sc.world;
  o += fmt::format("# chutelab transfer station, condition {} (written by chutelab; dem/liggghts/deck.h)\n",
                   st.condition);
  o += fmt::format("# V_b {} m/s, mass flow {} kg/s, plate at x = {} m; {} spheres of {} mm, dt {} s, {} steps\n",
                   num(sc.belt_speed), num(sc.mass_flow), num(st.plate_distance), station::name(sc.shape),
                   num(sc.diameter * 1e3), num(sc.dt), d.steps);
  o += "atom_style granular\natom_modify map array\nboundary f f f\nnewton off\ncommunicate single vel yes\n"
       "units si\n";
  const Box& dom = w.settings().domain;
  o += fmt::format("region domain block {} {} {} {} {} {} units box\n", num(dom.lo.x()), num(dom.hi.x()),
                   num(sc.sink_y), num(dom.hi.y()), num(dom.lo.z()), num(dom.hi.z()));
  o += fmt::format("create_box {} domain\n", w.materials().size());
  o += fmt::format("neighbor {} bin\nneigh_modify delay 0\n", num(w.settings().skin));
}

// The materials (type k+1 is scene material k), the contact law's pair style, the time step and
// gravity.
void write_contact_model(const station::Scene& sc, const station::RunSettings& s, std::string& o) {
  const World& w = *sc.world;
  const MaterialTable& mt = w.materials();
  const int nt = mt.size();
  const int particle = w.inserters().at(static_cast<std::size_t>(sc.inserter)).material;
  // `(o += ' ') += x`, not `o += " " + x`: GCC 12 at -O2 flags the temporary's insert at the front
  // with a false -Wrestrict warning.
  o += "fix m_E all property/global youngsModulus peratomtype";
  for (int k = 0; k < nt; ++k) (o += ' ') += num(mt.material(k).youngs_modulus);
  o += "\nfix m_nu all property/global poissonsRatio peratomtype";
  for (int k = 0; k < nt; ++k) (o += ' ') += num(mt.material(k).poisson_ratio);
  auto pair_table = [&](const char* id, const char* property, auto get) {
    o += fmt::format("\nfix {} all property/global {} peratomtypepair {}", id, property, nt);
    for (int a = 0; a < nt; ++a)
      for (int b = 0; b < nt; ++b) (o += ' ') += num(get(mt.interaction(a, b)));
  };
  // Wall-wall pairs never meet; LIGGGHTS needs a restitution in (0, 1] for them all the same.
  pair_table("m_e", "coefficientRestitution", [](const Interaction& p) { return std::clamp(p.restitution, 1e-3, 1.0); });
  pair_table("m_mu", "coefficientFriction", [](const Interaction& p) { return p.friction; });
  // cdt's lever is the effective radius R_i R_j / (R_i + R_j): R/2 between the deck's equal spheres, R
  // against a wall. The scene's coefficients are for the lever R_i (with rolling_lever = "effective"
  // it holds half the dataset's), so the same torque needs twice them between particles.
  o += "\n# rolling friction: particle-particle coefficients doubled for cdt's effective radius (deck.cpp)";
  o += fmt::format("\nfix m_mur all property/global coefficientRollingFriction peratomtypepair {}", nt);
  for (int a = 0; a < nt; ++a)
    for (int b = 0; b < nt; ++b)
      (o += ' ') += num(mt.interaction(a, b).rolling_friction * (a == particle && b == particle ? 2.0 : 1.0));
  // What the law's model reads per type pair beyond the above (dem/contact/normal_laws.h).
  for (const auto& [property, values] : s.contact.liggghts_pair_properties(mt)) {
    o += fmt::format("\nfix m_{} all property/global {} peratomtypepair {}", property, property, nt);
    for (double v : values) (o += ' ') += num(v);
  }
  o += fmt::format("\npair_style gran model {} tangential history rolling_friction cdt\npair_coeff * *\n",
                   s.contact.liggghts());
  o += fmt::format("timestep {}\n", num(sc.dt));
  const Vec3 g = w.settings().gravity;
  o += fmt::format("fix gravity all gravity {} vector {}\n", num(g.norm()), vec(g.normalized()));
}

// Every wall as a static mesh with its surface velocity, the plate as the stress mesh with the load
// cell's reference point, and the walls' contact. Returns the plate's fix id.
std::string write_walls(const station::Scene& sc, const station::RunSettings& s, Deck& d, std::string& o) {
  const World& w = *sc.world;
  std::vector<std::string> mesh_ids;
  std::string plate_id;
  for (std::size_t k = 0; k < w.walls().size(); ++k) {
    const Wall& wall = w.walls()[k];
    const auto* mesh = std::get_if<TriangleMesh>(&wall.shape);
    if (!mesh) throw InputError("", 0, "dem", fmt::format("wall '{}' is not a mesh", wall.name));
    if (wall.motion.moving())
      throw InputError("", 0, "dem", fmt::format("wall '{}' moves; the LIGGGHTS deck has static meshes", wall.name));
    const std::string id = fmt::format("w{}_{}", k, ident(wall.name));
    const std::string file = fmt::format("meshes/{}.stl", id);
    d.files[file] = ascii_stl(*mesh, id);
    const bool plate = static_cast<int>(k) == sc.plate_wall;
    std::string line = fmt::format("fix {} all mesh/surface{} file {} type {}", id, plate ? "/stress" : "", file,
                                   wall.material + 1);
    const bool slides = !wall.surface.linear.isZero(0.0), turns = !wall.surface.omega.isZero(0.0);
    if (slides && turns)
      throw InputError("", 0, "dem", fmt::format("wall '{}' both slides and turns along its surface", wall.name));
    if (slides) line += " surface_vel " + vec(wall.surface.linear);
    if (turns) {
      const double om = wall.surface.omega.norm();
      line += fmt::format(" surface_ang_vel origin {} axis {} omega {}", vec(wall.surface.centre),
                          vec(wall.surface.omega / om), num(om));
    }
    if (plate) {
      line += " reference_point " + vec(wall.load_point);
      plate_id = id;
    }
    o += line + "\n";
    mesh_ids.push_back(id);
  }
  o += fmt::format("fix walls all wall/gran model {} tangential history rolling_friction cdt mesh n_meshes {} "
                   "meshes {}\n", s.contact.liggghts(), mesh_ids.size(), fmt::join(mesh_ids, " "));
  return plate_id;
}

// The feed: a horizontal face at the bottom of the insertion box, extruded up over its height, at
// the inserter's mass rate and velocity.
void write_feed(const station::Scene& sc, const station::RunSettings& s, Deck& d, std::string& o) {
  const World& w = *sc.world;
  const auto& ins = w.inserters().at(static_cast<std::size_t>(sc.inserter));
  const Vec3 lo = ins.region.lo, hi = ins.region.hi;
  TriangleMesh face = TriangleMesh::from_soup(
      {{Vec3(lo.x(), lo.y(), lo.z()), Vec3(hi.x(), lo.y(), lo.z()), Vec3(hi.x(), lo.y(), hi.z())},
       {Vec3(lo.x(), lo.y(), lo.z()), Vec3(hi.x(), lo.y(), hi.z()), Vec3(lo.x(), lo.y(), hi.z())}},
      "feed face");
  d.files["meshes/feed_face.stl"] = ascii_stl(face, "feed_face");
  o += "fix feed_face all mesh/surface/planar file meshes/feed_face.stl type 1\n";
  const double r = ins.radius_max;
  o += fmt::format("fix feed_sphere all particletemplate/sphere {} atom_type 1 density constant {} radius constant {}\n",
                   prime_seed(s.seed, 0), num(w.materials().material(0).density), num(r));
  o += fmt::format("fix feed_psd all particledistribution/discrete {} 1 feed_sphere 1.0\n", prime_seed(s.seed, 1));
  // The total is what the run can use at most; the rate is the condition's.
  const double total = ins.mass_rate * (static_cast<double>(d.steps) * sc.dt + 1.0);
  o += fmt::format("fix feed all insert/stream seed {} distributiontemplate feed_psd maxattempt {} mass {} massrate {} "
                   "overlapcheck yes vel constant {} insertion_face feed_face extrude_length {}\n",
                   prime_seed(s.seed, 2), ins.max_attempts, num(total), num(ins.mass_rate), vec(ins.velocity),
                   num(hi.y() - lo.y()));
}

// The feeder relaxation (feeder_relaxation.h) as `fix addforce` with atom-style variables.
void write_feeder_relaxation(const station::FeederRelaxation& fr, std::string& o) {
  if (!(fr.rate > 0.0)) return;
  const Vec3 T = fr.belt.tangent_point, A = fr.belt.along, U = fr.belt.up;
  o += fmt::format("# feeder relaxation F = m k (V_b t - v) in the zone{} (dem/station/feeder_relaxation.h)\n",
                   fr.all_components ? ", every component" : ", a falling particle keeping its fall");
  o += fmt::format("variable fr_s atom (x-({}))*({})+(y-({}))*({})\n", num(T.x()), num(A.x()), num(T.y()), num(A.y()));
  o += fmt::format("variable fr_h atom (x-({}))*({})+(y-({}))*({})\n", num(T.x()), num(U.x()), num(T.y()), num(U.y()));
  o += fmt::format("variable fr_in atom (v_fr_s>={})*(v_fr_s<={})*(v_fr_h<={})\n", num(fr.s_begin), num(fr.s_end),
                   num(fr.h_max));
  o += fmt::format("variable fr_vn atom vx*({})+vy*({})\n", num(U.x()), num(U.y()));
  // A falling particle keeps its fall, unless the dataset's feeder relaxed every component.
  o += fr.all_components ? "variable fr_fall atom 0\n" : "variable fr_fall atom v_fr_vn*(v_fr_vn<0)\n";
  o += fmt::format("variable fr_fx atom mass*{}*v_fr_in*({}-vx+v_fr_fall*({}))\n", num(fr.rate),
                   num(fr.belt_speed * A.x()), num(U.x()));
  o += fmt::format("variable fr_fy atom mass*{}*v_fr_in*({}-vy+v_fr_fall*({}))\n", num(fr.rate),
                   num(fr.belt_speed * A.y()), num(U.y()));
  o += fmt::format("variable fr_fz atom -mass*{}*v_fr_in*vz\n", num(fr.rate));
  o += "fix feeder all addforce v_fr_fx v_fr_fy v_fr_fz\n";
}

// The outputs: the plate's load every sample, the particle count every snapshot, the dump of the
// sensors' region every sample; then the run.
void write_outputs(const Deck& d, const std::string& plate_id, std::string& o) {
  const long long ns = d.steps_per_sample;
  o += fmt::format("fix dt_check all check/timestep/gran {} 0.2 0.1\n", ns * d.samples_per_snapshot * 10);
  o += fmt::format("fix plate_load all ave/time 1 {} {} f_{}[1] f_{}[2] f_{}[3] f_{}[4] f_{}[5] f_{}[6] file {}\n", ns, ns,
                   plate_id, plate_id, plate_id, plate_id, plate_id, plate_id, Deck::plate_file);
  o += "thermo_style custom step atoms\n";
  o += fmt::format("thermo {}\nthermo_modify lost ignore norm no\n", ns * d.samples_per_snapshot);
  o += fmt::format("dump sensors all custom {} {} id x y z vx vy vz mass\n", ns, Deck::dump_file);
  o += fmt::format("dump_modify sensors thresh x > {}\n", num(d.dump_x_min));
  o += fmt::format("run {}\n", d.steps);
}

}  // namespace

Deck make_deck(const Station& st, const station::Scene& sc, const station::RunSettings& s, double sim_time) {
  check_scene(sc, s);
  Deck d;
  schedule(sc, s, sim_time, d);
  std::string& o = d.input;
  write_box(st, sc, d, o);
  write_contact_model(sc, s, o);
  const std::string plate_id = write_walls(sc, s, d, o);
  write_feed(sc, s, d, o);
  o += "fix integrate all nve/sphere\n";
  write_feeder_relaxation(sc.feeder, o);
  write_outputs(d, plate_id, o);
  return d;
}

void write_deck(const Deck& d, const std::string& dir) {
  namespace fs = std::filesystem;
  fs::create_directories(fs::path(dir) / "meshes");
  auto put = [&](const std::string& rel, const std::string& text) {
    std::ofstream f(fs::path(dir) / rel, std::ios::binary);
    f << text;
    if (!f) throw InputError((fs::path(dir) / rel).string(), 0, "", "cannot write the LIGGGHTS deck");
  };
  put(Deck::input_file, d.input);
  for (const auto& [rel, text] : d.files) put(rel, text);
}

}  // namespace chutelab::dem::liggghts
