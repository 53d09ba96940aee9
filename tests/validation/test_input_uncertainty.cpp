// u_input by sensitivity coefficients: the coefficients against closed forms of the analytical
// chain and against independent finite differences, the combination in quadrature, the rule for an
// expensive model, the dataset's input-uncertainty columns and [uncertainty] table, and the parts
// of u_val in errors.csv.
#include <boost/test/unit_test.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <fmt/format.h>

#include "core/input_error.h"
#include "core/units.h"
#include "validation/dataset.h"
#include "validation/strength_fit.h"
#include "validation/harness.h"
#include "validation/input_uncertainty.h"
#include "validation/output_files.h"
#include "../cli/cli_runner.h"

using namespace chutelab;
using namespace chutelab::validation;
namespace fs = std::filesystem;
namespace tt = boost::test_tools;

namespace {

const Setup& grima() {
  static const Setup s = read_setup(CHUTELAB_SOURCE_DIR "/datasets/grima2010/setup.toml");
  return s;
}

// 3 m/s, 35 t/h, plate at 450 mm: a high-speed release (V_b^2 / (g R_b) = 7) on a flat belt, well
// inside Korzen's stationary flow, with h_b stated.
Station station(double vb = 3.0) {
  return make_station(grima(), "t", vb, 35.0 * units::tph, 0.45, 0.25, 0.03);
}

const RigField* field(std::string_view section, std::string_view key) {
  for (const auto& f : rig_fields())
    if (f.section == section && f.key == key) return &f;
  throw std::logic_error("no such field");
}

const InputSensitivity& find(const std::vector<InputSensitivity>& s, const std::string& input) {
  for (const auto& x : s)
    if (x.input == input) return x;
  throw std::logic_error("input not perturbed: " + input);
}

// Every input the tests perturb: ~1-2 % of each value, as a dataset would state them.
InputUncertainties typical() {
  InputUncertainties u;
  u.belt_speed = 0.03;
  u.mass_flow = 0.5 * units::tph;
  u.plate_distance = 2e-3;
  u.plate_top = 2e-3;
  u.stream_thickness = 1e-3;
  u.rig = {{field("belt", "pulley_diameter_mm"), 1e-3},
           {field("material", "bulk_density_kgm3"), 10.0},
           {field("material", "friction_plate"), 0.02},
           {field("", "gravity_mps2"), 0.01}};
  return u;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(input_uncertainty_tests)

// With h_b given the 0.5 h_b streamline does not depend on the flow, and Korzen's R_n = m_s V_pn
// is linear in m_s: dR_n/dm = R_n/m. A central difference of a linear function is exact, so only
// rounding remains (1e-9 relative).
BOOST_AUTO_TEST_CASE(korzen_normal_force_is_linear_in_mass_flow) {
  const auto korzen = make_model("korzen");
  const Station st = station();
  InputUncertainties u;
  u.mass_flow = 1.0 * units::tph;
  const auto p = korzen->predict(st, {}, {});
  const auto s = sensitivities(*korzen, st, u, {}, {});
  BOOST_REQUIRE_EQUAL(s.size(), 1u);
  const double rn = *p.values[Quantity::normal_force];
  BOOST_TEST(*s[0].coefficient[Quantity::normal_force] == rn / st.mass_flow, tt::tolerance(1e-9));
  // The impact speed does not depend on the flow either.
  BOOST_TEST(std::abs(*s[0].coefficient[Quantity::impact_velocity]) < 1e-9);
}

// Booth's lower streamline for a high-speed release from a flat belt leaves the top of the pulley
// horizontally at V_b: y(x) = R_b - g x^2 / (2 V_b^2). Hence dy/dV_b = g x^2 / V_b^3 (central
// difference truncation 2 (u/V_b)^2 = 2e-4 relative at u = 0.03 m/s; tolerance 1e-3),
// dy/d(pulley diameter) = 1/2, dy/dg = -x^2/(2 V_b^2) and dy/d(plate top) = 0 (exact: linear or
// constant, rounding only).
BOOST_AUTO_TEST_CASE(booth_lower_streamline_closed_form) {
  const auto booth = make_model("booth-cema");
  const Station st = station();
  const double x = 0.3, g = st.gravity, vb = st.belt_speed, rb = st.belt.belt_radius();
  const std::vector<TrajectoryQuery> q = {{Boundary::lower, x}};
  const auto p = booth->predict(st, {}, {q, false});
  BOOST_REQUIRE(p.trajectory.at(0));
  BOOST_TEST(*p.trajectory[0] == rb - g * x * x / (2 * vb * vb), tt::tolerance(1e-9));
  const auto s = sensitivities(*booth, st, typical(), {}, q);
  BOOST_TEST(*find(s, "belt_speed_mps").trajectory[0] == g * x * x / (vb * vb * vb), tt::tolerance(1e-3));
  BOOST_TEST(*find(s, "belt.pulley_diameter_mm").trajectory[0] == 0.5, tt::tolerance(1e-7));
  BOOST_TEST(*find(s, "gravity_mps2").trajectory[0] == -x * x / (2 * vb * vb), tt::tolerance(1e-7));
  BOOST_TEST(std::abs(*find(s, "plate_top_mm").trajectory[0]) < 1e-9);
  BOOST_TEST(std::abs(*find(s, "material.friction_plate").trajectory[0]) < 1e-9);
}

// Every coefficient of both cheap models against an independent central difference with a step
// twenty times smaller. The two agree to the curvature of the response over ±u (inputs of 1-2 %
// here, smooth closed forms away from any switch of the chain): 2 % relative, or 1e-9 absolute
// for a coefficient that is zero.
BOOST_AUTO_TEST_CASE(coefficients_match_independent_finite_differences) {
  const Station st = station();
  const InputUncertainties u = typical();
  const std::vector<TrajectoryQuery> q = {{Boundary::upper, 0.2}, {Boundary::lower, 0.35}, {Boundary::centre, 0.4}};
  int checked = 0;
  for (const char* name : {"korzen", "booth-cema"}) {
    const auto m = make_model(name);
    const auto s = sensitivities(*m, st, u, {}, q);
    BOOST_TEST(s.size() == 9u);
    auto reference = [&](const std::string& input, double h, auto pick) {
      auto moved = [&](double dx) {
        Station x = st;
        if (input == "belt_speed_mps") x.belt_speed += dx;
        else if (input == "mass_flow_tph") x.mass_flow += dx;
        else if (input == "plate_distance_mm") x.plate_distance += dx;
        else if (input == "plate_top_mm") x.plate_top += dx;
        else if (input == "stream_thickness_mm") *x.stream_thickness += dx;
        else if (input == "belt.pulley_diameter_mm") x.belt.pulley_diameter += dx;
        else if (input == "material.bulk_density_kgm3") x.material.bulk_density += dx;
        else if (input == "material.friction_plate") x.material.friction_plate += dx;
        else if (input == "gravity_mps2") x.gravity += dx;
        else throw std::logic_error(input);
        return pick(m->predict(x, {}, {q, false}));
      };
      return (moved(h) - moved(-h)) / (2 * h);
    };
    for (const auto& is : s) {
      const double h = is.u / 20.0;
      for (Quantity qq : kAllQuantities) {
        if (!is.coefficient[qq]) continue;
        const double ref = reference(is.input, h, [qq](const ModelPrediction& p) { return *p.values[qq]; });
        BOOST_TEST_CONTEXT(name << " d" << info(qq).symbol << "/d" << is.input) {
          BOOST_TEST(std::abs(*is.coefficient[qq] - ref) <= 0.02 * std::abs(ref) + 1e-9);
        }
        ++checked;
      }
      for (std::size_t t = 0; t < q.size(); ++t) {
        if (!is.trajectory[t]) continue;
        const double ref = reference(is.input, h, [t](const ModelPrediction& p) { return *p.trajectory[t]; });
        BOOST_TEST_CONTEXT(name << " dy" << t << "/d" << is.input) {
          BOOST_TEST(std::abs(*is.trajectory[t] - ref) <= 0.02 * std::abs(ref) + 1e-9);
        }
        ++checked;
      }
    }
  }
  BOOST_TEST(checked > 60);
}

BOOST_AUTO_TEST_CASE(combined_in_quadrature_and_empty_without_inputs) {
  const auto korzen = make_model("korzen");
  const Station st = station();
  const auto u = typical();
  const auto p = korzen->predict(st, {}, {});
  const auto r = input_uncertainty(*korzen, st, u, {}, {}, p);
  const auto s = sensitivities(*korzen, st, u, {}, {});
  for (Quantity q : kAllQuantities) {
    if (!p.values[q]) continue;
    double sum = 0.0;
    for (const auto& is : s) sum += std::pow(*is.coefficient[q] * is.u, 2);
    BOOST_REQUIRE(r.u[q]);
    BOOST_TEST(*r.u[q] == std::sqrt(sum), tt::tolerance(1e-12));
    BOOST_TEST(*r.u[q] > 0.0);
  }
  const auto none = input_uncertainty(*korzen, st, InputUncertainties{}, {}, {}, p);
  for (Quantity q : kAllQuantities) BOOST_TEST(!none.u[q]);
  // Stated, but zero: estimated, and zero.
  InputUncertainties zero;
  zero.belt_speed = 0.0;
  const auto z = input_uncertainty(*korzen, st, zero, {}, {}, p);
  BOOST_TEST(*z.u[Quantity::normal_force] == 0.0);
}

namespace {
// An "expensive" code whose forces are 1.3x Korzen's and whose stream is 10 mm above Booth's.
class Expensive final : public Model {
 public:
  std::string name() const override { return "fake-dem"; }
  std::string description() const override { return "expensive stand-in"; }
  bool expensive() const override { return true; }
  ModelPrediction predict(const Station& st, const analytical::EffectList& fx,
                          const PredictRequest& req) const override {
    ++calls;
    auto p = korzen_->predict(st, fx, req);
    for (Quantity q : {Quantity::normal_force, Quantity::shear_force, Quantity::resultant_force})
      *p.values[q] *= 1.3;
    p.trajectory = booth_->predict(st, fx, req).trajectory;
    for (auto& y : p.trajectory) *y += 0.01;
    return p;
  }
  mutable int calls = 0;

 private:
  ModelPtr korzen_ = make_model("korzen"), booth_ = make_model("booth-cema");
};
}  // namespace

// The expensive model is not re-run; its coefficients come from the first cheap model in registry
// order that predicts each value: elasticities for forces and speeds, absolute for positions.
BOOST_AUTO_TEST_CASE(expensive_model_takes_cheap_coefficients) {
  const Expensive dem;
  const Station st = station();
  const auto u = typical();
  const std::vector<TrajectoryQuery> q = {{Boundary::lower, 0.3}};
  const auto p = dem.predict(st, {}, {q, false});
  dem.calls = 0;
  const auto r = input_uncertainty(dem, st, u, {}, q, p);
  BOOST_TEST(dem.calls == 0);
  const auto korzen = make_model("korzen"), booth = make_model("booth-cema");
  const auto pk = korzen->predict(st, {}, {q, false});
  const auto pb = booth->predict(st, {}, {q, false});
  const auto rk = input_uncertainty(*korzen, st, u, {}, q, pk);
  const auto rb = input_uncertainty(*booth, st, u, {}, q, pb);
  // R_n: Korzen's relative sensitivity times the expensive value (1.3x) = 1.3x Korzen's u_input.
  BOOST_TEST(*r.u[Quantity::normal_force] == 1.3 * *rk.u[Quantity::normal_force], tt::tolerance(1e-9));
  // V_p: Booth/CEMA predicts it first (registry order); scaled by dem / booth.
  const double vp_ratio = *p.values[Quantity::impact_velocity] / *pb.values[Quantity::impact_velocity];
  BOOST_TEST(*r.u[Quantity::impact_velocity] == vp_ratio * *rb.u[Quantity::impact_velocity], tt::tolerance(1e-9));
  // Positions: Booth/CEMA's absolute coefficients, whatever the expensive model's own level.
  BOOST_TEST(*r.u[Quantity::impact_point_y] == *rb.u[Quantity::impact_point_y], tt::tolerance(1e-12));
  BOOST_TEST(*r.trajectory[0] == *rb.trajectory[0], tt::tolerance(1e-12));
}

// ---- the dataset side ----

namespace {
fs::path dataset(const std::string& name, const std::string& setup_extra, const std::string& conditions) {
  const fs::path d = test::fresh_dir(name);
  for (const char* f : {"measurements.csv", "trajectory.csv"})
    fs::copy_file(fs::path(CHUTELAB_SOURCE_DIR) / "datasets/liggghts-rig" / f, d / f);
  std::ifstream in(fs::path(CHUTELAB_SOURCE_DIR) / "datasets/liggghts-rig/setup.toml");
  std::stringstream setup;
  setup << in.rdbuf();
  test::write_file(d / "setup.toml", setup.str() + "\n" + setup_extra);
  if (!conditions.empty()) test::write_file(d / "conditions.csv", conditions);
  else fs::copy_file(fs::path(CHUTELAB_SOURCE_DIR) / "datasets/liggghts-rig/conditions.csv", d / "conditions.csv");
  return d;
}

std::string conditions_with(const std::string& header_extra, const std::string& first_row_extra,
                            const std::string& other_rows_extra = "") {
  std::ifstream in(fs::path(CHUTELAB_SOURCE_DIR) / "datasets/liggghts-rig/conditions.csv");
  std::string out, l;
  for (int n = 1; std::getline(in, l); ++n)
    out += l + (n == 1 ? header_extra : n == 2 ? first_row_extra : other_rows_extra) + "\n";
  return out;
}

std::string error_of(const fs::path& d) {
  try {
    read_dataset(d);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}
}  // namespace

BOOST_AUTO_TEST_CASE(dataset_reads_columns_and_table_in_si) {
  const auto d = read_dataset(dataset(
      "unc-ok",
      "[uncertainty]\n\"material.friction_plate\" = 0.02\nmass_flow_tph = 0.4\n"
      "[uncertainty.plate]\nangle_deg = 0.5\n[uncertainty.material]\nbulk_density_kgm3 = 15.0\n",
      conditions_with(",belt_speed_uncertainty_mps,mass_flow_uncertainty_tph,plate_distance_uncertainty_mm,"
                      "plate_top_uncertainty_mm,stream_thickness_uncertainty_mm",
                      ",0.02,1.8,1.5,2.0,0.5", ",,,,,")));
  BOOST_REQUIRE_EQUAL(d.input_uncertainty.size(), d.stations.size());
  const auto& a = d.input_uncertainty[0];
  BOOST_TEST(*a.belt_speed == 0.02, tt::tolerance(1e-12));
  BOOST_TEST(*a.mass_flow == 1.8 / 3.6, tt::tolerance(1e-12));  // t/h -> kg/s
  BOOST_TEST(*a.plate_distance == 1.5e-3, tt::tolerance(1e-12));
  BOOST_TEST(*a.plate_top == 2e-3, tt::tolerance(1e-12));
  BOOST_TEST(*a.stream_thickness == 0.5e-3, tt::tolerance(1e-12));
  BOOST_REQUIRE_EQUAL(a.rig.size(), 3u);  // rig_fields() order: plate angle, bulk density, mu_pw
  BOOST_TEST(a.rig[0].first->key == "angle_deg");
  BOOST_TEST(a.rig[0].second == 0.5 * M_PI / 180.0, tt::tolerance(1e-12));
  BOOST_TEST(a.rig[1].second == 15.0);
  BOOST_TEST(a.rig[2].second == 0.02);
  // An empty cell takes the setup-wide default, or nothing.
  const auto& b = d.input_uncertainty[1];
  BOOST_TEST(!b.belt_speed);
  BOOST_TEST(*b.mass_flow == 0.4 / 3.6, tt::tolerance(1e-12));
  BOOST_TEST(b.rig.size() == 3u);
  // A dataset without any of it states nothing.
  const auto plain = read_dataset(CHUTELAB_SOURCE_DIR "/datasets/liggghts-rig");
  for (const auto& u : plain.input_uncertainty) BOOST_TEST(u.empty());
}

BOOST_AUTO_TEST_CASE(bad_uncertainties_name_file_line_field) {
  const std::string neg = error_of(dataset("unc-neg", "", conditions_with(",belt_speed_uncertainty_mps", ",-0.1", ",")));
  BOOST_TEST(neg.find("conditions.csv:2: belt_speed_uncertainty_mps") != std::string::npos, neg);
  BOOST_TEST(neg.find("negative") != std::string::npos, neg);
  const std::string inf = error_of(dataset("unc-inf", "", conditions_with(",mass_flow_uncertainty_tph", ",inf", ",")));
  BOOST_TEST(inf.find("conditions.csv:2: mass_flow_uncertainty_tph") != std::string::npos, inf);
  const std::string text = error_of(dataset("unc-text", "", conditions_with(",plate_top_uncertainty_mm", ",abc", ",")));
  BOOST_TEST(text.find("conditions.csv:2: plate_top_uncertainty_mm") != std::string::npos, text);
  const std::string unknown = error_of(dataset("unc-unknown", "[uncertainty]\n\"material.frictoin_plate\" = 0.02\n", ""));
  BOOST_TEST(unknown.find("setup.toml") != std::string::npos, unknown);
  BOOST_TEST(unknown.find("material.frictoin_plate") != std::string::npos, unknown);
  const std::string unknown_sub = error_of(dataset("unc-unknown-sub", "[uncertainty.belt]\nspeed = 0.1\n", ""));
  BOOST_TEST(unknown_sub.find("uncertainty.belt.speed") != std::string::npos, unknown_sub);
  const std::string negative = error_of(dataset("unc-neg-toml", "[uncertainty]\ngravity_mps2 = -0.1\n", ""));
  BOOST_TEST(negative.find("uncertainty.gravity_mps2") != std::string::npos, negative);
  const std::string twice = error_of(dataset(
      "unc-twice", "[uncertainty]\n\"material.friction_plate\" = 0.02\n[uncertainty.material]\nfriction_plate = 0.03\n", ""));
  BOOST_TEST(twice.find("given twice") != std::string::npos, twice);
  const std::string word = error_of(dataset("unc-word", "[uncertainty]\n\"material.friction_plate\" = \"0.02\"\n", ""));
  BOOST_TEST(word.find("must be a number") != std::string::npos, word);
  // The CLI: exit 2, one message, nothing written.
  const fs::path out = test::fresh_dir("unc-cli-out") / "out";
  const auto res = test::run_chutelab(fmt::format("validate --dataset {} --out {}",
                                                  dataset("unc-cli", "", conditions_with(",belt_speed_uncertainty_mps", ",-1", ",")).string(),
                                                  out.string()));
  BOOST_TEST(res.exit_code == 2);
  BOOST_TEST(!fs::exists(out));
}

// validate carries the parts into the comparison, u_val and the V&V 20 ratio, and errors.csv
// keeps its columns in order with the parts appended.
BOOST_AUTO_TEST_CASE(validate_carries_the_parts_into_u_val_and_errors_csv) {
  const auto d = read_dataset(dataset(
      "unc-validate", "[uncertainty]\n\"material.friction_plate\" = 0.02\n",
      conditions_with(",belt_speed_uncertainty_mps,mass_flow_uncertainty_tph", ",0.03,0.5", ",0.03,0.5")));
  const auto r = validate(d, make_models({"booth-cema", "korzen"}));
  int with_input = 0;
  for (const auto& c : r.comparisons) {
    if (!c.predicted) continue;
    BOOST_REQUIRE(c.u_input);
    ++with_input;
    BOOST_TEST(!c.u_num_disc);
    const double ud = c.uncertainty.value_or(0.0);
    BOOST_TEST(*c.validation_uncertainty() == std::hypot(ud, *c.u_input), tt::tolerance(1e-12));
    BOOST_TEST(*c.vv20_ratio() == std::abs(c.error()) / std::hypot(ud, *c.u_input), tt::tolerance(1e-12));
  }
  BOOST_TEST(with_input > 50);
  const std::string csv = errors_csv(r);
  const std::string header = csv.substr(0, csv.find('\n'));
  BOOST_TEST(header ==
             "condition,model,quantity,measured,uncertainty,predicted,error,relative_error,normalised_error,"
             "x_mm,validation_uncertainty,vv20_ratio,tolerance,u_num_stat,u_num_disc,u_input,y_mm,z_mm");
  // Each row has as many cells as the header.
  std::istringstream lines(csv);
  std::string line;
  while (std::getline(lines, line)) BOOST_TEST(std::count(line.begin(), line.end(), ',') == 17);
  // Discretisation and statistical parts of a model's prediction reach the comparison.
  struct WithNum final : public Model {
    std::string name() const override { return "num"; }
    std::string description() const override { return ""; }
    ModelPrediction predict(const Station& st, const analytical::EffectList& fx, const PredictRequest& req) const override {
      auto p = make_model("booth-cema")->predict(st, fx, req);
      p.uncertainty[Quantity::impact_point_y] = 1e-3;
      p.discretisation[Quantity::impact_point_y] = 2e-3;
      p.trajectory_uncertainty.assign(p.trajectory.size(), 3e-3);
      p.trajectory_discretisation.assign(p.trajectory.size(), 4e-3);
      return p;
    }
  };
  const auto r2 = validate(d, {std::make_shared<WithNum>()});
  int seen = 0;
  for (const auto& c : r2.comparisons) {
    if (!c.predicted) continue;
    const bool traj = c.boundary.has_value();
    if (!traj && c.q != Quantity::impact_point_y) continue;
    ++seen;
    const double stat = traj ? 3e-3 : 1e-3, disc = traj ? 4e-3 : 2e-3;
    BOOST_TEST(*c.u_num_stat() == stat);
    BOOST_TEST(*c.u_num_disc == disc);
    const double ud = c.uncertainty.value_or(0.0);
    BOOST_TEST(*c.validation_uncertainty() ==
                   std::sqrt(ud * ud + stat * stat + disc * disc + *c.u_input * *c.u_input),
               tt::tolerance(1e-12));
  }
  BOOST_TEST(seen > 20);
}

// The diagnosis weights each residual by u_val: u_D with the baseline's u_input (and u_num).
BOOST_AUTO_TEST_CASE(misfit_weights_are_u_val) {
  const auto d = read_dataset(dataset(
      "unc-misfit", "[uncertainty]\n\"material.friction_plate\" = 0.02\n",
      conditions_with(",belt_speed_uncertainty_mps", ",0.03", ",0.03")));
  const auto models = make_models({"booth-cema", "korzen"});
  const Misfit m(d, models);
  const auto r = validate(d, models);
  int n = 0;
  for (const auto& p : m.points()) {
    const std::string& cond = d.stations[p.condition].condition;
    // The comparison of the same value by the same model.
    const Comparison* c = nullptr;
    const double at_x = p.q ? 0.0 : trajectory_queries(d, cond).at(p.query).x;
    for (const auto& x : r.comparisons)
      if (x.condition == cond && x.model == models[p.model]->name() && x.quantity == p.quantity &&
          x.x == at_x) {
        c = &x;
        break;
      }
    BOOST_REQUIRE(c);
    BOOST_REQUIRE(c->u_input);
    BOOST_TEST(p.uncertainty == *c->validation_uncertainty(), tt::tolerance(1e-12));
    BOOST_TEST(p.uncertainty > *c->uncertainty);
    ++n;
  }
  BOOST_TEST(n > 50);
}

// A stream thickness uncertainty has nothing to act on where h_b comes from continuity.
BOOST_AUTO_TEST_CASE(stream_thickness_uncertainty_needs_a_stated_thickness) {
  const auto korzen = make_model("korzen");
  const Station st = make_station(grima(), "t", 3.0, 35.0 * units::tph, 0.45, 0.25, std::nullopt);
  InputUncertainties u;
  u.stream_thickness = 1e-3;
  const auto p = korzen->predict(st, {}, {});
  const auto r = input_uncertainty(*korzen, st, u, {}, {}, p);
  BOOST_TEST(*r.u[Quantity::normal_force] == 0.0);
  BOOST_REQUIRE_EQUAL(r.notes.size(), 1u);
  BOOST_TEST(r.notes[0].find("continuity") != std::string::npos);
}

BOOST_AUTO_TEST_SUITE_END()
