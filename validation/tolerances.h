#pragma once
// Acceptance tolerances (tolerances.toml): per model and quantity, the largest allowed |relative|,
// |normalised| and/or |absolute| error of any single comparison. A "*" table applies to every model
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

struct Tolerance {
  std::optional<double> relative;
  std::optional<double> normalised;
  std::optional<double> absolute;  // boundary unit of the quantity
};

struct ToleranceVerdict {
  bool checked = false;
  bool passed = true;
  std::string limit;  // which limit failed, for the report, e.g. "|rel| 0.21 > 0.15"
};

class Tolerances {
 public:
  static Tolerances read(const std::filesystem::path& file);
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
