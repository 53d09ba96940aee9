#pragma once
// The registry of normal contact laws. A law is a spring and a damping part side by side
// (SpringAndDamping, dem/contact/spring_and_damping.h: hertz_mindlin.h is the model to follow) and
// declares, as LAMMPS' granular sub-models and Chrono DEM-Engine's force models do, everything the
// engine and the tools ask of it:
//   key, title          its name in configuration and on the command line, and in prose
//   liggghts            LIGGGHTS' pair model of the same law ("" if none: no LIGGGHTS deck)
//   hertz_elastic       its elastic force grows as delta^{3/2} (the sJKR belt adhesion assumes it)
//   parameters          the numbers it reads from Interaction::law (LawParameter): its spring's and
//                       its damping part's
//   Coeffs, mix         its coefficients per material pair and the mixing rule that derives them
//   check               what a pair's coefficients need to run ("" if they have it); the World
//                       names the law before it
//   normal              force, normal and tangential stiffness, tangential damping at an overlap
//   collision_time      a binary collision's duration (the default time step)
//   elastic_energy      the energy in the normal spring (World::energy)
//   matched_parameters  its parameters for a collision of given restitution and duration (the
//                       station gives every law the Hertz collision time)
//   liggghts_pair_properties  what LIGGGHTS' model reads per type pair beyond the moduli,
//                       restitution and friction every deck writes (property name -> value)
// NormalContactLaw below states this contract, so a law that misses a part does not compile.
// Registering it is its include and its place in NormalLaws below; a spring with a damping part
// other than its law's own is registered as Composed<Spring, Damping>, one line. From this list come
// the dispatch of the contact loop (dem/contact/contact_model.h), the names the station's
// configuration and the command line accept, the LIGGGHTS deck's model, the time step and the energy.
#include <algorithm>
#include <concepts>
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <variant>
#include <vector>

#include "dem/contact/damping_ratio.h"
#include "dem/contact/hertz_mindlin.h"
#include "dem/contact/hooke.h"
#include "dem/contact/linear_spring_dashpot.h"
#include "dem/contact/pair_coeffs.h"
#include "dem/contact/spring_and_damping.h"

namespace chutelab::dem {

// What the engine and the tools ask of a normal law (see above).
template <class L>
concept NormalContactLaw = requires(const typename L::Coeffs& c, const Material& m, const Interaction& in, double x) {
  { L::key } -> std::convertible_to<std::string_view>;
  { L::title } -> std::convertible_to<std::string_view>;
  { L::liggghts } -> std::convertible_to<std::string_view>;
  { L::hertz_elastic } -> std::convertible_to<bool>;
  requires std::same_as<typename decltype(L::parameters)::value_type, LawParameter>;
  { L::mix(m, m, in) } -> std::same_as<typename L::Coeffs>;
  { L::check(c) } -> std::same_as<std::string>;
  { L::normal(c, x, x, x, x) } -> std::same_as<NormalResult>;
  { L::collision_time(c, x, x, x) } -> std::same_as<double>;
  { L::elastic_energy(c, x, x) } -> std::same_as<double>;
  { L::matched_parameters(x, x, x) } -> std::same_as<LawParameters>;
  { L::liggghts_pair_properties(c) } -> std::same_as<LawParameters>;
};

// No two laws answer to one name, and no law declares a parameter twice.
template <class... Laws>
constexpr bool distinct_names() {
  const std::string_view keys[] = {Laws::key...};
  for (std::size_t i = 0; i < sizeof...(Laws); ++i)
    for (std::size_t j = 0; j < i; ++j)
      if (keys[i] == keys[j]) return false;
  auto own = []<class L>() {
    for (std::size_t i = 0; i < L::parameters.size(); ++i)
      for (std::size_t j = 0; j < i; ++j)
        if (L::parameters[i].key == L::parameters[j].key) return false;
    return true;
  };
  return (own.template operator()<Laws>() && ...);
}

template <class... Laws>
struct LawList {
  static_assert((NormalContactLaw<Laws> && ...), "a registered law misses a part (dem/contact/normal_laws.h)");
  static_assert(distinct_names<Laws...>(), "two laws share a key, or a law declares a parameter twice");
  static constexpr std::size_t size = sizeof...(Laws);
  // Every pair table one World may hold (one law's at a time).
  using PairTables = std::variant<std::vector<PairCoeffs<Laws>>...>;

