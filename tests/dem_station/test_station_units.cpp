// The DEM station's bookkeeping without running a DEM: steady-state detection and block means on
// synthetic series, the result cache, the [dem] table and quality presets, impossible geometry,
// and how the harness's effects map onto DEM inputs.
#define BOOST_TEST_MODULE dem_station_units
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>

#include <fmt/format.h>

#include "core/input_error.h"
#include "dem/contact/mixing.h"
#include "dem/insertion.h"
#include "dem/station/belt_cohesion.h"
#include "dem/station/cache.h"
#include "dem/station/run.h"
#include "dem/walls/stl.h"
#include "dem/world.h"
#include "dem/station/scene.h"
#include "dem/station/settings.h"
#include "dem/station/steady_state.h"
#include "effects/registry.h"
#include "tiny_station.h"
#include "validation/models/dem_model.h"

using namespace chutelab;
using namespace chutelab::dem::station;
namespace fs = std::filesystem;

namespace {

// Gaussian noise from the DEM's own generator (Box-Muller), deterministic.
struct Noise {
  std::uint64_t state = 99;
  double operator()() {
    const double u1 = std::max(dem::uniform01(state), 1e-300), u2 = dem::uniform01(state);
    return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * M_PI * u2);
  }
};

// A [dem] table read_dem_table must refuse, naming this field and line.
void check_table_refused(const fs::path& file, const std::string& field, long line) {
  try {
    read_dem_table(file.string());
    BOOST_FAIL(file.string() + " accepted");
  } catch (const InputError& e) {
    BOOST_TEST(e.field() == field);
    BOOST_TEST(e.line() == line);
  }
}

fs::path temp_dir(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / ("chutelab-dem-station-" + std::to_string(::getpid())) / name;
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

}  // namespace

// A force that ramps up for 0.3 s and then fluctuates by 5 % about 30 N: the window starts after
// the ramp (one detection block later), is a whole number of 0.1 s blocks ending at the end, and
// its mean is 30 N within three standard errors.
BOOST_AUTO_TEST_CASE(steady_window_after_a_ramp) {
  Noise noise;
  std::vector<double> t, v;
  for (int k = 1; k <= 400; ++k) {  // 1.2 s at 3 ms
    const double tk = 0.003 * k;
    t.push_back(tk);
    v.push_back(30.0 * std::min(1.0, tk / 0.3) + 1.5 * noise());
  }
  const SteadyWindow w = detect_steady(t, v, SteadyParams{});
  BOOST_TEST(w.found);
  BOOST_TEST(w.start >= 0.3 - 1e-9);
  BOOST_TEST(w.start <= 0.5);
  BOOST_TEST(std::abs((w.end - w.start) / 0.1 - w.blocks) < 1e-9);
  const Estimate e = block_mean(t, v, std::vector<double>(t.size(), 1.0), w.start, w.end, 0.1);
  BOOST_TEST(std::abs(e.value - 30.0) < 3.0 * e.se);
  // White noise: the batch-means standard error is sd / sqrt(samples), within its own scatter.
  const double expected = 1.5 / std::sqrt(static_cast<double>(e.n));
  BOOST_TEST(e.se > 0.4 * expected);
  BOOST_TEST(e.se < 2.0 * expected);
  BOOST_TEST(!drifting(t, v, w.start, w.end, 0.1));
}

// A series that keeps rising: the rig's rule alone may accept part of it (its tolerance grows with
// the scatter of the tail's blocks, and a ramp scatters them), so a window it finds must be flagged
// as drifting, which stops an early end of the run.
BOOST_AUTO_TEST_CASE(no_steady_state_in_a_rising_series) {
  std::vector<double> t, v;
  for (int k = 1; k <= 300; ++k) {
    t.push_back(0.003 * k);
    v.push_back(10.0 + 40.0 * 0.003 * k);  // +40 % per 0.1 s block over the tail's level
  }
  const SteadyWindow w = detect_steady(t, v, SteadyParams{});
  BOOST_TEST((!w.found || drifting(t, v, w.start, w.end, 0.1)));
  BOOST_TEST(drifting(t, v, 0.4, 0.9, 0.1));
}

// A straight line through block means recovers a linear series' change across the window, and the
// ratio of two series' block means (an impact point) is trended the same way.
BOOST_AUTO_TEST_CASE(window_trend_of_a_line) {
  std::vector<double> t, v, num, den;
  for (int k = 1; k <= 300; ++k) {
    const double tk = 0.003 * k;
    t.push_back(tk);
    v.push_back(2.0 + 1.5 * tk);  // +0.75 over a 0.5 s window
    den.push_back(20.0);
    num.push_back(20.0 * (0.1 - 0.01 * tk));  // a ratio falling by 5 mm over 0.5 s
  }
  const WindowTrend tr = window_trend(t, v, 0.4, 0.9, 0.1);
  BOOST_TEST(tr.blocks == 5);
  // Block means of a line are the line at their samples' mean time; 3 ms samples do not divide the
  // 0.1 s blocks evenly (33 or 34 each), which moves those times by up to 1.5 ms: 0.1 % of the change.
  BOOST_TEST(std::abs(tr.change() - 0.75) < 1e-3 * 0.75);
  BOOST_TEST(tr.drifting());
  const WindowTrend rt = window_trend_ratio(t, num, den, 0.4, 0.9, 0.1);
  BOOST_TEST(std::abs(rt.change() + 0.005) < 1e-3 * 0.005);
  BOOST_TEST(rt.drifting(0.0));
  // Two blocks cannot show a trend.
  BOOST_TEST(!window_trend(t, v, 0.7, 0.9, 0.1).drifting());
}

