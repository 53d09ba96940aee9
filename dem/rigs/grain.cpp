#include "dem/rigs/grain.h"

#include <cmath>
#include <numbers>

#include <fmt/format.h>

#include "core/input_error.h"

namespace chutelab::dem::rigs {

Grain Grain::sphere(double d) {
  if (!(d > 0.0)) throw InputError("", 0, "particle diameter", fmt::format("must be > 0, got {} m", d));
  Grain g;
  g.kind = GrainKind::sphere;
  g.diameter = d;
  return g;
}

Grain Grain::reference_clump(double element_diameter) {
  if (!(element_diameter > 0.0))
    throw InputError("", 0, "clump diameter", fmt::format("must be > 0, got {} m", element_diameter));
  Grain g;
  g.kind = GrainKind::clump;
  g.diameter = element_diameter;
  const ClumpShape base = ClumpShape::reference_pellet();
  g.clump = base.scaled(element_diameter / (2.0 * base.largest_sphere_radius()));
  return g;
}

double Grain::volume() const {
  return kind == GrainKind::sphere ? std::numbers::pi / 6.0 * diameter * diameter * diameter : clump.volume;
}

double Grain::bounding_radius() const { return kind == GrainKind::sphere ? 0.5 * diameter : clump.bounding_radius; }

std::string Grain::label() const {
  if (kind == GrainKind::sphere) return fmt::format("sphere d={:g}mm", diameter * 1e3);
  return fmt::format("clump {}x{:g}mm", clump.spheres.size(), diameter * 1e3);
}

std::int64_t add_grain(World& w, const Grain& g, const Vec3& position, const Quat& q, int material, double density) {
  if (g.kind == GrainKind::sphere) {
    ParticleSpec s;
    s.position = position;
    s.radius = 0.5 * g.diameter;
    s.material = material;
    s.density = density;
    return w.add_particle(s);
  }
  // One registered shape per World and grain size (a rig adds grains of one kind).
  int shape = -1;
  for (std::size_t k = 0; k < w.clumps().shapes.size(); ++k)
    if (w.clumps().shapes[k].name == g.clump.name && w.clumps().shapes[k].volume == g.clump.volume) shape = static_cast<int>(k);
  if (shape < 0) shape = w.add_clump_shape(g.clump);
  ClumpSpec c;
  c.shape = shape;
  c.position = position;
  c.orientation = q;
  c.material = material;
  c.density = density;
  w.add_clump(c);
  return w.particles().id.back() - static_cast<std::int64_t>(g.clump.spheres.size()) + 1;
}

RigMaterials add_rig_materials(World& w, const chutelab::Material& m, double density, double modulus_scale,
                               double wall_friction, double wall_rolling) {
  RigMaterials r;
  r.pellet = w.materials().add({"pellet", m.youngs_modulus * modulus_scale, m.poisson_ratio, density});
  // The rigs' walls (acrylic tube, steel or polymer plates) are an order of magnitude stiffer than
  // the pellets; their exact modulus hardly matters once E_wall >> E_pellet.
  r.wall = w.materials().add({"wall", 10.0 * m.youngs_modulus * modulus_scale, 0.3, 0.0});
  Interaction pp;
  pp.friction = m.friction_particle;
  pp.rolling_friction = m.rolling_friction_particle;
  pp.restitution = m.restitution_particle;
  w.materials().set_interaction(r.pellet, r.pellet, pp);
  Interaction pw;
  pw.friction = wall_friction;
  pw.rolling_friction = wall_rolling;
  pw.restitution = m.restitution_plate > 0.0 ? m.restitution_plate : m.restitution_particle;
  w.materials().set_interaction(r.pellet, r.wall, pw);
  return r;
}

}  // namespace chutelab::dem::rigs
