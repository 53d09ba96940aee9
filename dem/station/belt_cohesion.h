#pragma once
// Belt adhesion in the DEM: the adhesive stress sigma_a of effects/belt_adhesion.cpp as the
// simplified-JKR cohesion (dem/contact/cohesion_sjkr.h) of the particle-belt pair, which the belt
// and the head pulley share.
//
// sigma_a is the largest tension per unit belt area that the belt-material interface holds. In the
// DEM that interface is the belt's contacts with the bottom layer of spheres, so we require
//   n F_pull = sigma_a,
// with F_pull the largest pull one contact holds and n the contacts per unit belt area.
//
// F_pull, one sphere of radius R* = d/2 on a wall (Hertz + sJKR, quasi-static: damping left out):
//   F(delta) = 4/3 E* sqrt(R*) delta^{3/2} - pi k_c R* delta          (> 0 pushes the sphere off)
// has its minimum where dF/ddelta = 0, sqrt(delta*) = pi k_c sqrt(R*) / (2 E*), and there
//   F_pull = -F(delta*) = pi k_c R* delta* / 3 = pi^3 k_c^3 R*^2 / (12 E*^2).
// A pull beyond it drives the overlap below delta*, where the attraction falls faster than the
// elastic push: the sphere lets go.
//
// n, assumption: the bottom layer is a hexagonally close-packed monolayer of spheres of the run's
// diameter d, one belt contact each: n = 2 / (sqrt(3) d^2). (A random dense monolayer has ~10 %
// fewer contacts; the DEM then holds ~10 % less than sigma_a.)
//
// Hence, since n R*^2 = 1 / (2 sqrt(3)),
//   k_c = (24 sqrt(3) E*^2 sigma_a)^{1/3} / pi.
// The particle size cancels: a scaled-up DEM particle keeps the interface's stress, so only E*
// (which the quality may scale) enters. What the DEM does not copy is the analytical effect's rigid
// layer (a_h = sigma_a / m'' on the whole layer's mass per area): here only the spheres touching the
// belt are held, the ones above leave as their own contacts allow, which is the physics of an
// adhesive belt and a cohesionless material.
//
// The hold needs a normal law whose push grows faster than the sJKR pull: with the linear
// spring-dashpot both are linear in delta and there is no finite pull-off (the spring is merely
// softened), so the mapping is defined for Hertz-Mindlin only.
#include <cmath>
#include <numbers>

namespace chutelab::dem::station {

// sJKR cohesion energy density k_c (J/m^3) whose pull-off stress over a hexagonal monolayer is
// sigma_a (Pa), for a particle-wall pair of effective modulus e_star (Pa).
inline double belt_cohesion_energy_density(double adhesive_stress, double e_star) {
  if (!(adhesive_stress > 0.0)) return 0.0;
  return std::cbrt(24.0 * std::sqrt(3.0) * e_star * e_star * adhesive_stress) / std::numbers::pi;
}

// The largest pull one sphere-wall contact of radius r_eff holds with cohesion k_c (N), and the
// contacts per unit area of the monolayer (1/m^2): the two halves of the mapping, for tests and notes.
inline double sjkr_pull_off_force(double k_c, double r_eff, double e_star) {
  const double pk = std::numbers::pi * k_c;
  return pk * pk * pk * r_eff * r_eff / (12.0 * e_star * e_star);
}
inline double monolayer_contacts_per_area(double diameter) { return 2.0 / (std::sqrt(3.0) * diameter * diameter); }

}  // namespace chutelab::dem::station