// A run whose R_n is steady while R_s still rises and the impact point still moves down the face:
// one note for each of the two, none for R_n; a flat run has none.
BOOST_AUTO_TEST_CASE(window_drifts_name_the_moving_loads) {
  Noise noise;
  StationResult r;
  r.window = SteadyWindow{true, 0.4, 0.9, 5};
  for (int k = 1; k <= 300; ++k) {
    const double tk = 0.003 * k;
    ForceSample f;
    f.t = tk;
    f.normal = 40.0 + 0.4 * noise();
    f.shear = 2.0 + 2.0 * (tk - 0.4) + 0.05 * noise();  // +1 N across the window, 40 % of its mean
    f.moment = -f.normal * (0.12 - 0.02 * (tk - 0.4));  // 10 mm down the face across the window
    r.forces.push_back(f);
  }
  const std::vector<WindowDrift> notes = window_drifts(r);
  BOOST_TEST_REQUIRE(notes.size() == 2u);
  BOOST_TEST(notes[0].load == "R_s");
  BOOST_TEST(notes[0].note.rfind("R_s still rises", 0) == 0, notes[0].note);
  BOOST_TEST(notes[1].load == "impact point");
  BOOST_TEST(notes[1].note.find("moves down the face") != std::string::npos, notes[1].note);
  BOOST_TEST(notes[1].note.find("10.0 mm") != std::string::npos, notes[1].note);

  StationResult flat = r;
  for (auto& f : flat.forces) {
    f.shear = 2.5 + 0.05 * noise();
    f.moment = -f.normal * 0.11;
  }
  BOOST_TEST(window_drifts(flat).empty());
  StationResult short_window = r;
  short_window.window = SteadyWindow{true, 0.7, 0.9, 2};
  BOOST_TEST(window_drifts(short_window).empty());
}

// The window judged on all three load-cell channels starts where the last of them settles: here R_n
// is steady from 0.3 s and R_s ramps until 0.8 s. On R_n alone the window starts right after
// R_n's ramp; on all three, once R_s is inside the rule's 10 % band (2 + 2.5 t = 3.6 at 0.64 s),
// and R_s's mean is then its plateau within that band's share of the window (1 %).
BOOST_AUTO_TEST_CASE(steady_window_on_all_loads_waits_for_the_shear) {
  Noise noise;
  StationSeries x;
  for (int k = 1; k <= 433; ++k) {  // 1.3 s at 3 ms
    const double tk = 0.003 * k;
    x.t.push_back(tk);
    x.normal.push_back(40.0 * std::min(1.0, tk / 0.3) + 0.4 * noise());
    x.shear.push_back(2.0 + 2.0 * std::min(1.0, tk / 0.8) + 0.05 * noise());
    x.moment.push_back(-x.normal.back() * 0.1);
  }
  RunSettings s;
  const SteadyWindow on_normal = load_cell_window(x, s);
  BOOST_TEST(on_normal.found);
  BOOST_TEST(on_normal.start < 0.5);
  s.steady_all_loads = true;
  const SteadyWindow on_all = load_cell_window(x, s);
  BOOST_TEST(on_all.found);
  BOOST_TEST(on_all.start >= 0.64);
  BOOST_TEST(std::abs((on_all.end - on_all.start) / 0.1 - on_all.blocks) < 1e-9);
  const Estimate rs = block_mean(x.t, x.shear, std::vector<double>(x.t.size(), 1.0), on_all.start, on_all.end, 0.1);
  BOOST_TEST(std::abs(rs.value - 4.0) < 0.04);
  // The same series judged on R_n alone averages much of the ramp.
  const Estimate early = block_mean(x.t, x.shear, std::vector<double>(x.t.size(), 1.0), on_normal.start, on_normal.end, 0.1);
  BOOST_TEST(early.value < rs.value - 0.2);
}

