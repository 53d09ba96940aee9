// Binary checkpoint of a World's dynamic state (everything the next step reads), so that a restarted
// run continues bit-identically. The scene definition (materials, walls, inserters, sinks, settings)
// is rebuilt by the caller and checked against the file.
#include <cstring>
#include <fstream>
#include <type_traits>

#include <fmt/format.h>

#include "core/input_error.h"
#include "dem/world.h"

namespace chutelab::dem {
namespace {

constexpr char kMagic[8] = {'C', 'H', 'L', 'D', 'E', 'M', 'C', 'K'};
// Raised whenever the layout changes, so that a checkpoint of another layout is refused by name and
// never misread (what each value changed: `git log -S kVersion -- dem/checkpoint.cpp`).
constexpr std::uint32_t kVersion = 4;

struct Writer {
  std::ofstream out;
  template <class T>
  void pod(const T& v) {
    static_assert(std::is_trivially_copyable_v<T> || std::is_same_v<T, Vec3>);  // Vec3 is three doubles
    out.write(reinterpret_cast<const char*>(&v), sizeof v);
  }
  template <class T>
  void vec(const std::vector<T>& v) {
    pod(static_cast<std::uint64_t>(v.size()));
    if (!v.empty()) out.write(reinterpret_cast<const char*>(v.data()), static_cast<std::streamsize>(v.size() * sizeof(T)));
  }
};

struct Reader {
  std::ifstream in;
  std::string path;
  template <class T>
  void pod(T& v, const char* what) {
    in.read(reinterpret_cast<char*>(&v), sizeof v);
    if (!in) throw InputError(path, 0, what, "checkpoint is truncated");
  }
  template <class T>
  void vec(std::vector<T>& v, const char* what) {
    std::uint64_t n = 0;
    pod(n, what);
    if (n > (1ULL << 36)) throw InputError(path, 0, what, "checkpoint array size is corrupt");
    v.resize(n);
    if (n) in.read(reinterpret_cast<char*>(v.data()), static_cast<std::streamsize>(n * sizeof(T)));
    if (!in) throw InputError(path, 0, what, "checkpoint is truncated");
  }
};

}  // namespace

void World::save_checkpoint(const std::string& path) const {
  const NeighborList& pairs = contacts_.pairs;
  const WallContactList& wall_list = contacts_.walls;
  const ContactLists::Reference& ref = contacts_.reference;
  Writer w{std::ofstream(path, std::ios::binary)};
  if (!w.out) throw InputError(path, 0, "", "cannot write checkpoint");
  w.out.write(kMagic, 8);
  w.pod(kVersion);
  w.pod(static_cast<std::int32_t>(settings_.normal.index()));
  w.pod(static_cast<std::int32_t>(settings_.tangential));
  w.pod(static_cast<std::int32_t>(settings_.rolling));
  w.pod(static_cast<std::int32_t>(materials_.size()));
  w.pod(static_cast<std::uint64_t>(walls_.size()));
  w.pod(static_cast<std::uint64_t>(sources_.inserters.size()));
  w.pod(static_cast<std::uint64_t>(sources_.sinks.size()));
  w.pod(static_cast<std::uint8_t>(initialised_));
  w.pod(clock_.time);
  w.pod(clock_.dt);
  w.pod(contacts_.skin);
  w.pod(max_speed_);
  w.pod(contacts_.max_disp);
  w.pod(clock_.step);
  w.pod(next_id_);
  w.pod(contacts_.rebuilds);
  w.pod(static_cast<std::uint8_t>(contacts_.dirty));
  w.vec(p_.x); w.vec(p_.v); w.vec(p_.w); w.vec(p_.f); w.vec(p_.t);
  w.vec(p_.radius); w.vec(p_.mass); w.vec(p_.inv_mass); w.vec(p_.inv_inertia);
  w.vec(p_.material); w.vec(p_.id);
  w.vec(pairs.row_begin); w.vec(pairs.neighbor); w.vec(pairs.shear); w.vec(pairs.roll);
  w.vec(pairs.touch);
  w.vec(wall_list.begin); w.vec(wall_list.wall); w.vec(wall_list.element);
  w.vec(wall_list.shear); w.vec(wall_list.roll); w.vec(wall_list.touch);
  w.vec(wall_list.force); w.vec(wall_list.torque); w.vec(wall_list.point);
  w.vec(ref.x); w.vec(ref.wall_time); w.vec(ref.index_map);
  for (const auto& wl : walls_) {
    w.pod(static_cast<std::uint64_t>(wl.element_count()));
    w.pod(wl.force); w.pod(wl.torque); w.vec(wl.element_force);
  }
  for (const auto& in : sources_.inserters) {
    w.pod(in.rng_state); w.pod(in.pending_mass); w.pod(in.inserted_mass); w.pod(in.next_time);
    w.pod(static_cast<std::uint8_t>(in.warned_full));
  }
  for (const auto& s : sources_.sinks) { w.pod(s.removed_mass); w.pod(s.removed_count); }
  // Clumps: member links and body state (shapes belong to the scene and are checked by count).
  w.vec(p_.clump); w.vec(p_.body_offset); w.vec(p_.contact_mass); w.vec(p_.held_by);
  w.pod(static_cast<std::uint64_t>(clumps_.shapes.size()));
  w.pod(next_clump_id_);
  const ClumpBodies& b = clumps_;
  std::vector<Vec3> q3;  // quaternion as (x, y, z) + w, stored as two arrays of trivially copyable data
  std::vector<double> qw;
  for (const auto& q : b.q) { q3.emplace_back(q.x(), q.y(), q.z()); qw.push_back(q.w()); }
  w.vec(b.x); w.vec(b.v); w.vec(q3); w.vec(qw); w.vec(b.L); w.vec(b.w); w.vec(b.f); w.vec(b.t);
  w.vec(b.mass); w.vec(b.inv_inertia); w.vec(b.member_moment); w.vec(b.shape); w.vec(b.members); w.vec(b.id);
  if (!w.out) throw InputError(path, 0, "", "error while writing checkpoint");
}

void World::load_checkpoint(const std::string& path) {
  NeighborList& pairs = contacts_.pairs;
  WallContactList& wall_list = contacts_.walls;
  ContactLists::Reference& ref = contacts_.reference;
  Reader r{std::ifstream(path, std::ios::binary), path};
  if (!r.in) throw InputError(path, 0, "", "cannot open checkpoint");
  char magic[8];
  r.in.read(magic, 8);
  if (!r.in || std::memcmp(magic, kMagic, 8) != 0) throw InputError(path, 0, "header", "not a chutelab DEM checkpoint");
  std::uint32_t version;
  r.pod(version, "version");
  if (version != kVersion) throw InputError(path, 0, "version", fmt::format("checkpoint version {} (this build reads {})", version, kVersion));
  std::int32_t nm, tm, rm, mats;
  std::uint64_t nw, ni, ns;
  r.pod(nm, "normal model"); r.pod(tm, "tangential model"); r.pod(rm, "rolling model"); r.pod(mats, "materials");
  r.pod(nw, "walls"); r.pod(ni, "inserters"); r.pod(ns, "sinks");
  auto mismatch = [&](const char* what, auto file, auto scene) {
    throw InputError(path, 0, what, fmt::format("checkpoint has {} but the scene has {}", file, scene));
  };
  if (nm != settings_.normal.index()) mismatch("normal model", nm, settings_.normal.index());
  if (tm != static_cast<std::int32_t>(settings_.tangential)) mismatch("tangential model", tm, static_cast<int>(settings_.tangential));
  if (rm != static_cast<std::int32_t>(settings_.rolling)) mismatch("rolling model", rm, static_cast<int>(settings_.rolling));
  if (mats != materials_.size()) mismatch("materials", mats, materials_.size());
  if (nw != walls_.size()) mismatch("walls", nw, walls_.size());
  if (ni != sources_.inserters.size()) mismatch("inserters", ni, sources_.inserters.size());
  if (ns != sources_.sinks.size()) mismatch("sinks", ns, sources_.sinks.size());
  std::uint8_t init, dirty;
  r.pod(init, "state");
  r.pod(clock_.time, "time"); r.pod(clock_.dt, "dt"); r.pod(contacts_.skin, "skin"); r.pod(max_speed_, "max speed");
  r.pod(contacts_.max_disp, "displacement"); r.pod(clock_.step, "step"); r.pod(next_id_, "next id"); r.pod(contacts_.rebuilds, "rebuilds");
  r.pod(dirty, "state");
  r.vec(p_.x, "x"); r.vec(p_.v, "v"); r.vec(p_.w, "w"); r.vec(p_.f, "f"); r.vec(p_.t, "t");
  r.vec(p_.radius, "radius"); r.vec(p_.mass, "mass"); r.vec(p_.inv_mass, "inv_mass"); r.vec(p_.inv_inertia, "inv_inertia");
  r.vec(p_.material, "material"); r.vec(p_.id, "id");
  const std::size_t n = p_.x.size();
  if (p_.v.size() != n || p_.w.size() != n || p_.f.size() != n || p_.t.size() != n || p_.radius.size() != n ||
      p_.mass.size() != n || p_.inv_mass.size() != n || p_.inv_inertia.size() != n || p_.id.size() != n ||
      p_.material.size() != n)
    throw InputError(path, 0, "particles", "particle arrays have different lengths");
  for (auto m : p_.material)
    if (m < 0 || m >= materials_.size()) throw InputError(path, 0, "particles", "particle material index out of range");
  r.vec(pairs.row_begin, "neighbour list"); r.vec(pairs.neighbor, "neighbour list"); r.vec(pairs.shear, "history");
  r.vec(pairs.roll, "history");
  r.vec(pairs.touch, "history");
  r.vec(wall_list.begin, "wall list"); r.vec(wall_list.wall, "wall list"); r.vec(wall_list.element, "wall list");
  r.vec(wall_list.shear, "wall history"); r.vec(wall_list.roll, "wall history"); r.vec(wall_list.touch, "wall history");
  r.vec(wall_list.force, "wall forces"); r.vec(wall_list.torque, "wall forces"); r.vec(wall_list.point, "wall forces");
  wall_list.wall_torque.resize(wall_list.point.size());  // derived in every force evaluation; not saved
  r.vec(ref.x, "reference positions"); r.vec(ref.wall_time, "wall times"); r.vec(ref.index_map, "index map");
  // The saving World listed each wall by its motion then, which the scene being restored repeats (a
  // list of an older version covers the whole skin for every wall: more than needed, still right).
  ref.wall_listed_moving.resize(walls_.size());
  for (std::size_t k = 0; k < walls_.size(); ++k) ref.wall_listed_moving[k] = walls_[k].motion.moving() ? 1 : 0;
  sources_.sink_scan.clearance.clear();  // derived at the next rebuild; until then the sinks scan every step
  if (pairs.row_begin.size() != n + 1 || wall_list.begin.size() != n + 1 || ref.x.size() != n)
    throw InputError(path, 0, "neighbour list", "sizes do not match the particle count");
  wall_list.index_owners();
  for (auto j : pairs.neighbor)
    if (j < 0 || static_cast<std::size_t>(j) >= n) throw InputError(path, 0, "neighbour list", "neighbour index out of range");
  if (pairs.row_begin.front() != 0 || static_cast<std::size_t>(pairs.row_begin.back()) != pairs.neighbor.size() ||
      pairs.shear.size() != pairs.neighbor.size() || pairs.roll.size() != pairs.neighbor.size() ||
      pairs.touch.size() != pairs.neighbor.size())
    throw InputError(path, 0, "neighbour list", "inconsistent neighbour list");
  pairs.index_slots(thread_count());
  blocks_.layout(n, kForceBlocks, thread_count(), pairs.row_begin, pairs.neighbor, wall_list.begin);
  pairs.measure_gaps(ref.x.data(), p_.radius.data(), n, thread_count());
  for (auto& wl : walls_) {
    std::uint64_t ne;
    r.pod(ne, "wall elements");
    if (ne != wl.element_count()) mismatch("wall elements", ne, wl.element_count());
    r.pod(wl.force, "wall force"); r.pod(wl.torque, "wall torque"); r.vec(wl.element_force, "wall element forces");
    wl.set_time(clock_.time);
  }
  for (auto& in : sources_.inserters) {
    std::uint8_t warned;
    r.pod(in.rng_state, "inserter"); r.pod(in.pending_mass, "inserter"); r.pod(in.inserted_mass, "inserter");
    r.pod(in.next_time, "inserter"); r.pod(warned, "inserter");
    in.warned_full = warned != 0;
  }
  for (auto& s : sources_.sinks) { r.pod(s.removed_mass, "sink"); r.pod(s.removed_count, "sink"); }
  r.vec(p_.clump, "clump links"); r.vec(p_.body_offset, "clump links"); r.vec(p_.contact_mass, "clump links");
  if (p_.clump.size() != n || p_.body_offset.size() != n || p_.contact_mass.size() != n) throw InputError(path, 0, "clumps", "clump link arrays have the wrong length");
  r.vec(p_.held_by, "held particles");
  if (p_.held_by.size() != n) throw InputError(path, 0, "held particles", "array has the wrong length");
  for (auto h : p_.held_by)
    if (h >= static_cast<std::int32_t>(sources_.inserters.size())) throw InputError(path, 0, "held particles", "inserter index out of range");
  index_held();
  std::uint64_t nshapes;
  r.pod(nshapes, "clump shapes");
  if (nshapes != clumps_.shapes.size()) mismatch("clump shapes", nshapes, clumps_.shapes.size());
  r.pod(next_clump_id_, "clumps");
  ClumpBodies& b = clumps_;
  std::vector<Vec3> q3;
  std::vector<double> qw;
  r.vec(b.x, "clumps"); r.vec(b.v, "clumps"); r.vec(q3, "clumps"); r.vec(qw, "clumps"); r.vec(b.L, "clumps");
  r.vec(b.w, "clumps"); r.vec(b.f, "clumps"); r.vec(b.t, "clumps"); r.vec(b.mass, "clumps");
  r.vec(b.inv_inertia, "clumps"); r.vec(b.member_moment, "clumps"); r.vec(b.shape, "clumps");
  r.vec(b.members, "clumps"); r.vec(b.id, "clumps");
  const std::size_t nb = b.x.size();
  if (b.v.size() != nb || q3.size() != nb || qw.size() != nb || b.L.size() != nb || b.w.size() != nb ||
      b.f.size() != nb || b.t.size() != nb || b.mass.size() != nb || b.inv_inertia.size() != nb ||
      b.member_moment.size() != nb || b.shape.size() != nb || b.members.size() != nb || b.id.size() != nb)
    throw InputError(path, 0, "clumps", "clump arrays have different lengths");
  for (auto c : p_.clump)
    if (c < -1 || c >= static_cast<std::int32_t>(nb)) throw InputError(path, 0, "clumps", "clump index out of range");
  b.q.clear();
  b.rot.clear();
  for (std::size_t c = 0; c < nb; ++c) {
    b.q.emplace_back(qw[c], q3[c].x(), q3[c].y(), q3[c].z());
    b.rot.push_back(b.q.back().toRotationMatrix());
  }
  if (settings_.dt > 0.0 && settings_.dt != clock_.dt)
    warn(fmt::format("checkpoint {} uses dt = {:.6g} s; the scene's dt {:.6g} s is ignored", path, clock_.dt, settings_.dt));
  initialised_ = init != 0;
  contacts_.dirty = dirty != 0;
}

}  // namespace chutelab::dem
