#include "validation/input_uncertainty.h"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <functional>
#include <limits>

namespace chutelab::validation {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

struct Perturbation {
  std::string name;
  double u = 0.0;
  double lo = -kInf, hi = kInf;  // SI bounds of the value
  bool open_lower = false;       // must stay > lo (a positive operating input)
  std::function<double(const Station&)> get;
  std::function<void(Station&, double)> set;
};

Setup as_setup(const Station& st) {
  Setup s;
  s.belt = st.belt;
  s.plate = st.plate;
  s.material = st.material;
  s.gravity = st.gravity;
  return s;
}

std::vector<Perturbation> perturbations(const Station& st, const InputUncertainties& u) {
  std::vector<Perturbation> out;
  auto operating = [&](const char* name, const std::optional<double>& v, double Station::*m, bool positive) {
    if (!v || *v <= 0.0) return;
    out.push_back({name, *v, positive ? 0.0 : -kInf, kInf, positive,
                   [m](const Station& s) { return s.*m; }, [m](Station& s, double x) { s.*m = x; }});
  };
  operating("belt_speed_mps", u.belt_speed, &Station::belt_speed, true);
  operating("mass_flow_tph", u.mass_flow, &Station::mass_flow, true);
  operating("plate_distance_mm", u.plate_distance, &Station::plate_distance, true);
  operating("plate_top_mm", u.plate_top, &Station::plate_top, false);
  if (u.stream_thickness && *u.stream_thickness > 0.0 && st.stream_thickness)
    out.push_back({"stream_thickness_mm", *u.stream_thickness, 0.0, kInf, true,
                   [](const Station& s) { return *s.stream_thickness; },
                   [](Station& s, double x) { s.stream_thickness = x; }});
  for (const auto& entry : u.rig) {
    const auto f = entry.first;  // a copy: clang 14 cannot capture a structured binding
    const double v = entry.second;
    if (v <= 0.0) continue;
    const std::string dotted = f->section.empty() ? std::string(f->key) : fmt::format("{}.{}", f->section, f->key);
    out.push_back({dotted, v, f->min * f->to_si, f->max * f->to_si, false,
                   [f](const Station& s) {
                     Setup x = as_setup(s);
                     return f->ref(x);
                   },
                   [f](Station& s, double value) {
                     Setup x = as_setup(s);
                     f->ref(x) = value;
                     s.belt = x.belt;
                     s.plate = x.plate;
                     s.material = x.material;
                     s.gravity = x.gravity;
                   }});
  }
  return out;
}

// A model that cannot handle a perturbed condition gives no value there, not an error: the
// perturbation is ours, not the user's.
std::optional<ModelPrediction> run(const Model& m, const Station& st, const analytical::EffectList& fx,
                                   std::span<const TrajectoryQuery> queries) {
  try {
    return m.predict(st, fx, {queries, false});
  } catch (const std::exception&) {
    return std::nullopt;
  }
}

std::optional<double> difference(std::optional<double> fp, std::optional<double> fm, std::optional<double> f0,
                                 double hp, double hm) {
  if (fp && fm) return (*fp - *fm) / (hp + hm);
  if (fp && f0 && hp > 0.0) return (*fp - *f0) / hp;
  if (fm && f0 && hm > 0.0) return (*f0 - *fm) / hm;
  return std::nullopt;
}

std::optional<double> at(const std::optional<ModelPrediction>& p, Quantity q) {
  return p ? p->values[q] : std::nullopt;
}
std::optional<double> at(const std::optional<ModelPrediction>& p, std::size_t t) {
  return p && t < p->trajectory.size() ? p->trajectory[t] : std::nullopt;
}

const std::vector<ModelPtr>& cheap_models() {
  static const std::vector<ModelPtr> models = [] {
    std::vector<ModelPtr> out;
    for (const auto& n : model_names())
      if (auto m = make_model(n); !m->expensive()) out.push_back(m);
    return out;
  }();
  return models;
}

}  // namespace