// [dem] steady_on reaches the settings and the cache key only when it is "all"; an override wins;
// anything else is refused naming the key and its line.
BOOST_AUTO_TEST_CASE(steady_on_table_key) {
  const fs::path d = temp_dir("steady_on");
  std::ofstream(d / "all.toml") << "[dem]\nsteady_on = \"all\"\n";
  std::ofstream(d / "normal.toml") << "[dem]\nsteady_on = \"normal\"\n";
  std::ofstream(d / "bad.toml") << "[dem]\n\nsteady_on = \"shear\"\n";
  const RunSettings all = resolve(read_dem_table((d / "all.toml").string()), SettingsOverrides{});
  const RunSettings normal = resolve(read_dem_table((d / "normal.toml").string()), SettingsOverrides{});
  BOOST_TEST(all.steady_all_loads);
  BOOST_TEST(!normal.steady_all_loads);
  BOOST_TEST(canonical(all).find("steady_on = all") != std::string::npos);
  BOOST_TEST(canonical(normal) == canonical(resolve(DemTable{}, SettingsOverrides{})));
  SettingsOverrides o;
  o.set("steady_on", "normal");
  BOOST_TEST(!resolve(read_dem_table((d / "all.toml").string()), o).steady_all_loads);
  check_table_refused(d / "bad.toml", "dem.steady_on", 3);
}

// The cache gives back exactly what was stored, and only for the same key.
BOOST_AUTO_TEST_CASE(cache_round_trip) {
  StationResult r;
  r.condition = "V3-41";
  r.quality = "quick";
  r.diameter = 0.0136;
  r.dt = 7.1e-5;
  r.simulated_time = 0.7;
  r.steps = 9876;
  r.rebuilds = 1234;
  r.early_stop = true;
  r.window = {true, 0.4, 0.7, 3};
  r.normal_force = {35.6874512, 0.356, 101};
  r.impact_point_y = {0.0559, 0.0009, 101};
  r.trajectory.push_back({0.1, {0.14, 0.001, 30}, {0.12, 0.001, 30}, {0.13, 0.0005, 30}});
  r.forces.push_back({0.003, 1.0, 2.0, -0.01, 0.004, 0.01, 0.0, 0.001});
  r.side_view.push_back({0.1f, 0.12f, -0.02f, 3.0f});
  r.notes.push_back("a note with spaces, and commas");
  const auto back = from_text(to_text(r));
  BOOST_REQUIRE(back.has_value());
  BOOST_TEST(to_text(*back) == to_text(r));
  BOOST_TEST(back->normal_force.value == r.normal_force.value);
  BOOST_TEST(back->rebuilds == 1234);
  // An entry written before the rebuild count was stored reads back as unknown, not as 0 rebuilds.
  std::string old_entry = to_text(r);
  const auto run_at = old_entry.find("\nrun ");
  const auto run_end = old_entry.find('\n', run_at + 1);
  old_entry.erase(old_entry.rfind(' ', run_end), run_end - old_entry.rfind(' ', run_end));
  const auto old_back = from_text(old_entry);
  BOOST_REQUIRE(old_back.has_value());
  BOOST_TEST(old_back->rebuilds == -1);
  BOOST_TEST(old_back->steps == 9876);

  const ResultCache cache(temp_dir("cache").string());
  BOOST_TEST(!cache.load("key A\n").has_value());
  BOOST_TEST(cache.store("key A\n", r).written);
  const auto hit = cache.load("key A\n");
  BOOST_REQUIRE(hit.has_value());
  BOOST_TEST(hit->steps == 9876);
  BOOST_TEST(!cache.load("key B\n").has_value());
  // A damaged file is a miss, not an error.
  std::ofstream(cache.path_for("key A\n")) << "garbage";
  BOOST_TEST(!cache.load("key A\n").has_value());
}

// [dem] table: values override the preset, command-line overrides beat both; unknown keys and bad
// values are errors naming the key and line.
BOOST_AUTO_TEST_CASE(dem_table_and_presets) {
  const fs::path d = temp_dir("table");
  std::ofstream(d / "setup.toml") << "name = \"x\"\n[dem]\nquality = \"standard\"\ndt_fraction = 0.05\n"
                                     "particle_diameter_mm = 11.0\n";
  const DemTable t = read_dem_table((d / "setup.toml").string());
  SettingsOverrides o;
  RunSettings s = resolve(t, o);
  BOOST_TEST((s.quality == Quality::standard));
  BOOST_TEST(s.dt_fraction == 0.05);
  BOOST_TEST(s.particle_diameter == 0.011);
  o.set_quality(Quality::quick);
  o.set("diameter_mm", 20.0);
  s = resolve(t, o);
  BOOST_TEST((s.quality == Quality::quick));
  BOOST_TEST(s.particle_diameter == 0.02);
  BOOST_TEST(s.dt_fraction == 0.05);  // the table still applies on top of the quick preset
  BOOST_TEST(preset(Quality::paper).particle_diameter == 5.6e-3);
  BOOST_TEST(preset(Quality::standard).particle_diameter == 0.0);  // the dataset's own

  std::ofstream(d / "bad.toml") << "name = \"x\"\n[dem]\nquallity = \"quick\"\n";
  check_table_refused(d / "bad.toml", "dem.quallity", 3);
  std::ofstream(d / "bad2.toml") << "[dem]\nquality = \"fast\"\n";
  BOOST_CHECK_THROW(read_dem_table((d / "bad2.toml").string()), InputError);
  std::ofstream(d / "bad3.toml") << "[dem.stl]\nplate = \"missing.stl\"\n";
  BOOST_CHECK_THROW(read_dem_table((d / "bad3.toml").string()), InputError);
  SettingsOverrides bad;
  bad.set("dt_fraction", 2.0);
  BOOST_CHECK_THROW(resolve(DemTable{}, bad), InputError);
}

