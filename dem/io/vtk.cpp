#include "dem/io/vtk.h"

#include <fstream>

#include <fmt/format.h>
#include <fmt/os.h>

#include "core/input_error.h"

namespace chutelab::dem {

void write_vtk_particles(const std::string& path, const Particles& p) {
  std::ofstream f(path);
  if (!f) throw InputError(path, 0, "", "cannot write VTK file");
  const std::size_t n = p.size();
  f << "# vtk DataFile Version 3.0\nchutelab DEM particles; lengths in mm, velocities in m/s, forces in N\n"
       "ASCII\nDATASET POLYDATA\n";
  f << fmt::format("POINTS {} double\n", n);
  for (const auto& x : p.x) f << fmt::format("{:.9g} {:.9g} {:.9g}\n", x.x() * 1e3, x.y() * 1e3, x.z() * 1e3);
  f << fmt::format("VERTICES {} {}\n", n, 2 * n);
  for (std::size_t i = 0; i < n; ++i) f << "1 " << i << '\n';
  f << fmt::format("POINT_DATA {}\n", n);
  f << "SCALARS id double 1\nLOOKUP_TABLE default\n";
  for (auto id : p.id) f << id << '\n';
  f << "SCALARS clump double 1\nLOOKUP_TABLE default\n";  // body index of a clump's spheres, -1 for free spheres
  for (auto c : p.clump) f << c << '\n';
  f << "SCALARS radius_mm double 1\nLOOKUP_TABLE default\n";
  for (double r : p.radius) f << fmt::format("{:.9g}\n", r * 1e3);
  auto vectors = [&](const char* name, const std::vector<Vec3>& a) {
    f << "VECTORS " << name << " double\n";
    for (const auto& v : a) f << fmt::format("{:.9g} {:.9g} {:.9g}\n", v.x(), v.y(), v.z());
  };
  vectors("velocity_mps", p.v);
  vectors("angular_velocity_radps", p.w);
  vectors("force_N", p.f);
  if (!f) throw InputError(path, 0, "", "error while writing VTK file");
}

void write_vtk_walls(const std::string& path, const std::vector<Wall>& walls) {
  std::vector<Vec3> pts;
  std::vector<std::vector<std::size_t>> polys;
  std::vector<Vec3> force;
  std::vector<int> wall_index;
  for (std::size_t wi = 0; wi < walls.size(); ++wi) {
    const Wall& w = walls[wi];
    if (const auto* m = std::get_if<TriangleMesh>(&w.current)) {
      const std::size_t base = pts.size();
      pts.insert(pts.end(), m->vertices.begin(), m->vertices.end());
      for (std::size_t t = 0; t < m->triangles.size(); ++t) {
        polys.push_back({base + static_cast<std::size_t>(m->triangles[t][0]), base + static_cast<std::size_t>(m->triangles[t][1]),
                         base + static_cast<std::size_t>(m->triangles[t][2])});
        force.push_back(w.element_force[t]);
        wall_index.push_back(static_cast<int>(wi));
      }
    } else if (const auto* p = std::get_if<Plane>(&w.current)) {
      // A patch: the plane's extent, or 1 m around its point when unbounded.
      const double hu = std::isfinite(p->half_u) ? p->half_u : 0.5, hv = std::isfinite(p->half_v) ? p->half_v : 0.5;
      const std::size_t base = pts.size();
      for (int k = 0; k < 4; ++k) {
        const double su = (k == 0 || k == 3) ? -1 : 1, sv = k < 2 ? -1 : 1;
        pts.push_back(p->point + su * hu * p->axis_u + sv * hv * p->axis_v);
      }
      polys.push_back({base, base + 1, base + 2, base + 3});
      force.push_back(w.force);
      wall_index.push_back(static_cast<int>(wi));
    } else {
      const auto& c = std::get<Cylinder>(w.current);
      const double a0 = std::isfinite(c.axial_min) ? c.axial_min : -0.5, a1 = std::isfinite(c.axial_max) ? c.axial_max : 0.5;
      const Vec3 trial = std::abs(c.axis.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY();
      const Vec3 u = (trial - trial.dot(c.axis) * c.axis).normalized(), v = c.axis.cross(u);
      const int seg = 36;
      const std::size_t base = pts.size();
      for (int k = 0; k < seg; ++k) {
        const double phi = 2.0 * 3.14159265358979323846 * k / seg;
        const Vec3 r = c.radius * (std::cos(phi) * u + std::sin(phi) * v);
        pts.push_back(c.point + a0 * c.axis + r);
        pts.push_back(c.point + a1 * c.axis + r);
      }
      for (int k = 0; k < seg; ++k) {
        const std::size_t a = base + 2 * static_cast<std::size_t>(k), b = base + 2 * static_cast<std::size_t>((k + 1) % seg);
        polys.push_back({a, b, b + 1, a + 1});
        force.push_back(w.force);
        wall_index.push_back(static_cast<int>(wi));
      }
    }
  }
  std::ofstream f(path);
  if (!f) throw InputError(path, 0, "", "cannot write VTK file");
  f << "# vtk DataFile Version 3.0\nchutelab DEM walls; lengths in mm, forces in N\nASCII\nDATASET POLYDATA\n";
  f << fmt::format("POINTS {} double\n", pts.size());
  for (const auto& x : pts) f << fmt::format("{:.9g} {:.9g} {:.9g}\n", x.x() * 1e3, x.y() * 1e3, x.z() * 1e3);
  std::size_t total = 0;
  for (const auto& p : polys) total += p.size() + 1;
  f << fmt::format("POLYGONS {} {}\n", polys.size(), total);
  for (const auto& p : polys) {
    f << p.size();
    for (auto k : p) f << ' ' << k;
    f << '\n';
  }
  f << fmt::format("CELL_DATA {}\nSCALARS wall int 1\nLOOKUP_TABLE default\n", polys.size());
  for (int w : wall_index) f << w << '\n';
  f << "VECTORS force_N double\n";
  for (const auto& v : force) f << fmt::format("{:.9g} {:.9g} {:.9g}\n", v.x(), v.y(), v.z());
  if (!f) throw InputError(path, 0, "", "error while writing VTK file");
}

}  // namespace chutelab::dem
