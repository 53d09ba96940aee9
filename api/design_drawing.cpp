#include "api/design_drawing.h"

#include "analytical/impact_zone.h"
#include "analytical/streamline_path.h"

namespace chutelab::api {

// The drawings name the chain's streamlines by their own enum, in the same order.
static_assert(static_cast<int>(analytical::Streamline::lower) == static_cast<int>(reports::Streamline::lower) &&
              static_cast<int>(analytical::Streamline::upper) == static_cast<int>(reports::Streamline::upper) &&
              static_cast<int>(analytical::Streamline::cema_centroid) == static_cast<int>(reports::Streamline::cema_centroid) &&
              static_cast<int>(analytical::Streamline::korzen_centroid) == static_cast<int>(reports::Streamline::korzen_centroid));

reports::DesignDrawing design_drawing(const analytical::TransferAnalysis& a) {
  reports::DesignDrawing d;
  d.station = a.station;
  d.load_height = a.load.height;
  d.load_contact_width = a.load.contact_width;
  d.thickness_from_continuity = a.thickness_from_continuity;
  for (std::size_t i = 0; i < a.streamlines.size(); ++i) {
    const auto& f = a.streamlines[i];
    auto& l = d.lines[static_cast<std::size_t>(f.which)];
    l.path = analytical::streamline_path(a, f.which);
    l.release = f.release.position;
    l.high_speed = f.release.high_speed;
    l.release_ratio = f.release.ratio;
    if (f.hit) l.hit = reports::DesignDrawing::Line::Hit{f.hit->point.position, f.hit->alpha, f.hit->on_plate};
  }
  const analytical::ImpactZone z = analytical::impact_zone(a);
  d.zone = {z.top_along, z.bottom_along, z.top_y, z.bottom_y, z.width, z.mean_pressure, z.mean_shear_stress,
            z.top_clipped, z.bottom_clipped};
  d.stationary_flow = a.korzen.stationary_flow;
  d.shear_equation = std::string(name(a.korzen.shear_equation));
  d.plate_friction = a.plate_interaction.friction;
  return d;
}

}  // namespace chutelab::api
