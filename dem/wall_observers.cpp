// The wall-contact observers (dem/walls/wall_contact.h), kept out of the force loop: one serial pass
// over the contact list after the forces of a step, only when some wall is observed.
#include <fmt/format.h>

#include "core/input_error.h"
#include "dem/world.h"

namespace chutelab::dem {

void World::observe_wall(int wall, WallContactObserver fn) {
  if (wall < 0 || static_cast<std::size_t>(wall) >= walls_.size())
    throw InputError("", 0, "observe_wall", fmt::format("no wall {}", wall));
  hooks_.wall_observers.resize(walls_.size());
  hooks_.wall_observers[static_cast<std::size_t>(wall)] = std::move(fn);
}

void World::report_wall_contacts() const {
  WallContact c;
  c.step = clock_.step;
  c.dt = clock_.dt;
  for (std::size_t q = 0; q < contacts_.walls.touch.size(); ++q) {
    if (!contacts_.walls.touch[q]) continue;
    const auto wi = static_cast<std::size_t>(contacts_.walls.wall[q]);
    if (wi >= hooks_.wall_observers.size() || !hooks_.wall_observers[wi]) continue;
    const auto i = static_cast<std::size_t>(contacts_.walls.owner[q]);
    c.wall = static_cast<int>(wi);
    c.element = contacts_.walls.element[q];
    c.particle = p_.id[i];
    c.point = contacts_.walls.point[q];
    c.normal = contacts_.walls.observed_normal[q];  // taken with the force (the particle has moved on since)
    c.force = -contacts_.walls.force[q];
    c.velocity = contacts_.walls.observed_velocity[q];
    c.mass = p_.contact_mass[i];
    c.radius = p_.radius[i];
    hooks_.wall_observers[wi](c);
  }
}

}  // namespace chutelab::dem
