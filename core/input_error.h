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

inline constexpr int kExitOk = 0;
inline constexpr int kExitAcceptanceFailed = 1;
inline constexpr int kExitBadInput = 2;

}  // namespace chutelab
