#include "dem/station/scene.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <fmt/format.h>

#include "core/input_error.h"
#include "core/rig_needs.h"
#include "dem/contact/mixing.h"
#include "dem/station/belt_cohesion.h"
#include "dem/timestep.h"
#include "dem/walls/stl.h"

namespace chutelab::dem::station {
namespace {

constexpr double pi = std::numbers::pi;

// A flat quadrilateral a-b-c-d (in order around it) as a two-triangle mesh. Meshes are thin
// two-sided sheets: a particle that gets behind one (a rebound under the belt, a particle beside a
// side panel) is pushed off its back instead of meeting the infinite half-space of a plane wall.
TriangleMesh quad(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d, std::string source) {
  return TriangleMesh::from_soup({{a, b, c}, {a, c, d}}, std::move(source));
}

// One triangle as its own wall, so it can carry its own surface velocity.
Wall triangle(std::string name, const Vec3& a, const Vec3& b, const Vec3& c, int material) {
  return Wall::mesh(std::move(name), TriangleMesh::from_soup({{a, b, c}}), material);
}

// Surface velocity of a belt piece: the belt slides along itself, so on a tilted piece its
// velocity is V_b along the direction of travel projected into the piece's plane.
Vec3 belt_velocity_on(const Vec3& normal, const Vec3& along, double vb) {
  const Vec3 n = normal.normalized();
  Vec3 t = along - along.dot(n) * n;
  return vb * t.normalized();
}

// The insertion box above the belt: its bottom's height over the belt surface and its depth.
struct FeedBox {
  double low = 0.0;
  double depth = 0.0;
};

// The materials of the scene: walls get the particles' modulus, as in the LIGGGHTS rig.
struct SceneMaterials {
  int particle = 0, plate = 0, belt = 0, side = 0;
};

// The particle diameter of the run, checked against the load's width and the plate.
double particle_diameter(const Station& st, const RunSettings& s) {
  const double d = s.particle_diameter > 0.0 ? s.particle_diameter : st.material.particle_diameter;
  const double W = st.belt.loaded_width;
  if (!(st.belt_speed > 0.0)) throw InputError("", 0, "belt_speed_mps", "the DEM needs a moving belt (V_b > 0)");
  if (!(st.mass_flow > 0.0)) throw InputError("", 0, "mass_flow_tph", "the DEM needs a positive mass flow");
  if (d > 0.25 * W)
    throw InputError("", 0, "particle_diameter_mm",
                     fmt::format("DEM particles of {:.1f} mm do not fit a load {:.0f} mm wide (need at least four "
                                 "across)", d * 1e3, W * 1e3));
  if (d > 0.25 * st.plate.height || d > 0.25 * st.plate.width)
    throw InputError("", 0, "particle_diameter_mm",
                     fmt::format("DEM particles of {:.1f} mm are too large for a {:.0f} x {:.0f} mm plate", d * 1e3,
                                 st.plate.width * 1e3, st.plate.height * 1e3));
  return d;
}

// The belt's and the plate's frames (frames.h); the plate must clear the pulley by a particle.
void place_frames(const Station& st, Scene& sc) {
  const double R = st.belt.belt_radius();
  const double th = st.belt.incline;
  sc.belt.radius = R;
  sc.belt.along = Vec3(std::cos(th), std::sin(th), 0.0);
  sc.belt.up = Vec3(-std::sin(th), std::cos(th), 0.0);
  sc.belt.tangent_point = R * sc.belt.up;

  const double beta = st.plate.angle;
  PlateFrame& pf = sc.plate;
  pf.angle = beta;
  pf.height = st.plate.height;
  pf.width = st.plate.width;
  pf.top_edge = Vec3(st.plate_distance, st.plate_top, 0.0);
  pf.into = Vec3(std::cos(beta), std::sin(beta), 0.0);
  pf.down = Vec3(std::sin(beta), -std::cos(beta), 0.0);
  pf.reference = pf.top_edge + (st.plate_top / std::cos(beta)) * pf.down;
  // Distance from the axis to the face segment.
  const Vec3 a = pf.top_edge, b = pf.bottom_edge();
  const Vec3 ab = b - a;
  const double t = std::clamp((-a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
  const double clearance = (a + t * ab).norm() - R;
  if (clearance < sc.diameter)
    throw InputError("", 0, "plate_distance_mm",
                     fmt::format("the plate face passes {:.0f} mm from the pulley surface; the stream needs at "
                                 "least a particle diameter ({:.1f} mm)", clearance * 1e3, sc.diameter * 1e3));
}

// Where along the belt the feed, the feeder relaxation and the belt itself begin and end (Scene's
// belt coordinates), and the insertion box above the feed.
FeedBox lay_out_feed(const Station& st, const RunSettings& s, Scene& sc) {
  const double d = sc.diameter, vb = sc.belt_speed, g = st.gravity, R = sc.belt.radius;
  const double lam = st.belt.trough.idler_angle;
  const double c_half = 0.5 * st.belt.trough.centre_roll;
  // Rise of the trough's wing at the edge of the load: the insertion box must clear it.
  const double wing_rise =
      st.belt.trough.troughed() ? std::max(0.0, 0.5 * st.belt.loaded_width - c_half) * std::tan(lam) : 0.0;
  FeedBox box;
  box.low = std::max(s.insert_low, 2.5 * d) + wing_rise;
  box.depth = std::max(s.insert_depth, 3.5 * d);
  if (s.insert_at_face && !(s.insert_speed_down > 0.0))
    throw InputError("", 0, field_name(&RunSettings::insert_speed_down), "insertion = \"face\" needs a downward insertion speed (> 0)");
  if (s.insert_at_face && s.particle_shape == ParticleShape::clump)
    throw InputError("", 0, field_name(&RunSettings::insert_at_face), "insertion = \"face\" feeds spheres only; use \"box\" for clumps");
  // Free fall of a particle inserted at the top of the box (or released at its face) onto the bare
  // belt: where the last inserted particles land, the relaxation must still act (feeder_relaxation.h).
  const double fall_h = s.insert_at_face ? box.low : box.low + box.depth, v0 = s.insert_speed_down;
  const double t_land = (-v0 + std::sqrt(v0 * v0 + 2.0 * g * fall_h)) / g;
  if (std::isfinite(s.face_end)) {
    // The dataset's feeder places the face itself; the relaxation follows from it.
    sc.feed_s_end = -(s.face_end + vb * s.face_end_time);
    sc.relax_s_end = s.relax_from_face ? sc.feed_s_end + s.relax_past : sc.feed_s_end + vb * t_land + s.relax_past;
  } else {
    sc.relax_s_end = -s.free_belt;
    sc.feed_s_end = sc.relax_s_end - s.relax_past - (s.relax_from_face ? 0.0 : vb * t_land);
  }
  if (sc.relax_s_end > 0.0)
    throw InputError("", 0, field_name(&RunSettings::relax_past), "the feeder relaxation would reach past the pulley");
  sc.feed_s_begin = sc.feed_s_end - s.feed_length;
  sc.belt_start = sc.feed_s_begin - s.belt_upstream;
  if (std::isfinite(s.belt_start_x)) {
    // Belt coordinate of the given x on the carrying run (s grows along the belt, 0 at the tangent point).
    const double s_x = (s.belt_start_x - R * -std::sin(st.belt.incline)) / std::cos(st.belt.incline);
    // A feed placed by the belt speed (face_end_time_s) reaches further upstream when the belt runs
    // faster than the setup was laid out for (a candidate's probe of the belt speed or the pulley):
    // the belt then starts just upstream of the feed, as it does without a given start.
    if (s_x > sc.feed_s_begin) {
      sc.notes.push_back(fmt::format("the belt starts at {:.0f} mm along the belt, upstream of the insertion face, not at "
                                     "dem.feed.belt_start_mm = {:.0f} mm (inside the feed)",
                                     1e3 * sc.belt_start, 1e3 * s.belt_start_x));
    } else {
      sc.belt_start = s_x;
    }
  }
  return box;
}

// The World's settings but its time step: the domain around the belt, the plate and the feed (and
// the discharge's height below the plate), gravity, the contact model, skin and threads.
Settings world_settings(const Station& st, const RunSettings& s, const FeedBox& box, Scene& sc) {
  const double R = sc.belt.radius;
  const PlateFrame& pf = sc.plate;
  const Vec3 p_start = sc.belt.tangent_point + sc.belt_start * sc.belt.along;
  const Vec3 p_bottom = pf.bottom_edge();
  sc.sink_y = std::min(p_bottom.y(), -R) - 0.15;  // LIGGGHTS rig: box bottom 150 mm below the plate
  const double x_hi = std::max(pf.top_edge.x(), p_bottom.x()) + 0.3;
  const double y_top = std::max({pf.top_edge.y(), p_start.y() + box.low + box.depth, R}) + 0.6;
  const double z_half = 0.5 * std::max({st.belt.belt_width, st.plate.width, st.belt.loaded_width}) + 0.15;
  Settings ws;
  ws.gravity = Vec3(0.0, -st.gravity, 0.0);
  ws.domain = Box{Vec3(std::min(p_start.x(), -R) - 0.15, sc.sink_y - 0.12, -z_half),
                  Vec3(x_hi, y_top, z_half)};
  ws.normal = s.contact;
  ws.tangential = TangentialModel::coulomb_history;
  // Constant directional torque (reference study Eq 10), as LIGGGHTS' `rolling_friction cdt` of the rig.
  ws.rolling = RollingModel::constant_torque;
  ws.skin = s.skin_fraction * (0.5 * sc.diameter);
  ws.threads = effective_threads(s.threads);
  ws.check_every = 10;
  sc.warnings = std::make_shared<std::vector<std::string>>();
  ws.on_warning = [warnings = sc.warnings](const std::string& m) {
    if (warnings->size() < 20) warnings->push_back(m);
  };
  return ws;
}

// The time step: the shortest of a fraction of the particle-particle Hertz collision at the
// characteristic impact speed and a fraction of the Rayleigh time. Returns the contact law's
// parameters that give the same collision time (any law other than Hertz-Mindlin needs them).
LawParameters pick_time_step(const Station& st, const RunSettings& s, double youngs_modulus, Scene& sc,
                             Settings& ws) {
  const chutelab::Material& mat = st.material;
  const double E = youngs_modulus, nu = mat.poisson_ratio, r = 0.5 * sc.diameter;
  // Characteristic impact speed: the belt speed plus a free fall from the belt to the plate's foot.
  const double drop = std::max(0.0, sc.belt.radius - sc.plate.bottom_edge().y());
  sc.characteristic_speed = sc.belt_speed + std::sqrt(2.0 * st.gravity * drop);
  ws.characteristic_speed = sc.characteristic_speed;
  const double G = E / (2.0 * (1.0 + nu));
  sc.rayleigh_time = rayleigh_time(r, mat.solid_density, G, nu);
  const double e_star = 1.0 / (2.0 * (1.0 - nu * nu) / E);
  const double m = sc.particle_mass;
  // Shortest collision: particle on particle (m* = m/2, R* = r/2).
  const double tc_hertz = hertz_collision_time(0.5 * m, 0.5 * r, e_star, sc.characteristic_speed);
  sc.collision_time = tc_hertz;
  sc.dt = std::min(s.dt_fraction * tc_hertz, s.rayleigh_fraction * sc.rayleigh_time);
  ws.dt = sc.dt;
  return s.contact.matched_parameters(mat.restitution_particle, 0.5 * m, tc_hertz);
}

// The particles, the plate, the belt (and pulley) and the side panels as materials, and their
// interactions; the belt's adhesion as the particle-belt pair's cohesion (belt_cohesion.h).
SceneMaterials add_materials(const Station& st, const RunSettings& s, const ExternalInputs& fx, double youngs_modulus,
                             const LawParameters& law_parameters, Scene& sc) {
  const chutelab::Material& mat = st.material;
  const double E = youngs_modulus, nu = mat.poisson_ratio;
  auto& mt = sc.world->materials();
  SceneMaterials m;
  m.particle = mt.add(Material{"particle", E, nu, mat.solid_density});
  m.plate = mt.add(Material{"plate", E, nu, 0.0});
  m.belt = mt.add(Material{"belt", E, nu, 0.0});
  m.side = mt.add(Material{"side", E, nu, 0.0});
  auto interaction = [&](double mu, double mu_r, double e) {
    Interaction in;
    in.friction = mu;
    in.rolling_friction = mu_r;
    in.restitution = std::clamp(e, 1e-3, 1.0);
    in.law = law_parameters;
    return in;
  };
  const double mu_plate = fx.plate_friction ? std::max(0.0, *fx.plate_friction) : mat.friction_plate;
  // The engine's rolling torque has the lever R_i (reference study Eq 10); LIGGGHTS' cdt uses R_i R_j/(R_i + R_j),
  // which for the station's equal spheres is the same law with half the coefficient.
  const double mu_r_pp = mat.rolling_friction_particle * (s.rolling_lever_effective ? 0.5 : 1.0);
  mt.set_interaction(m.particle, m.particle, interaction(mat.friction_particle, mu_r_pp, mat.restitution_particle));
  mt.set_interaction(m.particle, m.plate, interaction(mu_plate, mat.rolling_friction_wall, mat.restitution_plate));
  mt.set_interaction(m.particle, m.belt, interaction(mat.friction_belt, mat.rolling_friction_wall, mat.restitution_belt));
  if (fx.belt_adhesive_stress > 0.0) {
    // The belt and the pulley share m.belt, so one pair carries the adhesion over both.
    if (s.contact.hertz_elastic()) {
      const double es = effective_youngs_modulus(mt.material(m.particle), mt.material(m.belt));
      Interaction in = interaction(mat.friction_belt, mat.rolling_friction_wall, mat.restitution_belt);
      in.cohesion_energy_density = belt_cohesion_energy_density(fx.belt_adhesive_stress, es);
      mt.set_interaction(m.particle, m.belt, in);
      sc.notes.push_back(fmt::format(
          "belt adhesion {:.4g} Pa: particle-belt and particle-pulley cohesion k_c = {:.4g} J/m^3 (sJKR), a "
          "pull-off of {:.3g} N per contact over {:.4g} contacts/m^2",
          fx.belt_adhesive_stress, in.cohesion_energy_density,
          sjkr_pull_off_force(in.cohesion_energy_density, 0.5 * sc.diameter, es),
          monolayer_contacts_per_area(sc.diameter)));
    } else {
      sc.notes.push_back(fmt::format("belt adhesion {:.4g} Pa not represented: with the {} contact the sJKR "
                                     "cohesion has no finite pull-off (belt_cohesion.h)",
                                     fx.belt_adhesive_stress, s.contact.title()));
    }
  }
  // Side panels: their own friction (acrylic in the reference study), the plate's restitution.
  mt.set_interaction(m.particle, m.side, interaction(mat.friction_side, mat.rolling_friction_wall, mat.restitution_plate));
  return m;
}

// Troughed: centre strip and two wings at the idler angle on the carrying run; over the last
// stretch before the pulley the wings flatten linearly to zero (a twisted surface made of
// triangles, each sliding along itself at V_b).
void add_troughed_belt(const Station& st, int material, Scene& sc) {
  World& w = *sc.world;
  const Vec3 zhat = Vec3::UnitZ();
  const double vb = sc.belt_speed, B = st.belt.belt_width;
  const double lam = st.belt.trough.idler_angle;
  const double c_half = 0.5 * st.belt.trough.centre_roll;
  const double wing = 0.5 * B - c_half;
  const double trough_transition = std::min(std::max(B, 0.3), 0.8 * -sc.belt_start);
  const double s_tr = -trough_transition;  // transition starts here
  const Vec3 up = sc.belt.up, al = sc.belt.along, T = sc.belt.tangent_point;
  auto on_belt = [&](double s_, double z, double height) { return T + s_ * al + height * up + z * zhat; };
  {
    const Vec3 a = on_belt(sc.belt_start, 0, 0), b = on_belt(0, 0, 0), lat = c_half * zhat;
    Wall c = Wall::mesh("belt-centre", quad(a - lat, b - lat, b + lat, a + lat, "generated trough"), material);
    c.surface.linear = vb * al;
    w.add_wall(std::move(c));
  }
  for (int side : {-1, 1}) {
    // Carrying run: a flat wing from the belt start to the transition.
    const Vec3 root0 = on_belt(sc.belt_start, side * c_half, 0), root1 = on_belt(s_tr, side * c_half, 0);
    const Vec3 out_dir = (side * std::cos(lam)) * zhat + std::sin(lam) * up;
    Wall wr = Wall::mesh(fmt::format("belt-wing{}", side),
                         quad(root0, root1, root1 + wing * out_dir, root0 + wing * out_dir, "generated trough"), material);
    wr.surface.linear = vb * al;
    w.add_wall(std::move(wr));
    // Transition: 8 segments, two triangles each.
    const int n = 8;
    for (int k = 0; k < n; ++k) {
      const double s0 = s_tr * (1.0 - double(k) / n), s1 = s_tr * (1.0 - double(k + 1) / n);
      const double l0 = lam * (1.0 - double(k) / n), l1 = lam * (1.0 - double(k + 1) / n);
      const Vec3 a = on_belt(s0, side * c_half, 0), b = on_belt(s1, side * c_half, 0);
      const Vec3 a_out = a + wing * ((side * std::cos(l0)) * zhat + std::sin(l0) * up);
      const Vec3 b_out = b + wing * ((side * std::cos(l1)) * zhat + std::sin(l1) * up);
      for (int t = 0; t < 2; ++t) {
        const Vec3 p0 = a, p1 = t == 0 ? b : b_out, p2 = t == 0 ? b_out : a_out;
        Wall tw = triangle(fmt::format("belt-transition{}-{}-{}", side, k, t), p0, p1, p2, material);
        Vec3 nrm = (p1 - p0).cross(p2 - p0);
        if (nrm.dot(up) < 0) nrm = -nrm;
        tw.surface.linear = belt_velocity_on(nrm, al, vb);
        w.add_wall(std::move(tw));
      }
    }
  }
  sc.notes.push_back(fmt::format("troughed belt: {:.0f} deg wings flatten over the last {:.0f} mm before the pulley",
                                 lam / pi * 180.0, trough_transition * 1e3));
}

// The carrying belt from its start to the tangent point, sliding at V_b: a [dem.stl] mesh, a flat
// sheet or a trough.
void add_belt(const Station& st, const DemTable& geometry, int material, Scene& sc) {
  World& w = *sc.world;
  const double vb = sc.belt_speed;
  if (geometry.stl_belt) {
    Wall b = Wall::mesh("belt", read_stl(*geometry.stl_belt, 1e-3), material);
    b.surface.linear = vb * sc.belt.along;
    w.add_wall(std::move(b));
  } else if (!st.belt.trough.troughed()) {
    const Vec3 lat = 0.5 * st.belt.belt_width * Vec3::UnitZ();
    const Vec3 a = sc.belt.tangent_point + sc.belt_start * sc.belt.along, b = sc.belt.tangent_point;
    Wall w_belt = Wall::mesh("belt", quad(a - lat, b - lat, b + lat, a + lat, "generated belt"), material);
    w_belt.surface.linear = vb * sc.belt.along;
    w.add_wall(std::move(w_belt));
  } else {
    add_troughed_belt(st, material, sc);
  }
}

// The head pulley: the front half of a cylinder (72 facets, as the LIGGGHTS rig), turning with the
// belt; or a [dem.stl] mesh.
void add_pulley(const Station& st, const DemTable& geometry, int material, Scene& sc) {
  World& w = *sc.world;
  const double vb = sc.belt_speed, R = sc.belt.radius, B = st.belt.belt_width;
  if (geometry.stl_pulley) {
    Wall p = Wall::mesh("pulley", read_stl(*geometry.stl_pulley, 1e-3), material);
    p.surface.centre = Vec3::Zero();
    p.surface.omega = Vec3(0, 0, -vb / R);
    w.add_wall(std::move(p));
    return;
  }
  const int n = 72;
  std::vector<std::array<Vec3, 3>> soup;
  const double phi0 = -st.belt.incline;  // angle from the upward vertical, towards +x: the tangent point
  auto at = [&](double phi, double z) { return Vec3(R * std::sin(phi), R * std::cos(phi), z); };
  for (int k = 0; k < n; ++k) {
    const double a0 = phi0 + pi * k / n, a1 = phi0 + pi * (k + 1) / n;
    soup.push_back({at(a0, -0.5 * B), at(a1, -0.5 * B), at(a1, 0.5 * B)});
    soup.push_back({at(a0, -0.5 * B), at(a1, 0.5 * B), at(a0, 0.5 * B)});
  }
  Wall p = Wall::mesh("pulley", TriangleMesh::from_soup(soup, "generated pulley"), material);
  p.surface.centre = Vec3::Zero();
  p.surface.omega = Vec3(0, 0, -vb / R);  // surface speed V_b, moving with the belt over the top
  w.add_wall(std::move(p));
}

// The impact plate, the load cell (its moment about the plate frame's reference): a [dem.stl] mesh,
// or the face as one quad or as a grid of cells for the pressure and wear maps.
void add_plate(const RunSettings& s, const DemTable& geometry, int material, Scene& sc) {
  World& w = *sc.world;
  const PlateFrame& pf = sc.plate;
  if (geometry.stl_plate) {
    Wall p = Wall::mesh("plate", read_stl(*geometry.stl_plate, 1e-3), material);
    p.load_point = pf.reference;
    sc.plate_wall = w.add_wall(std::move(p));
    sc.notes.push_back("plate from " + *geometry.stl_plate + "; sensors use the dataset's plate position");
    return;
  }
  const Vec3 lat = 0.5 * pf.width * Vec3::UnitZ();
  const Vec3 top = pf.top_edge, bot = pf.bottom_edge();
  TriangleMesh mesh = quad(top - lat, bot - lat, bot + lat, top + lat, "generated plate");
  if (s.plate_cells > 0) {
    // A grid of near-square cells for the pressure and wear maps; each cell as the plate's quad.
    const int rows = s.plate_cells;
    const int cols = std::max(1, static_cast<int>(std::lround(rows * pf.width / pf.height)));
    std::vector<std::array<Vec3, 3>> soup;
    auto at = [&](int r, int c) {
      return top + (pf.height * r / rows) * pf.down + (pf.width * c / cols - 0.5 * pf.width) * Vec3::UnitZ();
    };
    for (int r = 0; r < rows; ++r)
      for (int c = 0; c < cols; ++c) {
        soup.push_back({at(r, c), at(r + 1, c), at(r + 1, c + 1)});
        soup.push_back({at(r, c), at(r + 1, c + 1), at(r, c + 1)});
      }
    mesh = TriangleMesh::from_soup(soup, "generated plate");
    sc.notes.push_back(fmt::format("plate meshed as {} x {} cells of {:.1f} x {:.1f} mm for the maps", rows, cols,
                                   pf.height / rows * 1e3, pf.width / cols * 1e3));
  }
  Wall p = Wall::mesh("plate", std::move(mesh), material);
  p.load_point = pf.reference;
  sc.plate_wall = w.add_wall(std::move(p));
}

// Side panels from the pulley to the plate, over the plate's height (LIGGGHTS rig: at +-W_plate/2).
void add_side_panels(const Station& st, int material, Scene& sc) {
  const PlateFrame& pf = sc.plate;
  const Vec3 p_bottom = pf.bottom_edge();
  const double x0 = 0.0, x1 = std::max(pf.top_edge.x(), p_bottom.x());
  const double y0 = p_bottom.y(), y1 = pf.top_edge.y();
  for (int side : {-1, 1}) {
    const double z = side * 0.5 * st.plate.width;
    sc.world->add_wall(Wall::mesh(fmt::format("side{}", side),
                                  quad(Vec3(x0, y0, z), Vec3(x1, y0, z), Vec3(x1, y1, z), Vec3(x0, y1, z),
                                       "generated side panel"),
                                  material));
  }
}

// The feed: an inserter over the feed's stretch of belt at the condition's mass flow, and the
// feeder relaxation's zone (feeder_relaxation.h).
void add_feed(const Station& st, const RunSettings& s, const FeedBox& box, int material, Scene& sc) {
  World& w = *sc.world;
  const double r = 0.5 * sc.diameter, vb = sc.belt_speed;
  const Vec3 a = sc.belt.tangent_point + sc.feed_s_begin * sc.belt.along;
  const Vec3 b = sc.belt.tangent_point + sc.feed_s_end * sc.belt.along;
  Inserter in;
  const double face_w = std::isfinite(s.face_width) ? s.face_width : st.belt.loaded_width;
  in.region.lo = Vec3(std::min(a.x(), b.x()), std::max(a.y(), b.y()) + box.low, -0.5 * face_w);
  in.region.hi = Vec3(std::max(a.x(), b.x()), in.region.lo.y() + box.depth, 0.5 * face_w);
  in.mass_rate = st.mass_flow;
  in.radius_min = in.radius_max = r;
  in.material = material;
  if (s.particle_shape == ParticleShape::clump) {
    // The reference study's pellet (Fig. 4c), the same definition `chutelab calibrate` uses
    // (rigs::Grain::reference_clump); the inserter scales it so that its spheres have diameter d and
    // turns each body at random. It owes the feed mass, not a count, so the mass flow is kept.
    in.clump_shape = w.add_clump_shape(ClumpShape::reference_pellet());
  }
  in.velocity = vb * sc.belt.along + Vec3(0.0, -s.insert_speed_down, 0.0);
  in.interval = s.insert_interval;
  in.hold_to_face = s.insert_at_face;
  // A held batch crosses the face in (box height - d) / v_down: the next one follows it then, so
  // the face releases a steady stream (as LIGGGHTS' insert/stream refills its extrusion).
  if (s.insert_at_face) in.interval = std::max(box.depth - 2.0 * r, r) / s.insert_speed_down;
  in.seed = s.seed * 0x9e3779b97f4a7c15ULL + 1;
  in.max_attempts = 400;
  sc.inserter = w.add_inserter(in);
  sc.feeder.belt = sc.belt;
  sc.feeder.belt_speed = vb;
  sc.feeder.rate = s.relax_rate;
  sc.feeder.all_components = s.relax_all;
  sc.feeder.s_begin = sc.belt_start - 0.05;
  sc.feeder.s_end = sc.relax_s_end;
  sc.feeder.h_max = box.low + box.depth + 0.05;
}

// The body forces: the feeder relaxation and the flight force (air drag).
void add_body_forces(const ExternalInputs& fx, Scene& sc) {
  sc.flight.belt = sc.belt;
  sc.flight.acceleration = fx.flight;
  const FeederRelaxation feeder = sc.feeder;
  const FlightForce flight = sc.flight;
  sc.world->set_body_force([feeder, flight](const Particles& p, double, std::size_t b, std::size_t e, std::vector<Vec3>& f) {
    feeder.add(p, b, e, f);
    flight.add(p, b, e, f);
  });
}

// The sinks: the discharge below the plate, and the domain's faces. The discharge is emptied in
// batches by the run loop (Scene::discharge): every removal from the World forces a neighbour-list
// rebuild, and at ~10^4 particles/s a per-step sink would rebuild at every step. The World's own
// sink just above the domain's floor only catches what a batch missed.
void add_sinks(Scene& sc) {
  World& w = *sc.world;
  const Box& dom = w.settings().domain;
  const double in = 0.02;
  sc.plate_sink = w.add_sink(Sink{Vec3(0, dom.lo.y() + in, 0), Vec3::UnitY()});
  sc.boundary_sinks.push_back(w.add_sink(Sink{Vec3(dom.lo.x() + in, 0, 0), Vec3::UnitX()}));
  sc.boundary_sinks.push_back(w.add_sink(Sink{Vec3(dom.hi.x() - in, 0, 0), -Vec3::UnitX()}));
  sc.boundary_sinks.push_back(w.add_sink(Sink{Vec3(0, dom.hi.y() - in, 0), -Vec3::UnitY()}));
  sc.boundary_sinks.push_back(w.add_sink(Sink{Vec3(0, 0, dom.lo.z() + in), Vec3::UnitZ()}));
  sc.boundary_sinks.push_back(w.add_sink(Sink{Vec3(0, 0, dom.hi.z() - in), -Vec3::UnitZ()}));
}

}  // namespace

Scene build_scene(const Station& st, const RunSettings& s, const DemTable& geometry, const ExternalInputs& fx) {
  check(s);
  require_dem_keys(st);
  Scene sc;
  const double d = particle_diameter(st, s);
  sc.belt_speed = st.belt_speed;
  sc.mass_flow = st.mass_flow;
  sc.diameter = d;
  sc.shape = s.particle_shape;
  // A sphere of diameter d; also what sets the collision time of clumps: their contacts are sphere
  // contacts with the body's (larger) mass, so the sphere's t_c is the shorter, safe one.
  sc.particle_mass = st.material.solid_density * pi / 6.0 * d * d * d;

  place_frames(st, sc);
  const FeedBox box = lay_out_feed(st, s, sc);
  Settings ws = world_settings(st, s, box, sc);
  const double youngs_modulus = st.material.youngs_modulus * s.shear_modulus_scale;
  const LawParameters law_parameters = pick_time_step(st, s, youngs_modulus, sc, ws);
  sc.world = std::make_unique<World>(ws);
  const SceneMaterials m = add_materials(st, s, fx, youngs_modulus, law_parameters, sc);

  add_belt(st, geometry, m.belt, sc);
  add_pulley(st, geometry, m.belt, sc);  // the belt and the pulley share a material
  add_plate(s, geometry, m.plate, sc);
  add_side_panels(st, m.side, sc);
  for (const auto& f : geometry.stl_walls)
    sc.map_walls.push_back(sc.world->add_wall(Wall::mesh(f, read_stl(f, 1e-3), m.side)));
  add_feed(st, s, box, m.particle, sc);
  add_body_forces(fx, sc);
  add_sinks(sc);
  return sc;
}

double Scene::discharge() {
  const Particles& p = world->particles();
  bool any = false;
  for (std::size_t i = 0; i < p.size() && !any; ++i) any = p.x[i].y() < sink_y;
  if (!any) return 0.0;
  // A clump goes whole once any of its spheres is below the sink (World::remove_particles_if), so
  // its other spheres count as discharged too.
  std::vector<char> gone(p.size(), 0), body_gone(world->clumps().size(), 0);
  for (std::size_t i = 0; i < p.size(); ++i)
    if (p.x[i].y() < sink_y) {
      gone[i] = 1;
      if (p.clump[i] >= 0) body_gone[static_cast<std::size_t>(p.clump[i])] = 1;
    }
  double removed = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (p.clump[i] >= 0 && body_gone[static_cast<std::size_t>(p.clump[i])]) gone[i] = 1;
    if (gone[i]) removed += p.mass[i];
  }
  world->remove_particles_if([&](std::size_t i) { return gone[i] != 0; });
  discharged += removed;
  return removed;
}

}  // namespace chutelab::dem::station
