#pragma once
// A normal law as two parts side by side: a spring and a damping part.
//   spring   the elastic force and the stiffnesses at an overlap (normal, and the tangential spring's),
//            its parameters, mixing rule and check, the collision time and the elastic energy
//            (hertz_mindlin.h, linear_spring_dashpot.h, hooke.h);
//   damping  the dashpot's coefficients at an overlap (normal, and the tangential spring's), how they
//            are set (from the restitution, a damping ratio, a rate), its parameters and its check, the
//            damping ratio the collision time of a linear spring reads, and its parameters for a
//            collision of given damping ratio (damping_restitution.h, damping_mass_proportional.h,
//            damping_ratio.h).
// The normal force is F_n = F_spring(delta) + c_n d(delta)/dt. SpringAndDamping composes the two into
// what the registry asks of a normal law (normal_laws.h); Composed adds a name and the rest, so a
// damping part runs with a spring by one registration line: Composed<HertzMindlinSpring, DampingRatio>.
#include <array>
#include <cmath>
#include <concepts>
#include <cstddef>
#include <initializer_list>
#include <string>
#include <string_view>

#include "dem/contact/damping_restitution.h"
#include "dem/contact/kinematics.h"
#include "dem/contact/law_parameters.h"
#include "dem/material.h"

namespace chutelab::dem {

// What a spring part declares. Its messages (check) say what it needs, e.g. "needs normal_stiffness
// > 0 N/m"; the World names the law before them.
template <class S>
concept SpringPart = requires(const typename S::Coeffs& c, const Material& m, const Interaction& in, double x,
                              double& w0) {
  { S::key } -> std::convertible_to<std::string_view>;
  { S::title } -> std::convertible_to<std::string_view>;
  { S::hertz_elastic } -> std::convertible_to<bool>;          // F grows as delta^{3/2}
  { S::fixed_tangential_ratio } -> std::convertible_to<bool>;  // kt / kn is one number per pair
  requires std::same_as<typename decltype(S::parameters)::value_type, LawParameter>;
  { S::mix(m, m, in) } -> std::same_as<typename S::Coeffs>;
  { S::check(c) } -> std::same_as<std::string>;
  { S::spring(c, x, x) } -> std::same_as<SpringForce>;  // (delta, R*)
  // The damping ratio that rebounds with restitution e is restitution_scale() beta(e).
  { S::restitution_scale() } -> std::same_as<double>;
  // k_n when it does not depend on the overlap (NaN otherwise): a damping part's ratio reads it.
  { S::linear_stiffness(c) } -> std::same_as<double>;
  { S::collision_time(c, x, x, x, x) } -> std::same_as<double>;  // (m*, R*, v, damping ratio)
  { S::elastic_energy(c, x, x) } -> std::same_as<double>;       // (delta, R*)
  // Its parameters for a collision of duration t and damping ratio zeta at m*, and the undamped
  // angular frequency sqrt(k_n / m*) they give (NaN if the spring has none).
  { S::matched_stiffness(x, x, x, w0) } -> std::same_as<LawParameters>;  // (zeta, m*, t, w0)
};

// What a damping part declares (dashpot and set are templates over the spring part).
template <class D, class S>
concept DampingPartFor = requires(const typename D::Coeffs& c, const Interaction& in, const SpringForce& s, double x) {
  { D::key } -> std::convertible_to<std::string_view>;
  { D::title } -> std::convertible_to<std::string_view>;
  requires std::same_as<typename decltype(D::parameters)::value_type, LawParameter>;
  { D::template set<S>(in) } -> std::same_as<typename D::Coeffs>;
  { D::check(c) } -> std::same_as<std::string>;
  { D::template dashpot<S>(c, s, x) } -> std::same_as<Dashpot>;  // (m*)
  { D::ratio(c, x, x) } -> std::same_as<double>;                 // c_n / (2 sqrt(k m*)) at (k, m*)
  { D::matched_parameters(x, x, x) } -> std::same_as<LawParameters>;  // (zeta, m*, w0)
};

template <class T, std::size_t N, std::size_t M>
constexpr std::array<T, N + M> join_arrays(const std::array<T, N>& a, const std::array<T, M>& b) {
  std::array<T, N + M> out{};
  for (std::size_t i = 0; i < N; ++i) out[i] = a[i];
  for (std::size_t i = 0; i < M; ++i) out[N + i] = b[i];
  return out;
}

template <std::size_t N>
constexpr std::array<char, N> join_text(std::initializer_list<std::string_view> parts) {
  std::array<char, N> out{};
  std::size_t i = 0;
  for (std::string_view p : parts)
    for (char ch : p) out[i++] = ch;
  return out;
}

template <SpringPart Spring, class Damping>
  requires DampingPartFor<Damping, Spring>
struct SpringAndDamping {
  using spring_part = Spring;
  using damping_part = Damping;
  static constexpr bool hertz_elastic = Spring::hertz_elastic;
  static constexpr auto parameters = join_arrays(Spring::parameters, Damping::parameters);

