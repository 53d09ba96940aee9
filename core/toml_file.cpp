#include "core/toml_file.h"

#include <fmt/format.h>

#include <fstream>
#include <utility>
#include <vector>

#include "core/input_error.h"
#include "core/message.h"
#include "core/text_file.h"

namespace chutelab {
namespace {

// Beyond this many nesting characters ('[', '{', '.') after a statement the scanner could not
// follow, toml++ is not given the text: it could nest that deep. Below it toml++'s own recursion is
// harmless (it overflowed at ~50 000 levels) and its syntax message is the better one.
constexpr std::size_t kCrudeNestingLimit = 1000;

// A single-pass scanner over TOML's statements that tracks only what nests and what hides
// characters (strings, comments). Recursion only for arrays and inline tables, and never deeper
// than kTomlMaxDepth: the depth is checked before each step down.
class Scanner {
 public:
  explicit Scanner(std::string_view s) : s_(s) {}

  std::optional<TomlBoundsProblem> run() {
    if (statements()) return std::nullopt;
    if (too_deep_) return TomlBoundsProblem{line_, *too_deep_};
    // Not followed: toml++ will refuse the text at or before this point, unless the scanner is
    // wrong; only a text that could still nest deeply is refused here.
    std::size_t nesting = 0;
    for (std::size_t k = statement_start_; k < s_.size(); ++k)
      if (s_[k] == '[' || s_[k] == '{' || s_[k] == '.') ++nesting;
    if (nesting <= kCrudeNestingLimit) return std::nullopt;
    return TomlBoundsProblem{line_, "malformed TOML: " + confused_};
  }

 private:
  char peek(std::size_t k = 0) const { return i_ + k < s_.size() ? s_[i_ + k] : '\0'; }
  bool at_end() const { return i_ >= s_.size(); }
  bool starts(std::string_view t) const { return s_.substr(i_, t.size()) == t; }

  bool fail(std::string what) {
    confused_ = std::move(what);
    return false;
  }
  bool deep(int depth) {
    too_deep_ = fmt::format(
        "nested {} levels deep; a value may be at most {} levels down (table header, dotted key, arrays "
        "and inline tables together)",
        depth, kTomlMaxDepth);
    return false;
  }

  void skip_ws() {
    while (peek() == ' ' || peek() == '\t') ++i_;
  }
  bool newline() {
    if (peek() == '\n') {
      ++i_;
    } else if (peek() == '\r' && peek(1) == '\n') {
      i_ += 2;
    } else {
      return false;
    }
    ++line_;
    return true;
  }
  void skip_comment() {
    if (peek() != '#') return;
    while (!at_end() && peek() != '\n') ++i_;
  }
  void skip_blank() {  // whitespace, line ends and comments
    for (;;) {
      skip_ws();
      skip_comment();
      if (!newline()) return;
    }
  }

  static bool bare(char c) {
    return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_' || c == '-';
  }

  bool basic_string() {  // "..." on one line
    ++i_;
    for (;;) {
      const char c = peek();
      if (at_end() || c == '\n') return fail("unterminated string");
      if (c == '\\') {
        if (i_ + 1 >= s_.size() || peek(1) == '\n') return fail("unterminated string");
        i_ += 2;
      } else {
        ++i_;
        if (c == '"') return true;
      }
    }
  }
  bool literal_string() {  // '...' on one line
    ++i_;
    for (;;) {
      const char c = peek();
      if (at_end() || c == '\n') return fail("unterminated string");
      ++i_;
      if (c == '\'') return true;
    }
  }
  bool multiline_string(char q, bool escapes) {  // """...""" or '''...'''
    i_ += 3;
    for (;;) {
      if (at_end()) return fail("unterminated multi-line string");
      const char c = peek();
      if (escapes && c == '\\') {
        ++i_;
        if (!newline() && !at_end()) ++i_;
        continue;
      }
      if (newline()) continue;
      if (c == q && peek(1) == q && peek(2) == q) {
        while (peek() == q) ++i_;  // up to two quotes of the content may precede the closing three
        return true;
      }
      ++i_;
    }
  }

  bool key(int& segments) {
    segments = 0;
    for (;;) {
      skip_ws();
      const char c = peek();
      if (c == '"') {
        if (!basic_string()) return false;
      } else if (c == '\'') {
        if (!literal_string()) return false;
      } else {
        const std::size_t start = i_;
        while (bare(peek())) ++i_;
        if (i_ == start) return fail("expected a key");
      }
      ++segments;
      skip_ws();
      if (peek() != '.') return true;
      ++i_;
    }
  }

