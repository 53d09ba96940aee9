// The wall contact list's search (dem/walls/wall_contact_list.h).
#include "dem/walls/wall_contact_list.h"

#include <algorithm>
#include <cmath>

#include <omp.h>

#include "dem/storage.h"
#include "dem/team.h"
#include "dem/walls/closest_point.h"

namespace chutelab::dem {
namespace {

// Distance from a sphere centre to a wall element (for candidate lists), or +inf if out of reach.
double element_distance(const Wall& w, std::size_t element, const Vec3& x) {
  if (const auto* p = std::get_if<Plane>(&w.current)) {
    const Vec3 r = x - p->point;
    const double s = r.dot(p->normal);
    if (std::abs(r.dot(p->axis_u)) > p->half_u + 1e-300 || std::abs(r.dot(p->axis_v)) > p->half_v + 1e-300) {
      // Outside the strip: distance to the rectangle.
      const double du = std::max(std::abs(r.dot(p->axis_u)) - p->half_u, 0.0);
      const double dv = std::max(std::abs(r.dot(p->axis_v)) - p->half_v, 0.0);
      return std::sqrt(s * s + du * du + dv * dv);
    }
    return s;  // signed: behind the plane counts as touching
  }
  if (const auto* c = std::get_if<Cylinder>(&w.current)) {
    const Vec3 r = x - c->point;
    const double a = r.dot(c->axis);
    const double rho = (r - a * c->axis).norm();
    const double radial = c->inside ? c->radius - rho : rho - c->radius;
    const double axial = std::max({c->axial_min - a, a - c->axial_max, 0.0});
    return std::hypot(std::max(radial, 0.0), axial) + std::min(radial, 0.0);
  }
  const auto& m = std::get<TriangleMesh>(w.current);
  const auto& t = m.triangles[element];
  const TriClosest cp = closest_point_on_triangle(x, m.vertices[static_cast<std::size_t>(t[0])],
                                                  m.vertices[static_cast<std::size_t>(t[1])],
                                                  m.vertices[static_cast<std::size_t>(t[2])]);
  return (cp.point - x).norm();
}

struct Candidate {
  std::int32_t p, wall, element;
};

// The candidates of wall wi that thread t of nth finds: a contiguous range of the particles for a
// primitive, of the triangles (each against the grid cells its box reaches) for a mesh.
void wall_candidates(const Wall& w, std::int32_t wi, const CellGrid& grid, const Particles& p, double wall_skin,
                     std::size_t t, std::size_t nth, std::vector<Candidate>& out) {
  const std::size_t n = p.size();
  const double reach = grid.rmax + wall_skin;
  if (const auto* m = std::get_if<TriangleMesh>(&w.current)) {
    const auto [first, last] = even_share(m->triangles.size(), t, nth);
    for (std::size_t tr = first; tr < last; ++tr) {
      Vec3 tlo = m->vertices[static_cast<std::size_t>(m->triangles[tr][0])], thi = tlo;
      for (int k = 1; k < 3; ++k) {
        tlo = tlo.cwiseMin(m->vertices[static_cast<std::size_t>(m->triangles[tr][static_cast<std::size_t>(k)])]);
        thi = thi.cwiseMax(m->vertices[static_cast<std::size_t>(m->triangles[tr][static_cast<std::size_t>(k)])]);
      }
      tlo.array() -= reach;
      thi.array() += reach;
      if (n == 0 || (tlo.array() > grid.hi.array()).any() || (thi.array() < grid.lo.array()).any()) continue;
      const std::int64_t x0 = grid.coord(tlo, 0), x1 = grid.coord(thi, 0);
      const std::int64_t y0 = grid.coord(tlo, 1), y1 = grid.coord(thi, 1);
      const std::int64_t z0 = grid.coord(tlo, 2), z1 = grid.coord(thi, 2);
      for (std::int64_t z = z0; z <= z1; ++z)
        for (std::int64_t y = y0; y <= y1; ++y)
          for (std::int64_t x = x0; x <= x1; ++x) {
            const auto c = static_cast<std::size_t>(grid.index(x, y, z));
            for (std::int32_t k = grid.cell_start[c]; k < grid.cell_start[c + 1]; ++k) {
              const std::int32_t pi = grid.members[static_cast<std::size_t>(k)];
              const auto ps = static_cast<std::size_t>(pi);
              if (element_distance(w, tr, p.x[ps]) < p.radius[ps] + wall_skin)
                out.push_back({pi, wi, static_cast<std::int32_t>(tr)});
            }
          }
    }
  } else {
    const auto [first, last] = even_share(n, t, nth);
    for (std::size_t i = first; i < last; ++i)
      if (element_distance(w, 0, p.x[i]) < p.radius[i] + wall_skin) out.push_back({static_cast<std::int32_t>(i), wi, 0});
  }
}

}  // namespace

void WallContactList::build(const CellGrid& grid, const Particles& p, const std::vector<Wall>& walls, double skin,
                            int nt) {
  const std::size_t n = p.size();
  std::vector<std::vector<Candidate>> found(static_cast<std::size_t>(nt));
  on_team(nt, [&] {
    const auto t = static_cast<std::size_t>(omp_get_thread_num());
    const auto nth = static_cast<std::size_t>(omp_get_num_threads());
    std::vector<Candidate> local;  // on this thread's stack while it grows (see NeighborList::build)
    for (std::size_t wi = 0; wi < walls.size(); ++wi) {
      const Wall& w = walls[wi];
      // Until the next rebuild no particle moves more than skin/2 (World::needs_rebuild), so an
      // element of a wall that does not move, farther than R + skin/2 now, cannot be touched before
      // then: listing it only cost its pre-test at every step (three in four of a station's entries
      // were such). The relative margin is far above the rounding of the distances. A moving wall
      // keeps the whole skin, which its own test in needs_rebuild shares with the particles.
      const double wall_skin = w.motion.moving() ? skin : 0.5 * skin * (1.0 + 1e-6);
      wall_candidates(w, static_cast<std::int32_t>(wi), grid, p, wall_skin, t, nth, local);
    }
    found[t] = std::move(local);
  });
  // The thread buffers hold, per thread, all walls in order; joined wall by wall they give the
  // serial order. Per particle the (wall, element) pairs must ascend: within one wall a particle's
  // entries come from ascending triangle ranges, so a stable counting sort by particle over the
  // walls in order (and, within a wall, the threads in order) keeps them ascending.
  begin.assign(n + 1, 0);
  for (const auto& b : found)
    for (const auto& c : b) ++begin[static_cast<std::size_t>(c.p) + 1];
  for (std::size_t i = 0; i < n; ++i) begin[i + 1] += begin[i];
  const auto entries = static_cast<std::size_t>(begin[n]);
  resize_for_overwrite(wall, entries);
  resize_for_overwrite(element, entries);
  {
    std::vector<std::int32_t> next(begin.begin(), begin.end() - 1);
    std::vector<std::size_t> pos(found.size(), 0);  // per thread buffer: first entry of the current wall
    for (std::size_t wi = 0; wi < walls.size(); ++wi)
      for (std::size_t t = 0; t < found.size(); ++t) {
        const auto& b = found[t];
        std::size_t k = pos[t];
        for (; k < b.size() && static_cast<std::size_t>(b[k].wall) == wi; ++k) {
          const auto at = static_cast<std::size_t>(next[static_cast<std::size_t>(b[k].p)]++);
          wall[at] = b[k].wall;
          element[at] = b[k].element;
        }
        pos[t] = k;
      }
  }
  resize_for_overwrite(shear, entries);
  resize_for_overwrite(roll, entries);
  resize_for_overwrite(touch, entries);
  std::fill(shear.begin(), shear.end(), Vec3::Zero());
  std::fill(roll.begin(), roll.end(), Vec3::Zero());
  std::fill(touch.begin(), touch.end(), std::uint8_t{0});
  resize_for_overwrite(force, entries);
  resize_for_overwrite(torque, entries);
  resize_for_overwrite(point, entries);
  resize_for_overwrite(wall_torque, entries);
  index_owners();
}

void WallContactList::carry_history(const TouchingHistory& saved, const std::vector<std::int32_t>& map, int threads) {
  // Likewise each old particle's wall entries go to its own new particle's entries.
  const std::size_t old_owners = saved.wall_begin.empty() ? 0 : saved.wall_begin.size() - 1;
  on_team(threads, [&] {
#pragma omp for schedule(dynamic, 512)
    for (std::size_t io = 0; io < old_owners; ++io) {
      const std::int32_t a = io < map.size() ? map[io] : -1;
      if (a < 0) continue;
      for (auto e = saved.wall_begin[io]; e < saved.wall_begin[io + 1]; ++e) {
        const auto eo = static_cast<std::size_t>(e);
        for (auto k = begin[static_cast<std::size_t>(a)]; k < begin[static_cast<std::size_t>(a) + 1]; ++k) {
          const auto kn = static_cast<std::size_t>(k);
          if (wall[kn] == saved.wall_wall[eo] && element[kn] == saved.wall_element[eo]) {
            shear[kn] = saved.wall_shear[eo];
            roll[kn] = saved.wall_roll[eo];
            touch[kn] = 1;
            break;
          }
        }
      }
    }
  });

}

}  // namespace chutelab::dem
