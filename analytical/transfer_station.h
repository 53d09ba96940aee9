#pragma once
// The whole analytical chain for one condition: load shape -> Booth discharge of each streamline ->
// flight to the plate -> Korzen impact. Both analytical models and `estimate` read from this.
#include <optional>
#include <string_view>

#include "analytical/booth.h"
#include "analytical/effect.h"
#include "analytical/flight.h"
#include "analytical/korzen.h"
#include "analytical/load_shape.h"
#include "core/rig.h"

namespace chutelab::analytical {

enum class Streamline { lower, upper, cema_centroid, korzen_centroid };
inline constexpr std::array<Streamline, 4> kAllStreamlines = {
    Streamline::lower, Streamline::upper, Streamline::cema_centroid, Streamline::korzen_centroid};
std::string_view name(Streamline s);

struct StreamlineFlight {
  Streamline which = Streamline::lower;
  double height_above_belt = 0.0;  // e, m
  Release release;
  Trajectory trajectory{FlightPoint{}, 9.80665};
  std::optional<PlateHit> hit;     // absent when the streamline never reaches the plate line
};

struct TransferAnalysis {
  Station station;                 // as given
  OperatingPoint operating;        // after effects (e.g. a biased mass-flow reading)
  bool thickness_from_continuity = false;
  LoadShape load;                  // h_b = load.height, CEMA a1 = load.centroid_height
  PlateLine plate;
  std::array<StreamlineFlight, 4> streamlines;
  PlateInteraction plate_interaction;
  KorzenResult korzen;             // on the Korzen centroid streamline (0.5 h_b)

  const StreamlineFlight& line(Streamline s) const {
    return streamlines[static_cast<std::size_t>(s)];
  }
  double drop_height() const;      // release to impact, CEMA centroid, m
  double flight_time() const;      // CEMA centroid, s
};

// What a caller that analyses one station many times (a fit of effect strengths) keeps between
// the analyses: the load shape of the last operating point. Finding it is a bisection over
// circular segments, a third of an analysis, and only an effect on the operating point (belt
// speed, delivered mass flow) changes it. One memo belongs to one station.
struct TransferMemo {
  std::optional<OperatingPoint> operating;
  // What else the load shape depends on: an effect on the record may change it.
  Belt belt;
  double bulk_density = 0.0;
  std::optional<double> stream_thickness;
  LoadShape load;
};

// Throws InputError for impossible geometry: plate behind the pulley, a centroid stream that
// misses the plate, a load that does not fit the belt. With a memo the result is the same, bit
// for bit: the load shape is reused only for the very same operating point.
TransferAnalysis analyse_transfer(const Station& station, const EffectList& effects = {},
                                  TransferMemo* memo = nullptr);

// The largest plate distance at which both centre lines still meet the plate above its foot, with
// the plate's top, angle and height of `a` kept (the bound whose breach analyse_transfer names);
// nullopt when none does.
std::optional<double> farthest_plate_distance(const TransferAnalysis& a);

}  // namespace chutelab::analytical