  bool value(int depth) {
    const char c = peek();
    if (c == '"') return starts("\"\"\"") ? multiline_string('"', true) : basic_string();
    if (c == '\'') return starts("'''") ? multiline_string('\'', false) : literal_string();
    if (c == '[') {
      ++i_;
      for (;;) {
        skip_blank();
        if (peek() == ']') {
          ++i_;
          return true;
        }
        // An element one level down: checked before the step (an empty array has none).
        if (depth + 1 > kTomlMaxDepth) return deep(depth + 1);
        if (!value(depth + 1)) return false;
        skip_blank();
        if (peek() == ',') {
          ++i_;
          continue;
        }
        if (peek() == ']') {
          ++i_;
          return true;
        }
        return fail("expected ',' or ']' in an array");
      }
    }
    if (c == '{') {
      ++i_;
      skip_blank();
      if (peek() == '}') {
        ++i_;
        return true;
      }
      for (;;) {
        int segments = 0;
        if (!key(segments)) return false;
        if (depth + segments > kTomlMaxDepth) return deep(depth + segments);
        skip_ws();
        if (peek() != '=') return fail("expected '=' after a key");
        ++i_;
        skip_ws();
        if (!value(depth + segments)) return false;
        skip_blank();
        if (peek() == ',') {
          ++i_;
          skip_blank();
          continue;
        }
        if (peek() == '}') {
          ++i_;
          return true;
        }
        return fail("expected ',' or '}' in an inline table");
      }
    }
    // A number, boolean or date: up to what ends a value (a date may hold one space).
    const std::size_t start = i_;
    while (!at_end() && peek() != ',' && peek() != ']' && peek() != '}' && peek() != '\n' && peek() != '\r' &&
           peek() != '#')
      ++i_;
    if (i_ == start) return fail("expected a value");
    return true;
  }

  bool statements() {
    if (starts("\xEF\xBB\xBF")) i_ += 3;  // a UTF-8 byte-order mark, which toml++ skips too
    int base = 0;  // depth of the current [table]
    for (;;) {
      skip_blank();
      statement_start_ = i_;
      if (at_end()) return true;
      if (peek() == '[') {
        const bool array = peek(1) == '[';
        i_ += array ? 2 : 1;
        int segments = 0;
        if (!key(segments)) return false;
        const int depth = segments + (array ? 1 : 0);
        if (depth > kTomlMaxDepth) return deep(depth);
        skip_ws();
        if (!starts(array ? "]]" : "]")) return fail("expected ']' to close a table header");
        i_ += array ? 2 : 1;
        base = depth;
      } else {
        int segments = 0;
        if (!key(segments)) return false;
        if (base + segments > kTomlMaxDepth) return deep(base + segments);
        skip_ws();
        if (peek() != '=') return fail("expected '=' after a key");
        ++i_;
        skip_ws();
        if (!value(base + segments)) return false;
      }
      skip_ws();
      skip_comment();
      if (!at_end() && !newline()) return fail("expected the end of the line");
    }
  }

  std::string_view s_;
  std::size_t i_ = 0, statement_start_ = 0;
  long line_ = 1;
  std::string confused_;
  std::optional<std::string> too_deep_;
};

// The parsed tree, walked without recursion: the second line of defence (the scanner let a text
// through that toml++ read differently).
std::optional<TomlBoundsProblem> tree_too_deep(const toml::table& doc) {
  std::vector<std::pair<const toml::node*, int>> todo = {{&doc, 0}};
  while (!todo.empty()) {
    const auto [n, depth] = todo.back();
    todo.pop_back();
    if (depth > kTomlMaxDepth)
      return TomlBoundsProblem{static_cast<long>(n->source().begin.line),
                               fmt::format("nested more than {} levels deep", kTomlMaxDepth)};
    if (const auto* t = n->as_table())
      for (const auto& [k, v] : *t) todo.emplace_back(&v, depth + 1);
    else if (const auto* a = n->as_array())
      for (const auto& v : *a) todo.emplace_back(&v, depth + 1);
  }
  return std::nullopt;
}

}  // namespace

std::optional<TomlBoundsProblem> check_toml_bounds(std::string_view text) {
  if (text.size() > kTomlMaxBytes)
    return TomlBoundsProblem{0, fmt::format("is {}; a TOML file chutelab reads is at most {}",
                                            byte_size(text.size()), byte_size(kTomlMaxBytes))};
  if (auto p = text_encoding_problem(text)) return TomlBoundsProblem{p->line, p->problem};
  return Scanner(text).run();
}

toml::table parse_toml_text(std::string_view text, const std::string& file) {
  if (auto p = check_toml_bounds(text)) throw InputError(file, p->line, "", p->problem);
  toml::table doc;
  try {
    doc = toml::parse(text, file);
  } catch (const toml::parse_error& e) {
    throw InputError(file, static_cast<long>(e.source().begin.line), "",
                     fmt::format("malformed TOML: {}", e.description()));
  }
  if (auto p = tree_too_deep(doc)) throw InputError(file, p->line, "", p->problem);
  return doc;
}

toml::table read_toml_file(const std::string& file, std::string_view field) {
  return parse_toml_text(read_text_file(file, kTomlMaxBytes, field), file);
}

}  // namespace chutelab
