#include "validation/tolerances.h"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <toml++/toml.h>
#include <vector>

#include "core/input_error.h"
#include "core/toml_file.h"
#include "core/quantity.h"
#include "validation/model.h"

namespace chutelab::validation {
// A tolerance that matches no comparison is never checked, so a misspelt name would let acceptance
// pass without testing anything: every name must be one the harness compares under.
std::vector<std::string> tolerance_models() {
  auto m = model_names();
  m.emplace_back("*");
  return m;
}

std::vector<std::string> tolerance_quantities() {
  std::vector<std::string> q;
  for (Quantity k : kAllQuantities) q.emplace_back(name(k));
  for (Boundary b : kAllBoundaries) q.push_back(trajectory_quantity(b));
  return q;
}

const std::vector<ToleranceLimit>& tolerance_limits() {
  static const std::vector<ToleranceLimit> limits = {
      {"relative", "the largest |E| as a fraction of the measured value (0.05: 5 %)", &Tolerance::relative},
      {"normalised", "the largest |E|/u_val, in units of the validation uncertainty", &Tolerance::normalised},
      {"absolute", "the largest |E|, in the quantity's unit", &Tolerance::absolute},
  };
  return limits;
}

namespace {

bool contains(const std::vector<std::string>& v, std::string_view s) {
  return std::find(v.begin(), v.end(), s) != v.end();
}

// Keys carry their own position; a table's node may have none when toml++ made it implicitly
// (e.g. `[korzen.normal_force_N]` without `[korzen]`).
long line_of(const toml::key& k, const toml::node& n) {
  if (k.source().begin.line > 0) return static_cast<long>(k.source().begin.line);
  return static_cast<long>(n.source().begin.line);
}

}  // namespace

Tolerances Tolerances::read(const std::filesystem::path& path, const std::string* text) {
  Tolerances t;
  t.file_ = path.string();
  toml::table doc = text ? parse_toml_text(*text, t.file_) : read_toml_file(t.file_, "tolerances");
  const auto models = tolerance_models();
  const auto known_quantities = tolerance_quantities();
  for (const auto& [model, node] : doc) {
    const std::string mn(model.str());
    const long mline = line_of(model, node);
    if (!contains(models, mn))
      throw InputError(t.file_, mline, mn,
                       fmt::format("unknown model '{}' (known: {}; \"*\" for every model)", mn,
                                   fmt::join(model_names(), ", ")));
    const toml::table* quantities = node.as_table();
    if (!quantities)
      throw InputError(t.file_, mline, mn, "expected a table per model, e.g. [korzen]");
    for (const auto& [quantity, limits] : *quantities) {
      const std::string qn(quantity.str());
      const std::string field = fmt::format("{}.{}", mn, qn);
      const long line = line_of(quantity, limits);
      if (!contains(known_quantities, qn))
        throw InputError(t.file_, line, field,
                         fmt::format("unknown quantity '{}' (known: {})", qn, fmt::join(known_quantities, ", ")));
      const toml::table* lt = limits.as_table();
      if (!lt)
        throw InputError(t.file_, line, field, "expected an inline table, e.g. { relative = 0.15 }");
      Tolerance tol;
      for (const auto& [kind, value] : *lt) {
        const std::string kfield = fmt::format("{}.{}", field, kind.str());
        const long vline = line_of(kind, value);
        std::optional<double>* slot = nullptr;
        for (const auto& l : tolerance_limits())
          if (kind.str() == l.key) slot = &(tol.*l.slot);
        if (!slot)
          throw InputError(t.file_, vline, kfield,
                           fmt::format("unknown limit '{}' (use relative, normalised or absolute)", kind.str()));
        const auto v = value.value<double>();
        // Zero could only be met exactly, and inf checks nothing: neither is a limit.
        if (!value.is_number() || !v || !std::isfinite(*v) || !(*v > 0.0))
          throw InputError(t.file_, vline, kfield,
                           v ? fmt::format("must be a positive finite number, got {}", *v)
                             : std::string("must be a positive finite number"));
        *slot = v;
      }
      if (lt->empty())
        throw InputError(t.file_, line, field, "no limit given (use relative, normalised or absolute)");
      t.table_[{mn, qn}] = tol;
      t.lines_[{mn, qn}] = line;
    }
  }
  return t;
}

std::optional<Tolerances::Key> Tolerances::find_key(const std::string& model, const std::string& quantity) const {
  if (table_.count({model, quantity})) return Key{model, quantity};
  if (table_.count({"*", quantity})) return Key{"*", quantity};
  return std::nullopt;
}

std::vector<std::pair<Tolerances::Key, long>> Tolerances::entries() const {
  std::vector<std::pair<Key, long>> v;
  for (const auto& [k, tol] : table_) v.emplace_back(k, lines_.count(k) ? lines_.at(k) : 0L);
  return v;
}

const Tolerance* Tolerances::find(const std::string& model, const std::string& quantity) const {
  if (auto it = table_.find({model, quantity}); it != table_.end()) return &it->second;
  if (auto it = table_.find({"*", quantity}); it != table_.end()) return &it->second;
  return nullptr;
}

}  // namespace chutelab::validation
