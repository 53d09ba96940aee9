// chutelab side of bench/dem_vs_liggghts: a dense bed of ~20 000 spheres (Hertz-Mindlin with tangential
// history and constant-torque rolling friction, 9 mm polyethylene-like pellets, dt = 3e-5 s) in a box of
// five planes. Modes:
//   settle  --out FILE.ckpt --data FILE.data   pour from a loose lattice and settle; write the state as
//                                              a chutelab checkpoint and as a LIGGGHTS data file
//   run     --data FILE.data | --in FILE.ckpt  --steps N --threads T   time N steps from the settled
//           state (the data file is what LIGGGHTS reads: same numbers, no contact history); prints psps
//   chute-init --out FILE.data              the starting lattice of the LAMMPS chute anchor
//           (bench/lammps_chute): a rough frozen base and 31 200 free spheres, LAMMPS data format
//   chute   --data FILE.data --steps N --threads T   chutelab's equivalent of LAMMPS's own in.chute on
//           the state LAMMPS wrote (see make_chute_world); prints psps like run
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

#include <fmt/format.h>
#include <omp.h>

#include "dem/world.h"

using namespace chutelab::dem;

namespace {

struct Params {
  int particles = 20000;
  double box = 0.2;        // m, square base side
  double radius = 4.5e-3;  // m (9 mm spheres, +-5 % uniform so the bed does not crystallise)
  double dt = 3e-5;        // s (the reference study's LIGGGHTS virtual rig)
  double skin = 1.0e-3;    // m, Verlet skin (same in LIGGGHTS: neighbor 0.001 bin)
  double settle_time = 0.35;
  int threads = 1;
  std::int64_t steps = 2000;
  std::string in, out, data;
  RollingModel rolling = RollingModel::constant_torque;
  bool fresh_contacts = false;
  int ke_every = 0;  // print kinetic energy every N steps (physics cross-check against LIGGGHTS)  // start without contact history, like LIGGGHTS reading a data file
  TangentialModel tangential = TangentialModel::coulomb_history;
};

World make_world(const Params& P, bool add_particles) {
  Settings s;
  s.dt = P.dt;
  s.skin = P.skin;
  s.threads = P.threads;
  s.gravity = Vec3(0, 0, -9.81);
  s.normal = NormalLaw::of<HertzMindlin>();
  s.tangential = P.tangential;
  s.rolling = P.rolling;
  s.domain = Box{Vec3(-0.01, -0.01, -0.01), Vec3(P.box + 0.01, P.box + 0.01, 2.0)};
  World w(s);
  // The reference study's material (polyethylene pellets, LIGGGHTS rig modulus) and steel walls.
  const int pe = w.materials().add({"pellet", 2.5e7, 0.38, 1000});
  const int steel = w.materials().add({"steel", 2.0e11, 0.30, 7800});
  Interaction pp, pw;
  pp.friction = 0.3;
  pp.rolling_friction = 0.1;
  pp.restitution = 0.7;
  pw.friction = 0.27;
  pw.rolling_friction = 0.1;
  pw.restitution = 0.66;
  w.materials().set_interaction(pe, pe, pp);
  w.materials().set_interaction(pe, steel, pw);
  w.materials().set_interaction(steel, steel, pw);
  w.add_wall(Wall::plane("floor", Vec3(0, 0, 0), Vec3::UnitZ(), steel));
  w.add_wall(Wall::plane("x0", Vec3(0, 0, 0), Vec3::UnitX(), steel));
  w.add_wall(Wall::plane("x1", Vec3(P.box, 0, 0), -Vec3::UnitX(), steel));
  w.add_wall(Wall::plane("y0", Vec3(0, 0, 0), Vec3::UnitY(), steel));
  w.add_wall(Wall::plane("y1", Vec3(0, P.box, 0), -Vec3::UnitY(), steel));
  if (add_particles) {
    const double rmax = 1.05 * P.radius;
    const double pitch = 2.0 * rmax * 1.04;
    const int per_row = static_cast<int>(std::floor((P.box - 2 * rmax) / pitch)) + 1;
    std::uint64_t seed = 2024;
    for (int k = 0; k < P.particles; ++k) {
      const int ix = k % per_row, iy = (k / per_row) % per_row, iz = k / (per_row * per_row);
      Vec3 x(rmax + ix * pitch, rmax + iy * pitch, rmax + iz * pitch);
      x.x() += 0.02 * P.radius * (uniform01(seed) - 0.5);
      x.y() += 0.02 * P.radius * (uniform01(seed) - 0.5);
      const double r = P.radius * (0.95 + 0.1 * uniform01(seed));
      w.add_particle({x, Vec3(0, 0, -0.5), Vec3::Zero(), r, pe});
    }
  }
  return w;
}

void write_liggghts_data(const std::string& path, const World& w, const Params& P) {
  std::ofstream f(path);
  const auto& p = w.particles();
  f << "LIGGGHTS data file written by chutelab dem_bench (settled bed)\n\n";
  f << p.size() << " atoms\n2 atom types\n\n";
  f << fmt::format("{:.9g} {:.9g} xlo xhi\n{:.9g} {:.9g} ylo yhi\n{:.9g} {:.9g} zlo zhi\n\n", -0.01, P.box + 0.01, -0.01,
                   P.box + 0.01, -0.01, 2.0);
  // atom_style granular: atom-ID atom-type diameter density x y z
  f << "Atoms\n\n";
  for (std::size_t i = 0; i < p.size(); ++i) {
    const double rho = p.mass[i] / (4.0 / 3.0 * M_PI * std::pow(p.radius[i], 3));
    f << fmt::format("{} 1 {:.17g} {:.17g} {:.17g} {:.17g} {:.17g}\n", i + 1, 2 * p.radius[i], rho, p.x[i].x(), p.x[i].y(),
                     p.x[i].z());
  }
  f << "\nVelocities\n\n";  // atom-ID vx vy vz wx wy wz
  for (std::size_t i = 0; i < p.size(); ++i)
    f << fmt::format("{} {:.17g} {:.17g} {:.17g} {:.17g} {:.17g} {:.17g}\n", i + 1, p.v[i].x(), p.v[i].y(), p.v[i].z(),
                     p.w[i].x(), p.w[i].y(), p.w[i].z());
}

// Reads the bed back from the LIGGGHTS data file, so that both codes start from the same numbers
// (positions, velocities, spins, diameters, densities; no contact history).
void read_liggghts_data(const std::string& path, World& w) {
  std::ifstream f(path);
  if (!f) throw std::runtime_error("cannot open " + path);
  std::string line;
  std::size_t n = 0;
  std::vector<ParticleSpec> specs;
  while (std::getline(f, line)) {
    if (line.find(" atoms") != std::string::npos && n == 0) n = std::stoul(line);
    if (line.rfind("Atoms", 0) == 0) {
      specs.resize(n);
      std::getline(f, line);
      for (std::size_t k = 0; k < n; ++k) {
        std::getline(f, line);
        std::istringstream in(line);
        std::size_t id;
        int type;
        double d, rho, x, y, z;
        in >> id >> type >> d >> rho >> x >> y >> z;
        specs.at(id - 1) = ParticleSpec{Vec3(x, y, z), Vec3::Zero(), Vec3::Zero(), 0.5 * d, 0, rho};
      }
    }
    if (line.rfind("Velocities", 0) == 0) {
      std::getline(f, line);
      for (std::size_t k = 0; k < n; ++k) {
        std::getline(f, line);
        std::istringstream in(line);
        std::size_t id;
        double vx, vy, vz, wx, wy, wz;
        in >> id >> vx >> vy >> vz >> wx >> wy >> wz;
        specs.at(id - 1).velocity = Vec3(vx, vy, vz);
        specs.at(id - 1).omega = Vec3(wx, wy, wz);
      }
    }
  }
  if (specs.empty()) throw std::runtime_error("no atoms in " + path);
  for (const auto& sp : specs) w.add_particle(sp);
}


// --- LAMMPS chute anchor (bench/lammps_chute) ------------------------------------------------------
// LAMMPS's in.chute in reduced units read as SI: d = 1 m, density 1 kg/m^3, g = 1 m/s^2 tilted
// 26 degrees down the chute (+x), dt = 1e-4 s, skin 0.1 m; gran/hooke/history with k_n = 2e5 N/m,
// k_t = 2/7 k_n, gamma_n = 50 1/s, mu = 0.5, no tangential damping; base atoms (type 2) frozen.
// chutelab's equivalent, and where it differs:
//   - linear spring-dashpot with tangential history (the reference study's Eq 8). LAMMPS' damping force is
//     m* gamma_n v_n; chutelab's is 2 zeta sqrt(k_n m*) v_n. zeta is set so the two agree for two
//     free spheres (m* = m/2); against the base (m* = m) chutelab damps 1/sqrt(2) as much. The
//     tangential spring keeps chutelab's damping at the same ratio (LAMMPS: none, dampflag 0).
//   - frozen base: spheres 1e12 times denser whose gravity is cancelled by the body-force hook
//     (they move less than 1e-12 m in a run); base-base pairs are in chutelab's list (LAMMPS excludes
//     them; ~2 % of the pairs).
//   - LAMMPS is periodic in x and y; chutelab has no periodic boundaries, so four side planes half a
//     diameter outside the periodic box close it (a grain wrapped to x = 0.1 must not start inside
//     a wall). Over the timed 0.1 s the grains move about a fifth of a diameter.
constexpr double kChuteAngle = 26.0;  // degrees
constexpr double kChuteLx = 40.0, kChuteLy = 20.0;

void write_chute_lattice(const std::string& path) {
  std::ofstream f(path);
  std::uint64_t seed = 1977;
  struct A { int type; double x, y, z; };
  std::vector<A> atoms;
  // Rough base: a square lattice of spacing 1 jittered by up to 0.3 in height.
  for (int iy = 0; iy < 20; ++iy)
    for (int ix = 0; ix < 40; ++ix) atoms.push_back({2, ix + 0.5, iy + 0.5, 0.5 + 0.3 * uniform01(seed)});
  // Free spheres on a loose lattice above it (spacing 1.05: no overlaps).
  const double a = 1.05;
  const int nx = 38, ny = 19;
  for (int k = 0; atoms.size() < 32000; ++k) {
    const int ix = k % nx, iy = (k / nx) % ny, iz = k / (nx * ny);
    atoms.push_back({1, 0.5 + ix * a + 0.01 * uniform01(seed), 0.5 + iy * a + 0.01 * uniform01(seed), 2.0 + iz * a});
  }
  f << "LAMMPS data file written by chutelab dem_bench chute-init\n\n" << atoms.size() << " atoms\n2 atom types\n\n";
  f << fmt::format("0 {} xlo xhi\n0 {} ylo yhi\n0 {} zlo zhi\n\nAtoms # sphere\n\n", kChuteLx, kChuteLy, 60.0);
  for (std::size_t i = 0; i < atoms.size(); ++i)
    f << fmt::format("{} {} 1 1 {:.9g} {:.9g} {:.9g}\n", i + 1, atoms[i].type, atoms[i].x, atoms[i].y, atoms[i].z);
}

struct ChuteAtom {
  int type = 1;
  ParticleSpec spec;
};

// Reads a LAMMPS data file (atom_style sphere: id type diameter density x y z [ix iy iz]; optional
// Velocities: id vx vy vz wx wy wz), unwrapping periodic images is not needed (positions only).
std::vector<ChuteAtom> read_chute_data(const std::string& path) {
  std::ifstream f(path);
  if (!f) throw std::runtime_error("cannot open " + path);
  std::string line;
  std::size_t n = 0;
  std::vector<ChuteAtom> atoms;
  while (std::getline(f, line)) {
    if (n == 0 && line.find(" atoms") != std::string::npos) n = std::stoul(line);
    if (line.rfind("Atoms", 0) == 0) {
      atoms.resize(n);
      std::getline(f, line);
      for (std::size_t k = 0; k < n; ++k) {
        std::getline(f, line);
        std::istringstream in(line);
        std::size_t id;
        ChuteAtom a;
        double d, rho, x, y, z;
        in >> id >> a.type >> d >> rho >> x >> y >> z;
        a.spec = ParticleSpec{Vec3(x, y, z), Vec3::Zero(), Vec3::Zero(), 0.5 * d, a.type == 2 ? 1 : 0, rho};
        atoms.at(id - 1) = a;
      }
    }
    if (line.rfind("Velocities", 0) == 0) {
      std::getline(f, line);
      for (std::size_t k = 0; k < n; ++k) {
        std::getline(f, line);
        std::istringstream in(line);
        std::size_t id;
        double vx, vy, vz, wx, wy, wz;
        in >> id >> vx >> vy >> vz >> wx >> wy >> wz;
        if (atoms.at(id - 1).type == 2) continue;  // frozen
        atoms.at(id - 1).spec.velocity = Vec3(vx, vy, vz);
        atoms.at(id - 1).spec.omega = Vec3(wx, wy, wz);
      }
    }
  }
  if (atoms.empty()) throw std::runtime_error("no atoms in " + path);
  return atoms;
}

World make_chute_world(const std::vector<ChuteAtom>& atoms, int threads) {
  const double th = kChuteAngle * M_PI / 180.0;
  Settings s;
  s.dt = 1e-4;
  s.skin = 0.1;
  s.threads = threads;
  s.gravity = Vec3(std::sin(th), 0.0, -std::cos(th));
  s.normal = NormalLaw::of<LinearSpringDashpot>();
  s.tangential = TangentialModel::coulomb_history;
  s.rolling = RollingModel::none;
  double ztop = 0.0;
  for (const auto& a : atoms) ztop = std::max(ztop, a.spec.position.z());
  s.domain = Box{Vec3(-1.0, -1.0, -1.0), Vec3(kChuteLx + 1.0, kChuteLy + 1.0, ztop + 20.0)};
  s.on_warning = [](const std::string&) {};  // E below only sizes the (unused) Hertz time-step estimate
  World w(s);
  const int grain = w.materials().add({"grain", 1e3, 0.3, 1.0});
  const int base = w.materials().add({"base", 1e3, 0.3, 1e12});
  const int wall = w.materials().add({"side", 1e3, 0.3, 1.0});
  const double kn = 2e5, gamma_n = 50.0, m_pair = 0.5 * M_PI / 6.0;  // m* of two free unit spheres
  const double zeta = 0.5 * gamma_n * std::sqrt(m_pair / kn);
  Interaction it;
  it.friction = 0.5;
  it.law = {{"normal_stiffness", kn}, {"tangential_ratio", 2.0 / 7.0}};
  it.restitution = std::exp(-zeta * M_PI / std::sqrt(1.0 - zeta * zeta));
  for (int a : {grain, base, wall})
    for (int b : {grain, base, wall}) w.materials().set_interaction(a, b, it);
  w.add_wall(Wall::plane("x0", Vec3(-0.5, 0, 0), Vec3::UnitX(), wall));
  w.add_wall(Wall::plane("x1", Vec3(kChuteLx + 0.5, 0, 0), -Vec3::UnitX(), wall));
  w.add_wall(Wall::plane("y0", Vec3(0, -0.5, 0), Vec3::UnitY(), wall));
  w.add_wall(Wall::plane("y1", Vec3(0, kChuteLy + 0.5, 0), -Vec3::UnitY(), wall));
  for (const auto& a : atoms) {
    ParticleSpec p = a.spec;
    p.material = a.type == 2 ? base : grain;
    p.density = a.type == 2 ? 1e12 * p.density : p.density;
    w.add_particle(p);
  }
  const Vec3 g = s.gravity;
  w.set_body_force([base, g](const Particles& p, double, std::size_t b, std::size_t e, std::vector<Vec3>& f) {
    for (std::size_t i = b; i < e; ++i)
      if (p.material[i] == base) f[i] -= p.mass[i] * g;  // frozen: no weight
  });
  return w;
}

double now() { return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count(); }

// CPU time of the whole process (all threads). On a shared machine wall time includes waiting for a
// core; CPU time does not, so A/B comparisons of one-thread runs use it.
double cpu_now() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

// Peak resident set size (VmHWM) of this process, bytes; 0 if /proc is not readable.
double peak_rss_bytes() {
  std::ifstream f("/proc/self/status");
  std::string line;
  while (std::getline(f, line))
    if (line.rfind("VmHWM:", 0) == 0) return 1024.0 * std::stod(line.substr(6));  // kB
  return 0.0;
}

// FNV-1a over the bytes of every particle's state (position, velocities, force, torque, in index
// order) and every wall's load: equal hashes mean bit-identical runs, which ke's six digits do not show.
std::uint64_t state_hash(const World& w) {
  std::uint64_t h = 1469598103934665603ULL;
  auto add = [&](const void* data, std::size_t bytes) {
    const auto* b = static_cast<const unsigned char*>(data);
    for (std::size_t k = 0; k < bytes; ++k) h = (h ^ b[k]) * 1099511628211ULL;
  };
  const auto& p = w.particles();
  for (const auto* a : {&p.x, &p.v, &p.w, &p.f, &p.t}) add(a->data(), a->size() * sizeof(Vec3));
  for (const auto& wl : w.walls()) {
    add(&wl.force, sizeof(Vec3));
    add(&wl.torque, sizeof(Vec3));
  }
  return h;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: dem_bench settle|run [--particles N] [--steps N] [--threads T] [--in F] [--out F] [--data F]\n");
    return 2;
  }
  const std::string mode = argv[1];
  Params P;
  for (int a = 2; a + 1 < argc; a += 2) {
    const std::string k = argv[a], v = argv[a + 1];
    if (k == "--particles") P.particles = std::stoi(v);
    else if (k == "--steps") P.steps = std::stoll(v);
    else if (k == "--threads") P.threads = std::stoi(v);
    else if (k == "--settle-time") P.settle_time = std::stod(v);
    else if (k == "--in") P.in = v;
    else if (k == "--out") P.out = v;
    else if (k == "--data") P.data = v;
    else if (k == "--ke-every") P.ke_every = std::stoi(v);
    else if (k == "--fresh-contacts") P.fresh_contacts = v == "1";
    else if (k == "--rolling") P.rolling = v == "none" ? RollingModel::none : v == "epsd" ? RollingModel::epsd : RollingModel::constant_torque;
    else if (k == "--tangential") P.tangential = v == "none" ? TangentialModel::frictionless : TangentialModel::coulomb_history;
    else { std::fprintf(stderr, "unknown option %s\n", k.c_str()); return 2; }
  }
  if (mode == "settle") {
    P.threads = P.threads > 0 ? P.threads : omp_get_max_threads();
    World w = make_world(P, true);
    w.initialise();
    const double t0 = now();
    const auto steps = static_cast<std::int64_t>(std::llround(P.settle_time / P.dt));
    for (std::int64_t s = 0; s < steps; s += 1000) {
      w.step(std::min<std::int64_t>(1000, steps - s));
      std::fprintf(stderr, "settle t=%.3f s  KE=%.3e J  contacts=%zu  (%.1f s wall)\n", w.time(), w.energy().translational,
                   w.contact_count(), now() - t0);
    }
    w.save_checkpoint(P.out);
    if (!P.data.empty()) write_liggghts_data(P.data, w, P);
    double top = 0;
    for (const auto& x : w.particles().x) top = std::max(top, x.z());
    std::printf("settled %zu particles, bed top %.4f m, %zu contacts, %zu wall contacts\n", w.particles().size(), top,
                w.contact_count(), w.wall_contact_count());
    return 0;
  }
  if (mode == "run") {
    const double rss0 = peak_rss_bytes();  // program, libraries and the empty World: the baseline
    World w = make_world(P, false);
    if (!P.data.empty()) {
      read_liggghts_data(P.data, w);
      w.initialise();
    } else {
      w.load_checkpoint(P.in);
      if (P.fresh_contacts) w.reset_contact_history();
    }
    if (P.ke_every > 0) {
      for (std::int64_t s = 0; s <= P.steps; s += P.ke_every) {
        std::printf("step %lld ke %.8g\n", static_cast<long long>(s), w.energy().translational);
        if (s < P.steps) w.step(P.ke_every);
      }
      return 0;
    }
    const std::int64_t r0 = w.rebuild_count();
    const double t0 = now(), c0 = cpu_now();
    w.step(P.steps);
    const double t1 = now(), c1 = cpu_now();
    const double psps = static_cast<double>(w.particles().size()) * static_cast<double>(P.steps) / (t1 - t0);
    // Memory per particle: peak RSS after the run minus the baseline before the World existed. It
    // includes the data-file reader's temporary ParticleSpec list (~100 B per particle, freed but
    // counted by the peak), so it is an upper bound on the engine's own footprint.
    const double bytes_per_particle = (peak_rss_bytes() - rss0) / static_cast<double>(w.particles().size());
    std::printf("threads=%d particles=%zu steps=%lld seconds=%.3f cpu_s=%.3f rebuilds=%lld pairs=%zu contacts=%zu "
                "ke=%.6g bytes_per_particle=%.0f psps=%.0f state=%016llx\n",
                P.threads, w.particles().size(), static_cast<long long>(P.steps), t1 - t0, c1 - c0,
                static_cast<long long>(w.rebuild_count() - r0), w.neighbor_pair_count(), w.contact_count(),
                w.energy().translational, bytes_per_particle, psps, static_cast<unsigned long long>(state_hash(w)));
    return 0;
  }
  if (mode == "chute-init") {
    write_chute_lattice(P.out);
    return 0;
  }
  if (mode == "chute") {
    const double rss0 = peak_rss_bytes();
    World w = make_chute_world(read_chute_data(P.data), P.threads);
    w.initialise();
    const std::int64_t r0 = w.rebuild_count();
    const double t0 = now(), c0 = cpu_now();
    w.step(P.steps);
    const double t1 = now(), c1 = cpu_now();
    double ke = 0.0;
    const auto& p = w.particles();
    for (std::size_t i = 0; i < p.size(); ++i)
      if (p.material[i] == 0) ke += 0.5 * p.mass[i] * p.v[i].squaredNorm();
    std::printf("threads=%d particles=%zu steps=%lld seconds=%.3f cpu_s=%.3f rebuilds=%lld pairs=%zu contacts=%zu "
                "ke=%.6g bytes_per_particle=%.0f psps=%.0f state=%016llx\n",
                P.threads, p.size(), static_cast<long long>(P.steps), t1 - t0, c1 - c0,
                static_cast<long long>(w.rebuild_count() - r0), w.neighbor_pair_count(), w.contact_count(), ke,
                (peak_rss_bytes() - rss0) / static_cast<double>(p.size()),
                static_cast<double>(p.size()) * static_cast<double>(P.steps) / (t1 - t0),
                static_cast<unsigned long long>(state_hash(w)));
    return 0;
  }
  std::fprintf(stderr, "unknown mode %s\n", mode.c_str());
  return 2;
}
