#include "core/input_error.h"

#include "core/message.h"

#include <fmt/format.h>

#include <filesystem>
#include <fstream>

namespace chutelab {
namespace {
std::string compose(const std::string& file, long line, const std::string& field,
                    const std::string& problem) {
  // Every part may come from the user (a file name with a line end, a 10 MB cell in the problem):
  // the whole message goes through the one formatter (core/message.h).
  std::string where = file;
  if (line > 0) where += fmt::format(":{}", line);
  if (!field.empty()) where += where.empty() ? fmt::format("{}", field) : fmt::format(": {}", field);
  return one_line(where.empty() ? problem : where + ": " + problem);
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

void require_readable_file(const std::string& file, const std::string& field) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const auto st = fs::status(file, ec);
  if (ec == std::errc::no_such_file_or_directory || (!ec && !fs::exists(st)))
    throw InputError(file, 0, field, "file not found");
  if (ec) throw InputError(file, 0, field, fmt::format("cannot read: {}", ec.message()));
  if (fs::is_directory(st)) throw InputError(file, 0, field, "is a folder, not a file");
  if (!fs::is_regular_file(st) && !fs::is_character_file(st) && !fs::is_fifo(st))
    throw InputError(file, 0, field, "is not a regular file");
  std::ifstream f(file, std::ios::binary);
  if (!f) throw InputError(file, 0, field, "cannot be opened for reading (permissions?)");
}

}  // namespace chutelab
