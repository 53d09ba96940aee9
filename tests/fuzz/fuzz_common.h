#pragma once
// Shared by the fuzz targets: each input goes to a private temporary folder as real files (the readers
// take paths, as the commands do), and the only acceptable failure is chutelab::InputError. Anything
// else escaping a reader is what `chutelab` would have aborted on, so it is turned into a crash that
// libFuzzer records.
#include <unistd.h>

#include <cstdint>
#include <cstdio>
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

// The TOML bound's own invariant (core/toml_file.h), checked on every input of a TOML target before
// the reader runs: whatever the scanner lets through, toml++ parses to a tree no deeper than the bound
// (else the scanner missed a nesting, and only the check after parsing stood between toml++ and
// its stack). The depth is measured here without recursion, independently of the library's walk.
inline void check_toml_scanner(std::string_view text) {
  if (check_toml_bounds(text)) return;  // refused before toml++: nothing to compare
  toml::table doc;
  try {
    doc = toml::parse(text);
  } catch (const toml::parse_error&) {
    return;  // a syntax error toml++ reports itself
  }
  std::vector<std::pair<const toml::node*, int>> todo = {{&doc, 0}};
  while (!todo.empty()) {
    const auto [n, d] = todo.back();
    todo.pop_back();
    if (d > kTomlMaxDepth) {
      std::fprintf(stderr, "fuzz: the TOML scanner let through a value %d levels deep\n", d);
      std::abort();
    }
    if (const auto* t = n->as_table())
      for (const auto& [k, v] : *t) todo.emplace_back(&v, d + 1);
    else if (const auto* a = n->as_array())
      for (const auto& v : *a) todo.emplace_back(&v, d + 1);
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
