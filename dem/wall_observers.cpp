// The wall-contact observers (dem/walls/wall_contact.h), kept out of the force loop: one serial pass
// over the contact list after the forces of a step, only when some wall is observed.
#include <fmt/format.h>

#include "core/input_error.h"
#include "dem/world.h"

namespace chutelab::dem {

void World::observe_wall(int wall, WallContactObserver fn) {
  if (wall < 0 || static_cast<std::size_t>(wall) >= walls_.size())
    throw InputError("", 0, "observe_wall", fmt::format("no wall {}", wall));
  wall_observers_.resize(walls_.size());
  wall_observers_[static_cast<std::size_t>(wall)] = std::move(fn);
}

void World::report_wall_contacts() const {
  WallContact c;
  c.step = step_;
  c.dt = dt_;
  for (std::size_t q = 0; q < wc_.touch.size(); ++q) {
    if (!wc_.touch[q]) continue;
    const auto wi = static_cast<std::size_t>(wc_.wall[q]);
    if (wi >= wall_observers_.size() || !wall_observers_[wi]) continue;
    const auto i = static_cast<std::size_t>(wc_.owner[q]);
    c.wall = static_cast<int>(wi);
    c.element = wc_.element[q];
    c.particle = p_.id[i];
    c.point = wc_.out_point[q];
    c.normal = wc_.obs_normal[q];  // taken with the force (the particle has moved on since)
    c.force = -wc_.out_f[q];
    c.velocity = wc_.obs_velocity[q];
    c.mass = p_.contact_mass[i];
    c.radius = p_.radius[i];
    wall_observers_[wi](c);
  }
}

}  // namespace chutelab::dem
