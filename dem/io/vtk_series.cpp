#include "dem/io/vtk_series.h"

#include <bit>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>

#include <fmt/format.h>

#include "core/input_error.h"

namespace chutelab::dem {
namespace {

static_assert(std::endian::native == std::endian::little, "the .vtp files declare LittleEndian");

// The appended block: for each array, a UInt64 byte count then the raw values.
class Appended {
 public:
  // Adds one array; returns its offset (what the DataArray's offset attribute says).
  template <class T>
  std::size_t add(const std::vector<T>& v) {
    const std::size_t at = bytes_.size();
    const std::uint64_t n = v.size() * sizeof(T);
    put(&n, sizeof n);
    if (n) put(v.data(), n);
    return at;
  }
  const std::string& bytes() const { return bytes_; }

 private:
  void put(const void* p, std::size_t n) {
    const auto* c = static_cast<const char*>(p);
    bytes_.append(c, n);
  }
  std::string bytes_;
};

std::vector<double> flat(const std::vector<Vec3>& a) {
  std::vector<double> o;
  o.reserve(3 * a.size());
  for (const auto& v : a) o.insert(o.end(), {v.x(), v.y(), v.z()});
  return o;
}

}  // namespace

void write_vtp_particles(const std::string& path, const Particles& p, const std::vector<double>& contact_force) {
  const std::size_t n = p.size();
  if (contact_force.size() != n) throw InputError(path, 0, "", "contact forces do not match the particles");
  Appended data;
  std::string arrays;
  auto array = [&](std::string_view type, std::string_view name, int components, std::size_t offset) {
    arrays += fmt::format("        <DataArray type=\"{}\" Name=\"{}\" NumberOfComponents=\"{}\" format=\"appended\" "
                          "offset=\"{}\"/>\n",
                          type, name, components, offset);
  };
  std::vector<double> speed(n);
  for (std::size_t i = 0; i < n; ++i) speed[i] = p.v[i].norm();
  std::vector<std::int64_t> clump(p.clump.begin(), p.clump.end());
  std::vector<std::int64_t> connectivity(n), offsets(n);
  for (std::size_t i = 0; i < n; ++i) connectivity[i] = static_cast<std::int64_t>(i), offsets[i] = static_cast<std::int64_t>(i + 1);

  std::string point_data;
  arrays.clear();
  array("Int64", "id", 1, data.add(p.id));
  array("Int64", "clump", 1, data.add(clump));
  std::vector<double> radius_mm(p.radius.begin(), p.radius.end());
  for (auto& r : radius_mm) r *= 1e3;
  array("Float64", "radius_mm", 1, data.add(radius_mm));
  array("Float64", "velocity_mps", 3, data.add(flat(p.v)));
  array("Float64", "speed_mps", 1, data.add(speed));
  array("Float64", "contact_force_N", 1, data.add(contact_force));
  point_data = arrays;
  arrays.clear();
  std::vector<double> points_mm = flat(p.x);
  for (auto& x : points_mm) x *= 1e3;
  array("Float64", "Points", 3, data.add(points_mm));
  const std::string points = arrays;
  arrays.clear();
  array("Int64", "connectivity", 1, data.add(connectivity));
  array("Int64", "offsets", 1, data.add(offsets));
  const std::string verts = arrays;

  std::ofstream f(path, std::ios::binary);
  if (!f) throw InputError(path, 0, "particle series", "cannot write this file");
  f << "<?xml version=\"1.0\"?>\n"
       "<!-- chutelab DEM particles: Points and radius_mm in mm, velocities in m/s, forces in N -->\n"
       "<VTKFile type=\"PolyData\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n"
       "  <PolyData>\n"
    << fmt::format("    <Piece NumberOfPoints=\"{}\" NumberOfVerts=\"{}\" NumberOfLines=\"0\" NumberOfStrips=\"0\" "
                   "NumberOfPolys=\"0\">\n",
                   n, n)
    << "      <PointData Scalars=\"radius_mm\" Vectors=\"velocity_mps\">\n"
    << point_data << "      </PointData>\n      <Points>\n"
    << points << "      </Points>\n      <Verts>\n"
    << verts << "      </Verts>\n    </Piece>\n  </PolyData>\n  <AppendedData encoding=\"raw\">\n   _";
  f.write(data.bytes().data(), static_cast<std::streamsize>(data.bytes().size()));
  f << "\n  </AppendedData>\n</VTKFile>\n";
  if (!f) throw InputError(path, 0, "particle series", "error while writing this file");
}

VtkSeries::VtkSeries(std::string dir, std::string name) : dir_(std::move(dir)), name_(std::move(name)) {
  std::filesystem::create_directories(dir_);
}

void VtkSeries::write(double t, const Particles& p, const std::vector<double>& contact_force) {
  namespace fs = std::filesystem;
  const std::string file = fmt::format("{}_{:05d}.vtp", name_, times_.size());
  write_vtp_particles((fs::path(dir_) / file).string(), p, contact_force);
  times_.push_back(t);
  files_.push_back(file);
  // The collection, whole after every frame (written aside, then renamed over the old one).
  const fs::path pvd = fs::path(dir_) / (name_ + ".pvd"), tmp = fs::path(dir_) / (name_ + ".pvd.part");
  {
    std::ofstream f(tmp);
    if (!f) throw InputError(tmp.string(), 0, "particle series", "cannot write this file");
    f << "<?xml version=\"1.0\"?>\n<!-- chutelab DEM particles: timestep in s; lengths in mm -->\n<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
         "  <Collection>\n";
    for (std::size_t k = 0; k < times_.size(); ++k)
      f << fmt::format("    <DataSet timestep=\"{:.9g}\" group=\"\" part=\"0\" file=\"{}\"/>\n", times_[k], files_[k]);
    f << "  </Collection>\n</VTKFile>\n";
    if (!f) throw InputError(tmp.string(), 0, "particle series", "error while writing this file");
  }
  fs::rename(tmp, pvd);
}

}  // namespace chutelab::dem
