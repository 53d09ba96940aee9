#pragma once
// Archard's sliding wear (Archard 1953, J. Appl. Phys. 24:981): the volume a surface loses while a
// body slides over it under a normal load is proportional to the load and the sliding distance and
// inversely to the softer surface's hardness,
//     V = k_A F_n s / H          [m^3] = [-] [N] [m] / [Pa],
// with k_A the dimensionless wear coefficient (a property of the pair and the regime, found by
// test: mild wear of metals lies orders of magnitude below severe wear) and H the plate's
// indentation hardness. In a DEM, s of one contact in one step is |v_t| dt, the slip of the
// particle's surface over the wall, so the worn volume is k_A / H times sum(F_n |v_t| dt).
namespace chutelab::dem::wear {

struct ArchardParams {
  // Defaults: an order-of-magnitude mild-wear coefficient and the hardness of mild steel plate
  // (~120 HV); set both for the plate and the material at hand (setup.toml [dem.wear]).
  double coefficient = 1e-6;   // k_A, dimensionless
  double hardness = 1.2e9;     // H, Pa
};

// Worn volume, m^3, for a sum of normal force x sliding distance, N m.
inline double archard_volume(const ArchardParams& p, double force_times_distance) {
  return p.coefficient * force_times_distance / p.hardness;
}

}  // namespace chutelab::dem::wear
