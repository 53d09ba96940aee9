#pragma once
// Bad input is reported once, naming where it came from, and ends the run with exit code 2.
#include <stdexcept>
#include <string>

namespace chutelab {

class InputError : public std::runtime_error {
 public:
  // file may be empty for command-line input; line 0 means "no line" (e.g. a TOML key or a flag).
  InputError(std::string file, long line, std::string field, const std::string& problem);
  const std::string& file() const { return file_; }
  long line() const { return line_; }
  const std::string& field() const { return field_; }
  const std::string& problem() const { return problem_; }
  // The same problem placed in a file and line (for errors found after parsing, e.g. a condition
  // whose stream misses the plate); keeps a location that is already set.
  InputError located(const std::string& file, long line) const;

 private:
  std::string file_;
  long line_;
  std::string field_;
  std::string problem_;
};

// A path the user gave as a file must be one: throws InputError (file, field) for a missing path, a
// folder, a symlink loop or a file that cannot be opened, so that no reader meets them later.
void require_readable_file(const std::string& file, const std::string& field = "");

inline constexpr int kExitOk = 0;
inline constexpr int kExitAcceptanceFailed = 1;
inline constexpr int kExitBadInput = 2;
// Not the user's fault: a bug or the machine (out of memory). One line on stderr, never an abort.
inline constexpr int kExitInternalError = 3;

}  // namespace chutelab
