#pragma once
// Shared by the fuzz targets: each input goes to a private temporary folder as real files (the readers
// take paths, as the commands do), and the only acceptable failure is chutelab::InputError. Anything
// else escaping a reader is what `chutelab` would have aborted on, so it is turned into a crash that
// libFuzzer records.
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <algorithm>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>
#include <vector>

#include "core/input_error.h"
#include "core/toml_file.h"

namespace chutelab::fuzz {

inline const std::filesystem::path& scratch() {
  static const std::filesystem::path dir = [] {
    auto d = std::filesystem::temp_directory_path() / ("chutelab-fuzz-" + std::to_string(::getpid()));
    std::filesystem::create_directories(d);
    return d;
  }();
  return dir;
}

inline void write_file(const std::filesystem::path& p, std::string_view content) {
  std::ofstream f(p, std::ios::binary | std::ios::trunc);
  f.write(content.data(), static_cast<std::streamsize>(content.size()));
}

// Splits an input into at most `n` parts at lines that are exactly "%%" (so the seeds stay readable).
inline std::vector<std::string> split_parts(std::string_view s, std::size_t n) {
  std::vector<std::string> parts(1);
  std::size_t pos = 0;
  while (pos <= s.size()) {
    auto end = s.find('\n', pos);
    const std::string_view line = s.substr(pos, end == std::string_view::npos ? std::string_view::npos : end - pos);
    if (line == "%%" && parts.size() < n) parts.emplace_back();
    else {
      parts.back() += line;
      if (end != std::string_view::npos) parts.back() += '\n';
    }
    if (end == std::string_view::npos) break;
    pos = end + 1;
  }
  return parts;
}

// The TOML bound's own invariants (core/toml_file.h), checked on every input of a TOML target before
// the reader runs, against toml++ itself (safe here: inputs of at most 8 KB nest far less deeply
// than the ~50 000 levels at which toml++ overflows its stack):
// - whatever the scanner lets through, toml++ parses to a tree no deeper than the bound (else the
//   scanner missed a nesting, and only the check after parsing stood between toml++ and its stack);
// - what the scanner calls too deep, toml++ either refuses or parses to a tree that deep;
// - what the scanner calls malformed, toml++ refuses too (else valid TOML would be refused).
// The depth is measured here without recursion, independently of the library's walk.
inline void check_toml_scanner(std::string_view text) {
  if (text.size() > 8192) return;
  const auto verdict = check_toml_bounds(text);
  // Size and encoding (a NUL, UTF-16, a byte-order mark inside) are not the scanner's verdicts.
  if (verdict && verdict->problem.rfind("nested", 0) != 0 && verdict->problem.rfind("malformed TOML", 0) != 0) return;
  toml::table doc;
  try {
    doc = toml::parse(text);
  } catch (const toml::parse_error&) {
    return;  // toml++ refuses it as well: nothing parsed to compare
  }
  if (verdict && verdict->problem.rfind("malformed TOML", 0) == 0) {
    std::fprintf(stderr, "fuzz: the TOML scanner refused what toml++ reads: %s\n", verdict->problem.c_str());
    std::abort();
  }
  int deepest = 0;
  std::vector<std::pair<const toml::node*, int>> todo = {{&doc, 0}};
  while (!todo.empty()) {
    const auto [n, d] = todo.back();
    todo.pop_back();
    deepest = std::max(deepest, d);
    if (const auto* t = n->as_table())
      for (const auto& [k, v] : *t) todo.emplace_back(&v, d + 1);
    else if (const auto* a = n->as_array())
      for (const auto& v : *a) todo.emplace_back(&v, d + 1);
  }
  if (!verdict && deepest > kTomlMaxDepth) {
    std::fprintf(stderr, "fuzz: the TOML scanner let through a value %d levels deep\n", deepest);
    std::abort();
  }
  if (verdict && deepest <= kTomlMaxDepth) {
    std::fprintf(stderr, "fuzz: the TOML scanner called %d levels too deep: %s\n", deepest, verdict->problem.c_str());
    std::abort();
  }
}

template <class F>
int guarded(F&& f) {
  try {
    f();
  } catch (const InputError&) {
    // the one allowed outcome of bad input
  } catch (const std::exception& e) {
    std::fprintf(stderr, "fuzz: escaped exception (would abort chutelab): %s\n", e.what());
    std::abort();
  } catch (...) {
    std::fprintf(stderr, "fuzz: escaped non-standard exception\n");
    std::abort();
  }
  return 0;
}

}  // namespace chutelab::fuzz