// [dem.feed] insertion = "face": the stream inserter (Inserter::hold_to_face) with a batch every
// (box height - d) / v_down, so that each held batch has crossed the face when the next arrives;
// "box" and no key keep the free insertion and the recipe's cache key; a clump feed refuses it.
BOOST_AUTO_TEST_CASE(dem_feed_insertion_through_the_face) {
  const fs::path d = temp_dir("feed-face");
  std::ofstream(d / "setup.toml") << "[dem.feed]\nface_low_mm = 62.0\nface_high_mm = 94.0\ninsertion = \"face\"\n";
  const DemTable t = read_dem_table((d / "setup.toml").string());
  RunSettings s = resolve(t, {}, Quality::standard);
  BOOST_TEST(s.insert_at_face);
  BOOST_TEST(canonical(s).find("insert_at_face = true") != std::string::npos);
  BOOST_TEST(canonical(preset(Quality::standard)).find("insert_at_face") == std::string::npos);
  Station st = test::tiny_station();
  s.particle_diameter = 0.0136;
  s.threads = 1;
  const Scene sc = build_scene(st, s, t, {});
  const dem::Inserter& in = sc.world->inserters()[static_cast<std::size_t>(sc.inserter)];
  BOOST_TEST(in.hold_to_face);
  BOOST_TEST(in.hold_axis == 1);
  BOOST_TEST(std::abs(in.region.lo.y() - (sc.belt.tangent_point.y() + 0.062)) < 1e-12);
  BOOST_TEST(std::abs(in.interval - (3.5 * 0.0136 - 0.0136) / 1.0) < 1e-12);  // the box is at least 3.5 d high
  std::ofstream(d / "box.toml") << "[dem.feed]\ninsertion = \"box\"\n";
  BOOST_TEST(!resolve(read_dem_table((d / "box.toml").string()), {}, Quality::standard).insert_at_face);
  std::ofstream(d / "bad.toml") << "[dem.feed]\ninsertion = \"stream\"\n";
  BOOST_CHECK_THROW(read_dem_table((d / "bad.toml").string()), InputError);
  RunSettings clump = s;
  clump.particle_shape = ParticleShape::clump;
  BOOST_CHECK_THROW(build_scene(st, clump, t, {}), InputError);
}

// [dem.feed]: the dataset's own feeder. The LIGGGHTS rig's face ends 0.15 + 0.075 V_b m before the
// pulley and its relaxation (of the whole velocity) ends 50 mm past the face; the belt starts at the
// declared x. Without the table the scene and the cache key are the recipe's.
BOOST_AUTO_TEST_CASE(dem_feed_table_places_the_feeder) {
  const fs::path d = temp_dir("feed");
  std::ofstream(d / "setup.toml") << "[dem.feed]\nface_length_mm = 300.0\nface_low_mm = 30.0\nface_high_mm = 62.0\n"
                                     "face_end_mm = 150.0\nface_end_time_s = 0.075\nrelax_components = \"all\"\n"
                                     "relax_end = \"face\"\nrelax_past_mm = 50.0\nbelt_start_mm = -950.0\n";
  const DemTable t = read_dem_table((d / "setup.toml").string());
  RunSettings s = resolve(t, {}, Quality::standard);
  BOOST_TEST(s.relax_all);
  BOOST_TEST(s.relax_from_face);
  BOOST_TEST(std::abs(s.insert_depth - 0.032) < 1e-12);
  Station st = test::tiny_station();
  s.particle_diameter = 0.0136;
  s.threads = 1;
  const Scene sc = build_scene(st, s, t, {});
  const double vb = st.belt_speed;
  BOOST_TEST(std::abs(sc.feed_s_end - -(0.15 + 0.075 * vb)) < 1e-12);
  BOOST_TEST(std::abs(sc.feed_s_begin - (sc.feed_s_end - 0.3)) < 1e-12);
  BOOST_TEST(std::abs(sc.relax_s_end - (sc.feed_s_end + 0.05)) < 1e-12);
  BOOST_TEST(std::abs(sc.belt_start - -0.95) < 1e-12);  // flat belt: s = x at the tangent point's level
  BOOST_TEST(sc.feeder.all_components);
  // The recipe's key is unchanged by the feed fields it does not set.
  BOOST_TEST(canonical(preset(Quality::standard)).find("relax_all") == std::string::npos);
  BOOST_TEST(canonical(s).find("relax_all = true") != std::string::npos);
  // A falling particle in the zone: "along" keeps its fall, "all" relaxes it too.
  FeederRelaxation f = sc.feeder;
  dem::Particles p;
  p.x.push_back(sc.belt.tangent_point + (sc.feed_s_begin + 0.01) * sc.belt.along + 0.02 * sc.belt.up);
  p.v.push_back(dem::Vec3(vb, -1.0, 0.0));
  p.mass.push_back(1.0);
  std::vector<dem::Vec3> force(1, dem::Vec3::Zero());
  f.add(p, 0, 1, force);
  BOOST_TEST(std::abs(force[0].y() - f.rate * 1.0) < 1e-9);
  f.all_components = false;
  force[0] = dem::Vec3::Zero();
  f.add(p, 0, 1, force);
  BOOST_TEST(std::abs(force[0].y()) < 1e-12);

  std::ofstream(d / "bad.toml") << "[dem.feed]\nrelax_components = \"some\"\n";
  check_table_refused(d / "bad.toml", "dem.feed.relax_components", 2);
  std::ofstream(d / "bad2.toml") << "[dem.feed]\nface_lenght_mm = 300.0\n";
  BOOST_CHECK_THROW(read_dem_table((d / "bad2.toml").string()), InputError);
  std::ofstream(d / "bad3.toml") << "[dem.feed]\nface_low_mm = 60.0\nface_high_mm = 30.0\n";
  BOOST_CHECK_THROW(read_dem_table((d / "bad3.toml").string()), InputError);
}

