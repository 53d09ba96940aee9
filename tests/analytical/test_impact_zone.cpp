#include <boost/test/unit_test.hpp>
#include <cmath>

#include "analytical/impact_zone.h"
#include "validation/dataset.h"

using namespace chutelab;
using namespace chutelab::analytical;
namespace tt = boost::test_tools;

namespace {
Station v3_41() {
  const auto d = validation::read_dataset(CHUTELAB_SOURCE_DIR "/datasets/liggghts-rig",
                                          validation::MeasurementsRequired::no);
  for (const auto& s : d.stations)
    if (s.condition == "V3-41") return s;
  throw std::runtime_error("V3-41 missing");
}

// The outer limits leave turned apart by +-delta (what effects/stream_spread.cpp does; the effect
// library is not linked into this module).
class Spread final : public Effect {
 public:
  explicit Spread(double rad) : d_(rad) {}
  std::string name() const override { return "spread"; }
  void adjust_release(Boundary b, Eigen::Vector2d& v) const override {
    const double t = b == Boundary::upper ? d_ : b == Boundary::lower ? -d_ : 0.0;
    v = Eigen::Vector2d(std::cos(t) * v.x() - std::sin(t) * v.y(), std::sin(t) * v.x() + std::cos(t) * v.y());
  }

 private:
  double d_;
};
}  // namespace

BOOST_AUTO_TEST_SUITE(impact_zone_band)

BOOST_AUTO_TEST_CASE(high_speed_band_is_h_b_tall_and_carries_R_n) {
  // High-speed discharge: both limits leave horizontally at V_b from heights R_b and R_b + h_b, so
  // their parabolas are the same curve shifted by h_b and cut a vertical plate h_b apart.
  const Station st = v3_41();
  const auto a = analyse_transfer(st);
  BOOST_REQUIRE(a.line(Streamline::lower).release.high_speed);
  BOOST_REQUIRE(a.line(Streamline::upper).release.high_speed);
  const ImpactZone z = impact_zone(a);
  BOOST_TEST(!z.top_clipped);
  BOOST_TEST(!z.bottom_clipped);
  BOOST_TEST(z.top_y - z.bottom_y == a.load.height, tt::tolerance(1e-9));
  BOOST_TEST(z.centroid_y < z.top_y);
  BOOST_TEST(z.centroid_y > z.bottom_y);
  BOOST_TEST(z.width == st.belt.loaded_width, tt::tolerance(1e-12));
  // The band carries Korzen's forces whole.
  BOOST_TEST(z.mean_pressure * z.area == a.korzen.normal_force, tt::tolerance(1e-12));
  BOOST_TEST(z.mean_shear_stress * z.area == a.korzen.shear_force, tt::tolerance(1e-12));
}

BOOST_AUTO_TEST_CASE(zone_moves_down_as_the_plate_moves_away) {
  Station st = v3_41();
  double last_top = 1e9, last_bottom = 1e9;
  for (double z_mm : {300.0, 350.0, 400.0, 450.0, 500.0}) {
    st.plate_distance = z_mm * 1e-3;
    const ImpactZone z = impact_zone(analyse_transfer(st));
    BOOST_TEST_CONTEXT("plate at " << z_mm << " mm") {
      BOOST_TEST(z.top_y < last_top);
      BOOST_TEST(z.bottom_y < last_bottom);
    }
    last_top = z.top_y;
    last_bottom = z.bottom_y;
  }
}

BOOST_AUTO_TEST_CASE(spread_widens_the_band_and_the_top_edge_clips_it) {
  const Station st = v3_41();
  const ImpactZone base = impact_zone(analyse_transfer(st));
  const EffectList spread = {std::make_shared<Spread>(5.0 * 3.14159265358979323846 / 180.0)};
  const ImpactZone wide = impact_zone(analyse_transfer(st, spread));
  BOOST_TEST(wide.length() > base.length());
  BOOST_TEST(wide.mean_pressure < base.mean_pressure);  // same R_n over more plate
  // A plate whose top edge sits between the centroid's and the upper limit's hits loses the top of
  // the band: the zone starts at the edge.
  Station low = st;
  low.plate_top = 0.5 * (base.top_y + base.centroid_y);
  const ImpactZone cut = impact_zone(analyse_transfer(low));
  BOOST_TEST(cut.top_clipped);
  BOOST_TEST(cut.top_along == 0.0);
  BOOST_TEST(cut.top_y == low.plate_top, tt::tolerance(1e-12));
}

BOOST_AUTO_TEST_SUITE_END()
