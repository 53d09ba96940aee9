#pragma once
// Acceptance tolerances (tolerances.toml): per model and quantity, the largest allowed |relative|,
// |normalised| and/or |absolute| error of any single comparison. "normalised" is |E| / u_val, the
// ratio of ASME V&V 20 (validation/harness.h), so a model with a large numerical uncertainty is
// not failed for a difference its own uncertainty covers. A "*" table applies to every model
// that has no table of its own for that quantity.
//
//   [korzen]
//   normal_force_N = { relative = 0.15 }
//   impact_point_y_mm = { absolute = 10.0, normalised = 3.0 }   # absolute in the quantity's unit
//
// A limit that matches no comparison would let acceptance pass unchecked, so read() throws
// InputError (file, line, field) for a model that is neither registered nor "*", a quantity outside
// the vocabulary (DESIGN.md §2 and trajectory_<upper|lower|centre>_y_mm), an unknown limit key, an
// empty limit table, or a limit that is not a positive finite number.
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace chutelab::validation {

struct Tolerance;
// The names a tolerances.toml may hold: the models' tables (and "*"), the quantities, the limits.
std::vector<std::string> tolerance_models();
std::vector<std::string> tolerance_quantities();
struct ToleranceLimit {
  const char* key;
  const char* meaning;
  std::optional<double> Tolerance::*slot;
};
const std::vector<ToleranceLimit>& tolerance_limits();

struct Tolerance {
  std::optional<double> relative;
  std::optional<double> normalised;
  std::optional<double> absolute;  // boundary unit of the quantity
};

struct ToleranceVerdict {
  bool checked = false;
  bool passed = true;
  // The first limit that failed, in words with the quantity's unit, e.g. "relative error 21.0 % >
  // 15 %", "error 12.3 mm > 10 mm", "|E|/u_val 3.19 > 2".
  std::string limit;
  std::string kind;           // "relative", "absolute" or "normalised" (empty while passed)
  double actual = 0.0;        // |relative error| (fraction), |E| (boundary unit) or |E|/u_val
  double allowed = 0.0;       // the limit in the same unit
};

class Tolerances {
 public:
  // With `text`, the file as already read (a dataset's own, Dataset::sources).
  static Tolerances read(const std::filesystem::path& file, const std::string* text = nullptr);
  using Key = std::pair<std::string, std::string>;  // model (or "*"), quantity
  const Tolerance* find(const std::string& model, const std::string& quantity) const;
  // The entry find() would use, so that the harness can tell which limits checked something.
  std::optional<Key> find_key(const std::string& model, const std::string& quantity) const;
  bool empty() const { return table_.empty(); }
  std::string file() const { return file_; }
  // Every limit with the line it is on, in file order of keys (map order).
  std::vector<std::pair<Key, long>> entries() const;

 private:
  std::string file_;
  std::map<Key, Tolerance> table_;
  std::map<Key, long> lines_;
};

}  // namespace chutelab::validation