// Impossible geometry is refused before any particle moves.
BOOST_AUTO_TEST_CASE(impossible_scenes_are_input_errors) {
  const RunSettings s = test::tiny_settings();
  Station st = test::tiny_station();
  st.plate_distance = 0.13;  // the face would cut the pulley (R_b = 130 mm)
  try {
    build_scene(st, s, {}, {});
    BOOST_FAIL("plate through the pulley accepted");
  } catch (const InputError& e) {
    BOOST_TEST(e.field() == "plate_distance_mm");
  }
  st = test::tiny_station();
  RunSettings big = s;
  big.particle_diameter = 0.05;  // 50 mm spheres in a 120 mm load
  BOOST_CHECK_THROW(build_scene(st, big, {}, {}), InputError);
  st.mass_flow = 0.0;
  BOOST_CHECK_THROW(build_scene(st, s, {}, {}), InputError);
}

// The harness's effects reach the DEM through what they change: the feed rate, the particle-plate
// friction, a body force in flight and the belt's adhesion; effects without a DEM counterpart leave
// a note.
BOOST_AUTO_TEST_CASE(effects_map_onto_dem_inputs) {
  const Station st = test::tiny_station();
  auto fx = [](const std::string& s) { return effects::instantiate({effects::parse_setting(s, false)}); };
  auto joined = [](const std::vector<std::string>& v) {
    std::string s;
    for (const auto& x : v) s += x + "\n";
    return s;
  };

  const auto bias = validation::dem_effect_inputs(st, fx("mass_flow_bias=0.1"));
  BOOST_TEST(std::abs(bias.station.mass_flow - 2.75) < 1e-12);
  BOOST_TEST(joined(bias.notes).find("honoured") != std::string::npos);

  const auto fric = validation::dem_effect_inputs(st, fx("plate_friction=0.1"));
  BOOST_REQUIRE(fric.external.plate_friction.has_value());
  BOOST_TEST(std::abs(*fric.external.plate_friction - 0.37) < 1e-12);

  const auto drag = validation::dem_effect_inputs(st, fx("air_drag=0.5"));
  BOOST_REQUIRE(static_cast<bool>(drag.external.flight));
  // a = -(3 rho_air C_d / (4 rho_s d)) |v| v with the dataset's real particles (9 mm, 1000 kg/m^3)
  const double k = 3.0 * 1.204 * 0.5 / (4.0 * 1000.0 * 9e-3);
  const Eigen::Vector2d a = drag.external.flight(Eigen::Vector2d(3.0, -4.0));
  BOOST_TEST(std::abs(a.x() - (-k * 5.0 * 3.0)) < 1e-12);
  BOOST_TEST(std::abs(a.y() - (-k * 5.0 * -4.0)) < 1e-12);
  BOOST_TEST(drag.key != validation::dem_effect_inputs(st, fx("air_drag=0.6")).key);

  // Adhesion: the analytical holding acceleration sigma_a / m'' is recognised as the stress sigma_a.
  const auto stick = validation::dem_effect_inputs(st, fx("belt_adhesion=500"));
  BOOST_TEST(std::abs(stick.external.belt_adhesive_stress - 500.0) < 1e-9);
  BOOST_TEST(joined(stick.notes).find("honoured") != std::string::npos);
  BOOST_TEST(joined(stick.notes).find("ignored") == std::string::npos);
  BOOST_TEST(stick.key != validation::dem_effect_inputs(st, {}).key);
  BOOST_TEST(stick.key != validation::dem_effect_inputs(st, fx("belt_adhesion=600")).key);
  BOOST_TEST(canonical(stick.external).find("belt_adhesive_stress = 500\n") != std::string::npos);
  BOOST_TEST(canonical(ExternalInputs{}).empty());  // no effect: the key of runs made before adhesion existed
  const RunSettings quick = preset(Quality::quick);
  BOOST_TEST(validation::dem_cache_key(stick, quick, {}) !=
             validation::dem_cache_key(validation::dem_effect_inputs(st, {}), quick, {}));

  // Belt slip: the belt and the pulley carry the layer at (1 - s) V_b.
  const auto slip = validation::dem_effect_inputs(st, fx("belt_slip=0.1"));
  BOOST_TEST(std::abs(slip.station.belt_speed - 0.9 * st.belt_speed) < 1e-12);
  BOOST_TEST(joined(slip.notes).find("honoured") != std::string::npos);
  BOOST_TEST(slip.key != validation::dem_effect_inputs(st, {}).key);

  for (const char* e : {"stream_spread=5", "plate_rebound=0.2"}) {
    const auto ig = validation::dem_effect_inputs(st, fx(e));
    BOOST_TEST(joined(ig.notes).find("ignored by the DEM") != std::string::npos, e);
    BOOST_TEST(ig.key == validation::dem_effect_inputs(st, {}).key, e);  // the DEM run is the baseline's
  }
  // The instrument effect is the harness's business: no DEM input changes.
  const auto cell = validation::dem_effect_inputs(st, fx("load_cell_offset=2"));
  BOOST_TEST(cell.key == validation::dem_effect_inputs(st, {}).key);
  BOOST_TEST(cell.notes.empty());
}

