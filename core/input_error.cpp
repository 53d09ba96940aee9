#include "core/input_error.h"

#include <fmt/format.h>

namespace chutelab {
namespace {
std::string compose(const std::string& file, long line, const std::string& field,
                    const std::string& problem) {
  std::string where = file;
  if (line > 0) where += fmt::format(":{}", line);
  if (!field.empty()) where += where.empty() ? fmt::format("{}", field) : fmt::format(": {}", field);
  return where.empty() ? problem : where + ": " + problem;
}
}  // namespace

InputError::InputError(std::string file, long line, std::string field, const std::string& problem)
    : std::runtime_error(compose(file, line, field, problem)),
      file_(std::move(file)),
      line_(line),
      field_(std::move(field)),
      problem_(problem) {}

InputError InputError::located(const std::string& file, long line) const {
  if (!file_.empty()) return *this;
  return InputError(file, line, field_, problem_);
}

}  // namespace chutelab