  struct Coeffs {
    typename Spring::Coeffs spring;
    typename Damping::Coeffs damping;
  };
  static Coeffs mix(const Material& a, const Material& b, const Interaction& in) {
    return {Spring::mix(a, b, in), Damping::template set<Spring>(in)};
  }
  static std::string check(const Coeffs& c) {
    std::string why = Spring::check(c.spring);
    return why.empty() ? Damping::check(c.damping) : why;
  }

  CHUTELAB_INLINE static NormalResult normal(const Coeffs& c, double delta, double delta_dot, double r_eff,
                                             double m_eff) {
    const SpringForce s = Spring::spring(c.spring, delta, r_eff);
    const Dashpot d = Damping::template dashpot<Spring>(c.damping, s, m_eff);
    return {s.force + d.cn * delta_dot, s.kn, s.kt, d.ct};
  }
  static double collision_time(const Coeffs& c, double m_eff, double r_eff, double v) {
    const double zeta = Damping::ratio(c.damping, Spring::linear_stiffness(c.spring), m_eff);
    return Spring::collision_time(c.spring, m_eff, r_eff, v, zeta);
  }
  static double elastic_energy(const Coeffs& c, double delta, double r_eff) {
    return Spring::elastic_energy(c.spring, delta, r_eff);
  }
  // The spring's and the damping's parameters for a collision of restitution e and duration t at m*.
  static LawParameters matched_parameters(double restitution, double m_eff, double duration) {
    const double zeta = Spring::restitution_scale() * damping_ratio_from_restitution(restitution);
    double w0 = 0.0;
    LawParameters p = Spring::matched_stiffness(zeta, m_eff, duration, w0);
    const LawParameters damping = Damping::matched_parameters(zeta, m_eff, w0);  // the loop reads into it
    for (const auto& [key, value] : damping.values()) p.set(key, value);
    return p;
  }
};

// A spring with a damping part other than its law's own, named "<spring>+<damping>" (e.g.
// "hertz-mindlin+damping-ratio"); no LIGGGHTS counterpart is claimed for it.
template <class Spring, class Damping>
struct Composed : SpringAndDamping<Spring, Damping> {
 private:
  static constexpr std::size_t key_size = Spring::key.size() + 1 + Damping::key.size();
  static constexpr std::size_t title_size = Spring::title.size() + 6 + Damping::title.size();
  static constexpr std::array<char, key_size> key_chars = join_text<key_size>({Spring::key, "+", Damping::key});
  static constexpr std::array<char, title_size> title_chars =
      join_text<title_size>({Spring::title, " with ", Damping::title});

 public:
  static constexpr std::string_view key{key_chars.data(), key_size};
  static constexpr std::string_view title{title_chars.data(), title_size};
  static constexpr std::string_view liggghts = "";
  static LawParameters liggghts_pair_properties(const typename SpringAndDamping<Spring, Damping>::Coeffs&) {
    return {};
  }
};

}  // namespace chutelab::dem
