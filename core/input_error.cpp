#include "core/input_error.h"

#include "core/message.h"

#include <fmt/format.h>

#include <filesystem>
#include <fstream>

namespace chutelab {
namespace {
// A mention travels inside the problem text between two control characters, which no value shown
// in a message can hold (core/message.h escapes them), so a file's text never reads as one.
constexpr char kMentionOpen = '\x01', kMentionClose = '\x02';

std::string render(const std::string& problem, const FieldNames& names) {
  std::string out;
  for (std::size_t at = 0;;) {
    const std::size_t open = problem.find(kMentionOpen, at);
    const std::size_t close = open == std::string::npos ? open : problem.find(kMentionClose, open);
    if (close == std::string::npos) return out + problem.substr(at);
    out += problem.substr(at, open - at);
    const std::string key = problem.substr(open + 1, close - open - 1);
    out += names ? names(key) : key;
    at = close + 1;
  }
}

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

std::string mention(std::string_view key) {
  return std::string(1, kMentionOpen) + std::string(key) + kMentionClose;
}

std::string said_text(const std::string& text, const FieldNames& names) { return render(text, names); }

InputError::InputError(std::string file, long line, std::string field, const std::string& problem)
    : std::runtime_error(compose(file, line, field, render(problem, {}))),
      file_(std::move(file)),
      line_(line),
      field_(std::move(field)),
      problem_(problem) {}

std::string InputError::problem_said(const FieldNames& names) const { return render(problem_, names); }

std::string InputError::said(const FieldNames& field_names, const FieldNames& mention_names) const {
  return compose(file_, line_, field_.empty() || !field_names ? field_ : field_names(field_),
                 render(problem_, mention_names));
}

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
