#pragma once
// Bad input is reported once, naming where it came from, and ends the run with exit code 2.
//
// The library names an input by a neutral key ("models", "effect", "dem.threads"), never by the
// way one front end spells it: the command line shows the key as its flag (--models), the Python
// package as its keyword (models=). A problem text that points at another input says so with
// mention("key"), which each front end renders the same way (InputError::said).
#include <functional>
#include <stdexcept>
#include <string>
#include <string_view>

namespace chutelab {

// How a front end spells an input's key "dem.threads": the command line's flag, Python's keyword dem_threads.
using FieldNames = std::function<std::string(std::string_view key)>;

// Another input named inside a problem text ("contradicts " + mention("dem.no_cache")); shown by
// what() as the key itself and by said() in the front end's words.
std::string mention(std::string_view key);

// Any text that holds mentions (a progress line, a note) with each shown by `names` (the key itself
// when no names are given).
std::string said_text(const std::string& text, const FieldNames& names = {});

class InputError : public std::runtime_error {
 public:
  // file may be empty for an option; line 0 means "no line" (e.g. a TOML key or an option). field is
  // a neutral key (a column, a TOML key, an option's key): never a front end's spelling of it.
  InputError(std::string file, long line, std::string field, const std::string& problem);
  const std::string& file() const { return file_; }
  long line() const { return line_; }
  const std::string& field() const { return field_; }
  // As given, mentions of other inputs kept as such (an InputError made again from these parts, e.g.
  // after a campaign job's exchange or to place it in a file, says the same).
  const std::string& problem() const { return problem_; }
  // The problem with each mention shown by `names` (the key itself when no names are given).
  std::string problem_said(const FieldNames& names = {}) const;
  // The whole one-line message in a front end's words: the field shown by `field_names`, mentions by
  // `mention_names` (what() is this with every key as it is).
  std::string said(const FieldNames& field_names, const FieldNames& mention_names) const;
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
