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
  for (std::size_t q = 0; q < wall_list_.touch.size(); ++q) {
    if (!wall_list_.touch[q]) continue;
    const auto wi = static_cast<std::size_t>(wall_list_.wall[q]);
    if (wi >= wall_observers_.size() || !wall_observers_[wi]) continue;
    const auto i = static_cast<std::size_t>(wall_list_.owner[q]);
    c.wall = static_cast<int>(wi);
    c.element = wall_list_.element[q];
    c.particle = p_.id[i];
    c.point = wall_list_.point[q];
    c.normal = wall_list_.observed_normal[q];  // taken with the force (the particle has moved on since)
    c.force = -wall_list_.force[q];
    c.velocity = wall_list_.observed_velocity[q];
    c.mass = p_.contact_mass[i];
    c.radius = p_.radius[i];
    wall_observers_[wi](c);
  }
}

}  // namespace chutelab::dem
