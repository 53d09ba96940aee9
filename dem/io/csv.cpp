#include "dem/io/csv.h"

#include <fmt/format.h>

#include "core/input_error.h"

namespace chutelab::dem {

TimeSeriesCsv::TimeSeriesCsv(const std::string& path, const World& world)
    : out_(path), path_(path), walls_(world.walls().size()) {
  if (!out_) throw InputError(path, 0, "", "cannot write CSV file");
  out_ << "time_s,step,particles,kinetic_J,rotational_J,max_speed_m_s,contacts,wall_contacts";
  for (const auto& w : world.walls())
    for (const char* q : {"Fx_N", "Fy_N", "Fz_N", "Tx_Nm", "Ty_Nm", "Tz_Nm"}) out_ << ',' << w.name << '_' << q;
  out_ << '\n';
}

void TimeSeriesCsv::record(const World& world) {
  if (world.walls().size() != walls_)
    throw InputError(path_, 0, "walls", "the number of walls changed after the CSV header was written");
  const Energy e = world.energy();
  double vmax = 0.0;
  for (const auto& v : world.particles().v) vmax = std::max(vmax, v.norm());
  out_ << fmt::format("{:.9g},{},{},{:.9g},{:.9g},{:.9g},{},{}", world.time(), world.step_count(),
                      world.particles().size(), e.translational, e.rotational, vmax, world.contact_count(),
                      world.wall_contact_count());
  for (const auto& w : world.walls())
    out_ << fmt::format(",{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g}", w.force.x(), w.force.y(), w.force.z(),
                        w.torque.x(), w.torque.y(), w.torque.z());
  out_ << '\n';
  out_.flush();
}

}  // namespace chutelab::dem
