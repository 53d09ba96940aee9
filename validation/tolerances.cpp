#include "validation/tolerances.h"

#include <fmt/format.h>
#include <toml++/toml.h>

#include "core/input_error.h"
#include "core/quantity.h"

namespace chutelab::validation {

Tolerances Tolerances::read(const std::filesystem::path& path) {
  Tolerances t;
  t.file_ = path.string();
  if (!std::filesystem::exists(path)) throw InputError(t.file_, 0, "", "file not found");
  toml::table doc;
  try {
    doc = toml::parse_file(t.file_);
  } catch (const toml::parse_error& e) {
    throw InputError(t.file_, static_cast<long>(e.source().begin.line), "",
                     fmt::format("malformed TOML: {}", e.description()));
  }
  for (const auto& [model, node] : doc) {
    const toml::table* quantities = node.as_table();
    const long mline = static_cast<long>(node.source().begin.line);
    if (!quantities)
      throw InputError(t.file_, mline, std::string(model.str()),
                       "expected a table per model, e.g. [korzen]");
    for (const auto& [quantity, limits] : *quantities) {
      const std::string field = fmt::format("{}.{}", model.str(), quantity.str());
      const long line = static_cast<long>(limits.source().begin.line);
      const std::string qn(quantity.str());
      const bool trajectory = qn.rfind("trajectory_", 0) == 0;
      if (!parse_quantity(qn) && !trajectory)
        throw InputError(t.file_, line, field, fmt::format("unknown quantity '{}'", qn));
      const toml::table* lt = limits.as_table();
      if (!lt)
        throw InputError(t.file_, line, field,
                         "expected an inline table, e.g. { relative = 0.15 }");
      Tolerance tol;
      for (const auto& [kind, value] : *lt) {
        const auto v = value.value<double>();
        const long vline = static_cast<long>(value.source().begin.line);
        if (!v || !value.is_number() || !(*v > 0.0))
          throw InputError(t.file_, vline, fmt::format("{}.{}", field, kind.str()),
                           "must be a positive number");
        if (kind == "relative") tol.relative = v;
        else if (kind == "normalised") tol.normalised = v;
        else if (kind == "absolute") tol.absolute = v;
        else
          throw InputError(t.file_, vline, fmt::format("{}.{}", field, kind.str()),
                           "unknown limit (use relative, normalised or absolute)");
      }
      t.table_[{std::string(model.str()), qn}] = tol;
    }
  }
  return t;
}

const Tolerance* Tolerances::find(const std::string& model, const std::string& quantity) const {
  if (auto it = table_.find({model, quantity}); it != table_.end()) return &it->second;
  if (auto it = table_.find({"*", quantity}); it != table_.end()) return &it->second;
  return nullptr;
}

}  // namespace chutelab::validation