// belt_cohesion.h's mapping in the DEM engine itself: a sphere of the quick quality (13.6 mm, the
// tiny rig's modulus / 3) hangs under a belt-like mesh with the cohesion mapped from sigma_a, and a
// pull that ramps up over 30 contact periods (quasi-static) to f times the predicted pull-off force
// sigma_a / n. It must hold at f = 0.95 and let go at f = 1.05: the closed form of F_pull is right
// to 5 %, and the per-area count n turns it into sigma_a. Without the cohesion it falls at once.
BOOST_AUTO_TEST_CASE(belt_cohesion_holds_the_adhesive_stress) {
  const double sigma = 300.0, d = 0.0136, r = 0.5 * d, rho = 1000.0;
  const double E = 2.5e7 / 3.0, nu = 0.38;
  auto hangs = [&](double f, bool cohesion) {
    dem::Settings s;
    s.dt = 2e-6;
    s.gravity = dem::Vec3::Zero();
    s.domain = dem::Box{dem::Vec3::Constant(-0.2), dem::Vec3::Constant(0.2)};
    s.rolling = dem::RollingModel::none;
    s.threads = 1;
    s.max_speed = 100.0;  // a released sphere accelerates freely
    s.on_warning = [](const std::string&) {};
    dem::World w(s);
    const int mp = w.materials().add({"particle", E, nu, rho}), mb = w.materials().add({"belt", E, nu, 0.0});
    dem::Interaction in;
    in.friction = 0.7;
    in.restitution = 0.4;
    w.materials().set_interaction(mp, mb, in);
    const double es = dem::effective_youngs_modulus(w.materials().material(mp), w.materials().material(mb));
    in.cohesion_energy_density = cohesion ? belt_cohesion_energy_density(sigma, es) : 0.0;
    w.materials().set_interaction(mp, mb, in);
    // Belt face at y = 0 facing down; the sphere under it at the overlap where elastic push and
    // cohesion balance with no load (F(delta) = 0: delta = 9/4 delta*).
    const double a = 0.05;
    w.add_wall(dem::Wall::mesh("belt", dem::TriangleMesh::from_soup({{dem::Vec3(-a, 0, -a), dem::Vec3(a, 0, -a), dem::Vec3(a, 0, a)},
                                                                     {dem::Vec3(-a, 0, -a), dem::Vec3(a, 0, a), dem::Vec3(-a, 0, a)}}),
                               mb));
    const double k = in.cohesion_energy_density;
    const double delta0 = cohesion ? 9.0 * M_PI * M_PI * k * k * r / (16.0 * es * es) : 1e-7;
    w.add_particle({dem::Vec3(0, -(r - delta0), 0), dem::Vec3::Zero(), dem::Vec3::Zero(), r, mp});
    const double f_pull = sigma / monolayer_contacts_per_area(d);
    const double ramp = 0.1;
    w.set_body_force([&](const dem::Particles&, double t, std::size_t b, std::size_t e, std::vector<dem::Vec3>& force) {
      if (b == 0 && e > 0) force[0].y() -= f * f_pull * std::min(1.0, t / ramp);
    });
    const auto n = static_cast<std::int64_t>(1.2 * ramp / s.dt);
    for (std::int64_t i = 0; i < n; ++i) {
      w.step();
      if (w.particles().x[0].y() < -r) {
        BOOST_TEST_MESSAGE("f = " << f << (cohesion ? "" : " without cohesion") << ": let go at t = " << i * s.dt
                                  << " s, pull " << f * std::min(1.0, i * s.dt / ramp) << " F_pull");
        return false;
      }
    }
    return true;
  };
  const double es = E / (2.0 * (1.0 - nu * nu));
  BOOST_TEST_MESSAGE("sigma_a " << sigma << " Pa -> k_c " << belt_cohesion_energy_density(sigma, es)
                                << " J/m^3, pull-off " << sigma / monolayer_contacts_per_area(d) << " N per contact");
  BOOST_TEST(std::abs(sjkr_pull_off_force(belt_cohesion_energy_density(sigma, es), r, es) -
                      sigma / monolayer_contacts_per_area(d)) < 1e-9 * sigma / monolayer_contacts_per_area(d));
  BOOST_TEST(hangs(0.95, true));
  BOOST_TEST(!hangs(1.05, true));
  BOOST_TEST(!hangs(0.95, false));
}

