#pragma once
// The particle a calibration rig is filled with: a sphere or a rigid multi-sphere clump (reference study Fig. 4b
// and 4c), and the material numbers the rigs need, taken from a dataset's [material] table.
#include <cstdint>
#include <string>

#include "core/rig.h"
#include "dem/clump.h"
#include "dem/rigid_rotation.h"
#include "dem/world.h"

namespace chutelab::dem::rigs {

enum class GrainKind { sphere, clump };

struct Grain {
  GrainKind kind = GrainKind::sphere;
  double diameter = 5.6e-3;  // m: the sphere's, or the clump's element spheres' (largest)
  ClumpShape clump;          // used when kind == clump (scaled to `diameter`)

  static Grain sphere(double d);
  // The reference study's pellet (two overlapping spheres, Fig. 4c) with element spheres of diameter d.
  static Grain reference_clump(double element_diameter = 4.4e-3);
  double volume() const;            // m^3 of solid
  double bounding_radius() const;   // m
  std::string label() const;        // "sphere d=5.6mm", "clump 2x4.4mm"
};

// Adds one grain at `position`, orientation `q` (ignored for spheres), at rest; `density` kg/m^3.
// Returns the persistent id of its first sphere.
std::int64_t add_grain(World& w, const Grain& g, const Vec3& position, const Quat& q, int material, double density);

// Materials of a rig scene: the particles ("pellet") and one wall material ("wall"), with the reference study's
// interaction coefficients from a dataset material: particle-particle friction, rolling friction and
// restitution; particle-wall friction `wall_friction`, rolling friction `wall_rolling` and restitution
// restitution_plate. Young's modulus (particles and walls) is multiplied by modulus_scale.
struct RigMaterials {
  int pellet = 0, wall = 1;
};
RigMaterials add_rig_materials(World& w, const chutelab::Material& m, double density, double modulus_scale,
                               double wall_friction, double wall_rolling);

}  // namespace chutelab::dem::rigs
