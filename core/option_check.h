#pragma once
// One validator for every option and argument, whichever door it comes in by: the command line
// (app/option_checks.h attaches these rules to CLI11 options, and a finite / whole / non-empty check
// to every option that has no rule of its own) and the Python package (python/chutelab_module.cpp
// calls the same rules with the keyword's value). Every check happens before any work, and a
// failure is an InputError naming the option by its neutral key (the command line shows it as its flag, the Python package as its keyword).
#include <cstdint>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

namespace chutelab::options {

// A number an option takes: finite, within [lo, hi] (an open end excludes the bound itself), whole
// when `whole` (1.5 is not a thread count; 2.0 is 2).
struct NumberRule {
  constexpr NumberRule() = default;
  constexpr NumberRule(std::string_view f, double l, double h, bool lo_o, bool hi_o, bool w, std::string_view u = {},
                       std::string_view h_text = {})
      : key(f), lo(l), hi(h), lo_open(lo_o), hi_open(hi_o), whole(w), unit(u), hi_text(h_text) {}
  std::string_view key;  // the option's neutral key (core/input_error.h)
  double lo = -std::numeric_limits<double>::max();
  double hi = std::numeric_limits<double>::max();
  bool lo_open = false, hi_open = false;
  bool whole = false;
  std::string_view unit;
  std::string_view hi_text;  // the upper bound as people write it ("2^64"), when its digits would not help
  // Returns v, or throws InputError(key) saying what the value must be.
  double check(double v) const;
  // The same for a value as typed ("nan", "1e400", "0x10", "5mm"): shown as typed when refused.
  double check(std::string_view typed) const;
  std::string describe() const;  // "a whole number in [1, 256]"
};

// Throws InputError(key) for an empty text value (an empty --only on the command line).
void non_empty(std::string_view key, std::string_view value);

// A comma list: every item non-empty ("a,,b" and a trailing comma are mistakes, not gaps to skip)
// and given once; an empty list is refused too.
std::vector<std::string> list(std::string_view key, std::string_view text);
// A comma list of numbers, each checked by `rule` (whose key names them), none given twice.
std::vector<double> number_list(const NumberRule& rule, std::string_view text);
// Refuses a list longer than `max` items, saying what each item costs (a DEM run, a slump test).
void at_most(std::string_view key, std::size_t n, std::size_t max, std::string_view each);

// Rules shared by the command line and the Python package.
namespace rules {
// Any 64-bit seed: [0, 2^64), exactly as a double sees it.
inline constexpr NumberRule seed{"seed", 0.0, 18446744073709551616.0, false, true, true, "", "2^64"};
inline constexpr NumberRule noise_scale{"noise_scale", 0.0, 100.0, false, false, false, ""};
inline constexpr NumberRule alpha{"alpha", 1e-6, 0.5, false, false, false, ""};
// OpenMP threads of a DEM run: 0 is one per idle core.
inline constexpr NumberRule dem_threads{"dem.threads", 0.0, 256.0, false, false, true, ""};
inline constexpr NumberRule threads{"threads", 0.0, 256.0, false, false, true, ""};
inline constexpr NumberRule jobs{"jobs", 1.0, 256.0, false, false, true, ""};
// synthesize: the real scatter in stated uncertainties, and gross reading errors.
inline constexpr NumberRule noise_factor{"noise_factor", 0.0, 100.0, false, false, false, ""};
inline constexpr NumberRule outliers{"outliers", 0.0, 100000.0, false, false, true, ""};
// diagnose: replicas of the dataset's design (each about as long as the diagnosis itself).
inline constexpr NumberRule self_check{"self_check", 0.0, 100000.0, false, false, true, ""};
}  // namespace rules

}  // namespace chutelab::options