// A [dem.stl] plate replaces the generated one and is the load cell; its moment reference stays the
// dataset's plate face at y = 0.
BOOST_AUTO_TEST_CASE(stl_plate_replaces_the_generated_plate) {
  const fs::path d = temp_dir("stl");
  dem::TriangleMesh m = dem::TriangleMesh::from_soup(
      {{dem::Vec3(350, 250, -300), dem::Vec3(350, -150, -300), dem::Vec3(350, -150, 300)},
       {dem::Vec3(350, 250, -300), dem::Vec3(350, -150, 300), dem::Vec3(350, 250, 300)}});
  dem::write_stl_binary((d / "plate.stl").string(), m);  // millimetres, like every STL of a dataset
  std::ofstream(d / "setup.toml") << "[dem.stl]\nplate = \"plate.stl\"\n";
  const DemTable t = read_dem_table((d / "setup.toml").string());
  BOOST_REQUIRE(t.stl_plate.has_value());
  const Scene sc = build_scene(test::tiny_station(), test::tiny_settings(), t, {});
  const dem::Wall& plate = sc.world->walls()[static_cast<std::size_t>(sc.plate_wall)];
  BOOST_TEST(plate.name == "plate");
  const auto& mesh = std::get<dem::TriangleMesh>(plate.shape);
  BOOST_TEST(mesh.triangles.size() == 2u);
  BOOST_TEST(std::abs(mesh.bounds().lo.x() - 0.35) < 1e-9);
  BOOST_TEST((plate.load_point - dem::Vec3(0.35, 0.0, 0.0)).norm() < 1e-12);
}

// A troughed belt (wings flattening towards the pulley) under an inclined plate: the scene builds,
// the plate frame follows DESIGN.md (top edge at (Z, top), leaning towards the pulley), and a short
// run stays stable.
BOOST_AUTO_TEST_CASE(troughed_belt_and_inclined_plate) {
  Station st = test::tiny_troughed_station();
  st.plate.angle = 15.0 * M_PI / 180.0;
  RunSettings s = test::tiny_settings();
  s.max_time = 0.12;
  s.min_window = 0.05;
  RunOptions o;
  o.settings = s;
  Scene sc = build_scene(st, s, {}, {});
  const PlateFrame& pf = sc.plate;
  BOOST_TEST(std::abs(pf.reference.y()) < 1e-12);
  BOOST_TEST(pf.reference.x() > st.plate_distance);  // the face leans away below its top edge
  BOOST_TEST(std::abs(pf.into.dot(pf.down)) < 1e-12);
  BOOST_TEST(std::abs(pf.y_at(pf.up_from_reference(pf.top_edge)) - st.plate_top) < 1e-12);
  int transition = 0;
  for (const auto& w : sc.world->walls()) transition += w.name.rfind("belt-transition", 0) == 0;
  BOOST_TEST(transition == 32);  // 2 wings x 8 segments x 2 triangles
  const StationResult r = run_station(st, o);
  BOOST_TEST(r.inserted > 0.1);
  BOOST_TEST(r.escaped == 0.0);
}

namespace {

// A value each field accepts (its lowest, or within an open range), as TOML text and as given.
std::pair<std::string, DemValue> accepted(const DemField& f) {
  DemValue v;
  if (f.kind == DemKind::word) {
    v.word = f.words().back().word;
    return {"\"" + v.word + "\"", v};
  }
  const double x = f.lo <= -1e300 ? 1.0 : !f.lo_open ? f.lo : f.hi < 1e300 ? 0.5 * (f.lo + f.hi) : f.lo + 0.25;
  v.number = x;
  v.whole = static_cast<std::uint64_t>(x);
  return {f.kind == DemKind::whole ? std::to_string(v.whole) : fmt::format("{:.17g}", x), v};
}

// The TOML of one [dem] key (in its table) at line 3 of the file.
std::string toml_of(const DemField& f, const std::string& value) {
  const std::string key(f.key);
  const auto dot = key.find('.');
  if (dot == std::string::npos) return "name = \"x\"\n[dem]\n" + key + " = " + value + "\n";
  return "name = \"x\"\n[dem." + key.substr(0, dot) + "]\n" + key.substr(dot + 1) + " = " + value + "\n";
}

}  // namespace

