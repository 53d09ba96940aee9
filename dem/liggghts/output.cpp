#include "dem/liggghts/output.h"

#include <sstream>

#include <fmt/format.h>

#include "core/input_error.h"
#include "core/number.h"

namespace chutelab::dem::liggghts {
namespace {

std::vector<std::string> words(const std::string& s) {
  std::istringstream is(s);
  std::vector<std::string> w;
  for (std::string t; is >> t;) w.push_back(t);
  return w;
}

}  // namespace

std::vector<PlateSample> read_plate_file(const std::string& path) {
  std::ifstream f(path);
  if (!f) throw InputError(path, 0, "", "LIGGGHTS wrote no plate load file (did the run start?)");
  std::vector<PlateSample> out;
  std::string line;
  long n = 0;
  while (std::getline(f, line)) {
    ++n;
    const auto w = words(line);
    if (w.empty() || w[0][0] == '#') continue;
    if (w.size() != 7) throw InputError(path, n, "", fmt::format("expected 7 columns (step, force, torque), found {}", w.size()));
    PlateSample s;
    double v[7];
    for (int k = 0; k < 7; ++k) {
      const auto d = parse_number(w[static_cast<std::size_t>(k)]);
      if (!d) throw InputError(path, n, "", fmt::format("'{}' is not a number", w[static_cast<std::size_t>(k)]));
      v[k] = *d;
    }
    s.step = static_cast<long long>(std::llround(v[0]));
    s.force = Vec3(v[1], v[2], v[3]);
    s.torque = Vec3(v[4], v[5], v[6]);
    out.push_back(s);
  }
  return out;
}

DumpReader::DumpReader(std::string path) : path_(std::move(path)), in_(path_) {
  if (!in_) throw InputError(path_, 0, "", "LIGGGHTS wrote no particle dump (did the run start?)");
}

void DumpReader::fail(const std::string& what) const { throw InputError(path_, line_, "", what); }

bool DumpReader::next(Frame& f) {
  std::string line;
  auto get = [&]() {
    if (!std::getline(in_, line)) fail("the dump ends inside a frame");
    ++line_;
  };
  if (!std::getline(in_, line)) return false;
  ++line_;
  if (line.rfind("ITEM: TIMESTEP", 0) != 0) fail("expected 'ITEM: TIMESTEP'");
  get();
  const auto step = parse_number(line);
  if (!step) fail("the time step is not a number");
  f.step = static_cast<long long>(std::llround(*step));
  get();
  if (line.rfind("ITEM: NUMBER OF ATOMS", 0) != 0) fail("expected 'ITEM: NUMBER OF ATOMS'");
  get();
  const auto n_atoms = parse_number(line);
  if (!n_atoms || *n_atoms < 0) fail("the number of atoms is not a count");
  const auto n = static_cast<std::size_t>(std::llround(*n_atoms));
  get();
  if (line.rfind("ITEM: BOX BOUNDS", 0) != 0) fail("expected 'ITEM: BOX BOUNDS'");
  for (int k = 0; k < 3; ++k) get();
  get();
  if (line.rfind("ITEM: ATOMS", 0) != 0) fail("expected 'ITEM: ATOMS'");
  const auto cols = words(line.substr(11));
  int c_id = -1, c_x = -1, c_y = -1, c_z = -1, c_vx = -1, c_vy = -1, c_vz = -1, c_m = -1;
  for (int k = 0; k < static_cast<int>(cols.size()); ++k) {
    const std::string& c = cols[static_cast<std::size_t>(k)];
    int* slot = c == "id" ? &c_id : c == "x" ? &c_x : c == "y" ? &c_y : c == "z" ? &c_z : c == "vx" ? &c_vx
              : c == "vy" ? &c_vy : c == "vz" ? &c_vz : c == "mass" ? &c_m : nullptr;
    if (slot) *slot = k;
  }
  for (int c : {c_id, c_x, c_y, c_z, c_vx, c_vy, c_vz, c_m})
    if (c < 0) fail("the dump needs the columns id x y z vx vy vz mass");
  f.id.resize(n);
  f.x.resize(n);
  f.v.resize(n);
  f.mass.resize(n);
  std::vector<double> val(cols.size());
  for (std::size_t i = 0; i < n; ++i) {
    get();
    std::istringstream is(line);
    for (auto& v : val)
      if (!(is >> v)) fail(fmt::format("expected {} numbers per particle", cols.size()));
    if (!(val[static_cast<std::size_t>(c_id)] >= 0)) fail("negative particle id");
    f.id[i] = static_cast<std::int64_t>(std::llround(val[static_cast<std::size_t>(c_id)]));
    auto at = [&](int c) { return val[static_cast<std::size_t>(c)]; };
    f.x[i] = Vec3(at(c_x), at(c_y), at(c_z));
    f.v[i] = Vec3(at(c_vx), at(c_vy), at(c_vz));
    f.mass[i] = at(c_m);
  }
  return true;
}

LogSummary read_log(const std::string& path) {
  LogSummary s;
  std::ifstream f(path);
  if (!f) return s;
  std::string line;
  bool thermo = false;
  while (std::getline(f, line)) {
    if (s.version.empty() && line.rfind("LIGGGHTS (Version", 0) == 0) s.version = line;
    if (s.error.empty() && line.rfind("ERROR", 0) == 0) s.error = line;
    const auto w = words(line);
    if (w.size() >= 2 && w[0] == "Step" && w[1] == "Atoms") {
      thermo = true;
      continue;
    }
    if (thermo) {
      const auto step = w.size() >= 2 ? parse_number(w[0]) : std::nullopt;
      const auto atoms = w.size() >= 2 ? parse_number(w[1]) : std::nullopt;
      if (step && atoms) {
        s.final_atoms = static_cast<std::size_t>(*atoms);
        s.peak_atoms = std::max(s.peak_atoms, s.final_atoms);
      } else if (line.rfind("Loop time", 0) == 0) {
        thermo = false;
      }
    }
    // " - a total of N particle templates (mass M) inserted so far."
    const auto p = line.find("(mass ");
    if (line.find("inserted so far") != std::string::npos && p != std::string::npos) {
      const auto e = line.find(')', p);
      if (const auto m = parse_number(line.substr(p + 6, e - p - 6))) s.inserted_mass = *m;
    }
  }
  return s;
}

}  // namespace chutelab::dem::liggghts
