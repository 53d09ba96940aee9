#pragma once
// The one door through which a TOML file reaches toml++ (setup.toml, tolerances.toml, the
// import-digitised mapping, the [dem] table; the Python package reads through the same functions).
// toml++ parses nested keys, table headers, arrays and inline tables recursively: a key 50 000 levels
// deep overflows the stack inside it (a segfault no exception can catch). So the text is bounded
// before toml++ sees it: its size, NUL bytes and UTF-16, and the nesting depth of every value (table
// header segments + dotted key segments + arrays + inline tables), measured by a scanner of our own
// that follows TOML's strings and comments and never recurses. The parsed tree is checked again.
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

#include <toml++/toml.h>

namespace chutelab {

// A chutelab TOML file is a few kilobytes; the largest real ones (a [dem] table with an STL list,
// a mapping of a hundred curves) stay far below these.
inline constexpr std::size_t kTomlMaxBytes = std::size_t{1} << 20;
// The deepest value chutelab reads is 3 levels down ([dem.feeder] key = { ... }).
inline constexpr int kTomlMaxDepth = 32;

struct TomlBoundsProblem {
  long line = 0;  // 1-based; 0 = the whole file
  std::string problem;
};

// Checks `text` against the bounds above without parsing it; nullopt when toml++ may be given it.
// A syntax error the scanner meets is reported only when the rest of the text could still nest
// deeply (otherwise toml++ is left to report it, in its own words).
std::optional<TomlBoundsProblem> check_toml_bounds(std::string_view text);

// Reads `file` (at most kTomlMaxBytes + 1 bytes, so a FIFO or /dev/zero ends too), checks its
// bounds and parses it. Every failure is an InputError naming the file (and line): missing,
// unreadable, too big, not UTF-8 text, too deep, malformed.
toml::table read_toml_file(const std::string& file, std::string_view field = "");

// The same for text already in memory (`file` names it in messages).
toml::table parse_toml_text(std::string_view text, const std::string& file);

}  // namespace chutelab