  template <class Law>
  static constexpr int index_of() {
    int i = 0, found = -1;
    ((std::is_same_v<Law, Laws> ? (found = i, ++i) : ++i), ...);
    return found;
  }
  // f.template operator()<Law>() for the law at index i (0 <= i < size).
  template <class F>
  static decltype(auto) visit(int i, F&& f) {
    return visit_from<0, Laws...>(i, std::forward<F>(f));
  }

 private:
  template <int I, class L, class... Rest, class F>
  static decltype(auto) visit_from(int i, F&& f) {
    if constexpr (sizeof...(Rest) == 0) {
      return f.template operator()<L>();
    } else {
      if (i == I) return f.template operator()<L>();
      return visit_from<I + 1, Rest...>(i, std::forward<F>(f));
    }
  }
};

// The registry. Checkpoints store a law's place: append new laws at the end.
using NormalLaws = LawList<HertzMindlin, LinearSpringDashpot, Hooke,
                           Composed<HertzMindlinSpring, DampingRatio>>;

// Which registered law a scene runs.
class NormalLaw {
 public:
  constexpr NormalLaw() = default;  // the first registered: Hertz-Mindlin
  template <class Law>
  static constexpr NormalLaw of() {
    static_assert(NormalLaws::index_of<Law>() >= 0, "not a registered law (dem/contact/normal_laws.h)");
    return NormalLaw(NormalLaws::index_of<Law>());
  }
  static std::optional<NormalLaw> named(std::string_view key) {
    for (int i = 0; i < static_cast<int>(NormalLaws::size); ++i)
      if (NormalLaw(i).key() == key) return NormalLaw(i);
    return std::nullopt;
  }
  static std::optional<NormalLaw> at(int index) {
    if (index < 0 || index >= static_cast<int>(NormalLaws::size)) return std::nullopt;
    return NormalLaw(index);
  }
  // The registered keys for a message: "hertz-mindlin", "lsd", ...
  static std::string keys() {
    std::string s;
    for (int i = 0; i < static_cast<int>(NormalLaws::size); ++i)
      s += (i ? ", \"" : "\"") + std::string(NormalLaw(i).key()) + "\"";
    return s;
  }

  template <class F>
  decltype(auto) visit(F&& f) const {
    return NormalLaws::visit(index_, std::forward<F>(f));
  }
  int index() const { return index_; }
  std::string_view key() const { return visit([]<class L>() { return L::key; }); }
  std::string_view title() const { return visit([]<class L>() { return L::title; }); }
  std::string_view liggghts() const { return visit([]<class L>() { return L::liggghts; }); }
  bool hertz_elastic() const { return visit([]<class L>() { return L::hertz_elastic; }); }
  LawParameters matched_parameters(double restitution, double m_eff, double duration) const {
    return visit([&]<class L>() { return L::matched_parameters(restitution, m_eff, duration); });
  }
  // The law's LIGGGHTS properties for every pair of the table: name and row-major values (a pair the
  // law cannot run, such as two walls that never meet, gets 0).
  std::vector<std::pair<std::string, std::vector<double>>> liggghts_pair_properties(const MaterialTable& mt) const {
    return visit([&]<class L>() {
      std::vector<std::pair<std::string, std::vector<double>>> out;
      const auto n = static_cast<std::size_t>(mt.size());
      for (int a = 0; a < mt.size(); ++a)
        for (int b = 0; b < mt.size(); ++b) {
          const typename L::Coeffs c = L::mix(mt.material(a), mt.material(b), mt.interaction(a, b));
          const bool runs = L::check(c).empty();
          const LawParameters properties = L::liggghts_pair_properties(c);  // the loop reads into it
          for (const auto& property : properties.values()) {
            auto it = std::find_if(out.begin(), out.end(), [&](const auto& p) { return p.first == property.first; });
            if (it == out.end()) it = out.insert(out.end(), {property.first, std::vector<double>(n * n, 0.0)});
            it->second[static_cast<std::size_t>(a) * n + static_cast<std::size_t>(b)] = runs ? property.second : 0.0;
          }
        }
      return out;
    });
  }
  friend bool operator==(NormalLaw, NormalLaw) = default;

 private:
  constexpr explicit NormalLaw(int index) : index_(index) {}
  int index_ = 0;
};

}  // namespace chutelab::dem