std::vector<InputSensitivity> sensitivities(const Model& model, const Station& station,
                                            const InputUncertainties& u,
                                            const analytical::EffectList& effects,
                                            std::span<const TrajectoryQuery> queries) {
  std::vector<InputSensitivity> out;
  const auto inputs = perturbations(station, u);
  if (inputs.empty()) return out;
  const auto base = run(model, station, effects, queries);
  for (const auto& p : inputs) {
    const double x = p.get(station);
    const double hp = std::min(p.u, p.hi - x);
    const double hm = p.open_lower ? std::min(p.u, 0.5 * (x - p.lo)) : std::min(p.u, x - p.lo);
    std::optional<ModelPrediction> plus, minus;
    if (hp > 0.0) {
      Station s = station;
      p.set(s, x + hp);
      plus = run(model, s, effects, queries);
    }
    if (hm > 0.0) {
      Station s = station;
      p.set(s, x - hm);
      minus = run(model, s, effects, queries);
    }
    InputSensitivity is;
    is.input = p.name;
    is.u = p.u;
    for (Quantity q : kAllQuantities)
      is.coefficient[q] = difference(at(plus, q), at(minus, q), at(base, q), std::max(hp, 0.0), std::max(hm, 0.0));
    is.trajectory.resize(queries.size());
    for (std::size_t t = 0; t < queries.size(); ++t)
      is.trajectory[t] = difference(at(plus, t), at(minus, t), at(base, t), std::max(hp, 0.0), std::max(hm, 0.0));
    out.push_back(std::move(is));
  }
  return out;
}

InputUncertaintyResult input_uncertainty(const Model& model, const Station& station,
                                         const InputUncertainties& u,
                                         const analytical::EffectList& effects,
                                         std::span<const TrajectoryQuery> queries,
                                         const ModelPrediction& own) {
  InputUncertaintyResult r;
  r.trajectory.resize(queries.size());
  if (u.empty()) return r;
  if (u.stream_thickness && *u.stream_thickness > 0.0 && !station.stream_thickness)
    r.notes.push_back("stream thickness uncertainty not used: h_b from continuity");

  // Sources of coefficients: the model itself, or for an expensive one the cheap models in
  // registry order; `scale` turns a cheap coefficient into the expensive model's (1 = absolute).
  struct Source {
    std::optional<ModelPrediction> base;
    std::vector<InputSensitivity> s;
  };
  std::vector<Source> sources;
  if (!model.expensive()) {
    sources.push_back({own, sensitivities(model, station, u, effects, queries)});
  } else {
    for (const auto& m : cheap_models())
      sources.push_back({run(*m, station, effects, queries), sensitivities(*m, station, u, effects, queries)});
  }

  auto combine = [&](const std::string& what, bool position, std::optional<double> value,
                     const std::function<std::optional<double>(const std::optional<ModelPrediction>&)>& base_of,
                     const std::function<std::optional<double>(const InputSensitivity&)>& coef_of)
      -> std::optional<double> {
    if (!value) return std::nullopt;
    for (const auto& src : sources) {
      const auto b = base_of(src.base);
      if (!b) continue;
      const double scale = !model.expensive() || position || !(*b > 0.0 && *value > 0.0) ? 1.0 : *value / *b;
      // An elasticity carried across a factor of more than 2 rests on a cheap model far from this
      // prediction (e.g. Korzen's V_a near the root of Eq 4): say so beside the number.
      if (scale > 2.0 || scale < 0.5)
        r.notes.push_back(fmt::format("u_input of {} from the relative coefficients of a cheap model whose value is {:.2g} times this one", what,
                                      1.0 / scale));
      double sum = 0.0;
      for (const auto& is : src.s) {
        const auto c = coef_of(is);
        if (!c) {
          r.notes.push_back(fmt::format("u_input of {} not estimated: no prediction at {} ± its uncertainty",
                                        what, is.input));
          return std::nullopt;
        }
        sum += std::pow(*c * scale * is.u, 2);
      }
      return std::sqrt(sum);
    }
    r.notes.push_back(fmt::format("u_input of {} not estimated: no cheap model predicts it", what));
    return std::nullopt;
  };

  for (Quantity q : kAllQuantities)
    r.u[q] = combine(std::string(info(q).symbol), q == Quantity::impact_point_y, own.values[q],
                     [q](const std::optional<ModelPrediction>& p) { return at(p, q); },
                     [q](const InputSensitivity& is) { return is.coefficient[q]; });
  for (std::size_t t = 0; t < queries.size(); ++t) {
    std::optional<double> v;
    if (t < own.trajectory.size()) v = own.trajectory[t];
    r.trajectory[t] = combine(fmt::format("the {} stream limit at x = {:.0f} mm", name(queries[t].boundary),
                                          queries[t].x * 1e3),
                              true, v, [t](const std::optional<ModelPrediction>& p) { return at(p, t); },
                              [t](const InputSensitivity& is) {
                                return t < is.trajectory.size() ? is.trajectory[t] : std::nullopt;
                              });
  }
  return r;
}

}  // namespace chutelab::validation