// Each [dem] setting is declared once, in dem_fields(): every key there is read from setup.toml and
// reaches RunSettings, an out-of-range value is refused naming the file, line and key, and every
// option is accepted by the overrides; the known-keys message lists every key of its table.
BOOST_AUTO_TEST_CASE(every_dem_field_is_read_checked_and_overridable) {
  const fs::path d = temp_dir("fields");
  std::set<std::string_view> options;
  for (const DemField& f : dem_fields()) {
    BOOST_TEST_CONTEXT(f.key) {
      const auto [text, value] = accepted(f);
      std::string toml = toml_of(f, text);
      if (!f.needs.empty()) toml += std::string(dem_field(f.needs).key).substr(dem_field(f.needs).key.find('.') + 1) + " = 0\n";
      std::ofstream(d / "ok.toml") << toml;
      const DemTable t = read_dem_table((d / "ok.toml").string());
      const auto at = std::find_if(t.settings.begin(), t.settings.end(), [&](const DemSetting& g) { return g.field == &f; });
      BOOST_TEST_REQUIRE((at != t.settings.end()));
      BOOST_TEST(at->line == 3);
      RunSettings s = preset(Quality::standard);
      apply(t, s);
      if (const auto m = f.member_of<double>()) BOOST_TEST((s.*m) == value.number * f.to_si);
      if (const auto m = f.member_of<int>()) BOOST_TEST((s.*m) == static_cast<int>(value.whole));
      if (const auto m = f.member_of<std::uint64_t>()) BOOST_TEST((s.*m) == value.whole);
      // Code names the setting by its member and finds this field (or the first that sets it).
      if (!std::holds_alternative<std::monostate>(f.member))
        BOOST_TEST(std::visit([](auto m) { if constexpr (std::is_same_v<decltype(m), std::monostate>) return std::string_view();
                                           else return dem_field(m).key; }, f.member) ==
                   (f.key == "feed.face_length_mm" ? std::string_view("feed_length_mm") : f.key));
      // Refused: a word not in the list, a number past an end of the range, a text for a number.
      std::vector<std::string> bad = {f.kind == DemKind::word ? "\"no-such-word\"" : "\"text\""};
      if (f.kind != DemKind::word && f.hi < 1e300) bad.push_back(fmt::format("{:.17g}", f.hi * 2 + 1));
      if (f.kind == DemKind::number && f.lo > -1e300)
        bad.push_back(fmt::format("{:.17g}", f.zero_means.empty() ? f.lo - 1 : 0.5 * f.lo));
      for (const auto& b : bad) {
        std::ofstream(d / "bad.toml") << toml_of(f, b);
        check_table_refused(d / "bad.toml", "dem." + std::string(f.key), 3);
      }
      if (!f.option.empty()) {
        BOOST_TEST(options.insert(f.option).second);  // one field an option
        BOOST_TEST(dem_option(f.option) == &f);
        SettingsOverrides o;
        if (f.kind == DemKind::word) o.set(f.option, value.word);
        else if (f.kind == DemKind::whole) o.set_whole(f.option, value.whole);
        else o.set(f.option, value.number);
        BOOST_CHECK_NO_THROW(o.check());
        BOOST_TEST(o.find(f.option) != nullptr);
      }
    }
  }
  std::ofstream(d / "unknown.toml") << "[dem]\nno_such_key = 1\n";
  try {
    read_dem_table((d / "unknown.toml").string());
    BOOST_FAIL("unknown key accepted");
  } catch (const InputError& e) {
    for (const DemField& f : dem_fields()) {
      const std::string_view k = f.key.substr(0, f.key.find('.'));
      BOOST_TEST(e.problem().find(k) != std::string::npos, k);
    }
  }
}

// The settings' share of the DEM cache key is the text it always was: cached runs keep their entries.
BOOST_AUTO_TEST_CASE(canonical_text_of_the_default_settings_is_unchanged) {
  const std::string standard =
      "quality = standard\ncontact = hertz-mindlin\nseed = 1\nparticle_diameter = 0\nshear_modulus_scale = 1\n"
      "dt_fraction = 0.10000000000000001\nrayleigh_fraction = 0.20000000000000001\nfeed_length = 0.40000000000000002\n"
      "free_belt = 0.20000000000000001\nbelt_upstream = 0.025000000000000001\ninsert_low = 0.029999999999999999\n"
      "insert_depth = 0.032000000000000001\ninsert_speed_down = 1\ninsert_interval = 0.0030000000000000001\n"
      "relax_rate = 50\nrelax_past = 0.050000000000000003\nmin_time = 0.5\nmax_time = 1.3\nmin_window = 0.5\n"
      "sample_interval = 0.0030000000000000001\nsnapshot_interval = 0.01\ndetect_block = 0.050000000000000003\n"
      "mean_block = 0.10000000000000001\ndetect_tail = 0.40000000000000002\nskin_fraction = 1\n"
      "momentum_plane_fraction = 0.5\n";
  BOOST_TEST(canonical(resolve(DemTable{}, {}, Quality::standard)) == standard);
  // An override of the time limit shortens the earliest stop and the window with it, as a [dem]
  // max_time_s does not (both as they were).
  SettingsOverrides o;
  o.set("max_time", 0.3);
  const RunSettings s = resolve(DemTable{}, o, Quality::standard);
  BOOST_TEST(s.min_time == 0.3);
  BOOST_TEST(s.min_window == 0.15);
}
