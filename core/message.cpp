#include "core/message.h"

#include <fmt/format.h>

#include <algorithm>
#include <cstdint>
#include <iostream>

#include "core/utf8.h"

namespace chutelab {
namespace {

std::uint32_t code_point(std::string_view s, std::size_t i, std::size_t n) {
  const auto b = [&](std::size_t k) { return static_cast<std::uint32_t>(static_cast<unsigned char>(s[i + k])); };
  switch (n) {
    case 1: return b(0);
    case 2: return ((b(0) & 0x1F) << 6) | (b(1) & 0x3F);
    case 3: return ((b(0) & 0x0F) << 12) | ((b(1) & 0x3F) << 6) | (b(2) & 0x3F);
    default: return ((b(0) & 0x07) << 18) | ((b(1) & 0x3F) << 12) | ((b(2) & 0x3F) << 6) | (b(3) & 0x3F);
  }
}

// Code points a terminal shows as nothing (or as a plain space) or that reorder the text around them.
bool invisible(std::uint32_t c) {
  return (c >= 0x80 && c <= 0xA0) || c == 0xAD || c == 0x034F || c == 0x061C || c == 0x115F || c == 0x1160 ||
         c == 0x17B4 || c == 0x17B5 || c == 0x180E || (c >= 0x2000 && c <= 0x200F) || (c >= 0x2028 && c <= 0x202F) ||
         (c >= 0x205F && c <= 0x206F) || c == 0x3000 || c == 0x3164 || (c >= 0xFE00 && c <= 0xFE0F) || c == 0xFEFF ||
         c == 0xFFA0 || (c >= 0xFFF0 && c <= 0xFFFB) || (c >= 0xE0000 && c <= 0xE0FFF);
}

// Appends s[i, i + n) escaped; returns the bytes consumed.
std::size_t escape_one(std::string_view s, std::size_t i, std::string& out) {
  const auto c = static_cast<unsigned char>(s[i]);
  if (c < 0x80) {
    switch (c) {
      case '\0': out += "<NUL>"; break;
      case '\t': out += "\\t"; break;
      case '\n': out += "\\n"; break;
      case '\r': out += "\\r"; break;
      default:
        if (c < 0x20 || c == 0x7F) out += fmt::format("\\x{:02x}", c);
        else out += static_cast<char>(c);
    }
    return 1;
  }
  const std::size_t n = utf8_sequence(s, i);
  if (n == 0) {
    out += fmt::format("\\x{:02x}", c);
    return 1;
  }
  const std::uint32_t cp = code_point(s, i, n);
  if (cp == 0xFEFF) out += "<BOM>";
  else if (invisible(cp)) out += cp > 0xFFFF ? fmt::format("\\U{:08x}", cp) : fmt::format("\\u{:04x}", cp);
  else out.append(s.substr(i, n));
  return n;
}

std::string escaped(std::string_view s) {
  std::string out;
  out.reserve(s.size());
  for (std::size_t i = 0; i < s.size();) i += escape_one(s, i, out);
  return out;
}

// The largest cut <= at that does not split a UTF-8 sequence.
std::size_t boundary(std::string_view s, std::size_t at) {
  at = std::min(at, s.size());
  while (at > 0 && at < s.size() && (static_cast<unsigned char>(s[at]) & 0xC0) == 0x80) --at;
  return at;
}

long line_at(std::string_view text, std::size_t pos) {
  return 1 + static_cast<long>(std::count(text.begin(), text.begin() + static_cast<long>(pos), '\n'));
}

}  // namespace

void warn(std::string_view message) { std::cerr << "warning: " << one_line(message) << "\n"; }

std::string byte_size(std::size_t n) {
  if (n < 1024) return fmt::format("{} bytes", n);
  if (n < 1024 * 1024) return fmt::format("{:.3g} KiB", static_cast<double>(n) / 1024.0);
  if (n < std::size_t{1024} * 1024 * 1024) return fmt::format("{:.3g} MiB", static_cast<double>(n) / 1048576.0);
  return fmt::format("{:.3g} GiB", static_cast<double>(n) / 1073741824.0);
}

std::string shown(std::string_view value, std::size_t max) {
  if (value.size() <= max) return fmt::format("'{}'", escaped(value));
  const std::size_t cut = boundary(value, max);
  return fmt::format("'{}…' ({})", escaped(value.substr(0, cut)), byte_size(value.size()));
}

std::string one_line(std::string_view message, std::size_t max) {
  std::string e = escaped(message);
  if (e.size() <= max) return e;
  const std::size_t head = boundary(e, max * 2 / 3);
  std::size_t tail_start = e.size() - max / 4;
  while (tail_start < e.size() && (static_cast<unsigned char>(e[tail_start]) & 0xC0) == 0x80) ++tail_start;
  return fmt::format("{} … [{} left out] … {}", e.substr(0, head), byte_size(tail_start - head), e.substr(tail_start));
}

std::optional<TextProblem> text_encoding_problem(std::string_view t) {
  const auto starts = [&](std::string_view p) { return t.substr(0, p.size()) == p; };
  using namespace std::string_view_literals;
  if (starts("\xFF\xFE\x00\x00"sv) || starts("\x00\x00\xFE\xFF"sv))
    return TextProblem{0, "is UTF-32 text; save it as UTF-8"};
  if (starts("\xFF\xFE"sv) || starts("\xFE\xFF"sv))
    return TextProblem{0, fmt::format("is UTF-16 text ({} byte-order mark); save it as UTF-8",
                                      t[0] == '\xFF' ? "little-endian" : "big-endian")};
  if (const auto nul = t.find('\0'); nul != std::string_view::npos) {
    // ASCII in UTF-16 without a byte-order mark: every other byte is NUL.
    const std::size_t n = std::min<std::size_t>(t.size(), 512);
    std::size_t even = 0, odd = 0;
    for (std::size_t i = 0; i < n; ++i)
      if (t[i] == '\0') (i % 2 ? odd : even)++;
    // (One parity of bytes mostly NUL and the other mostly not; all NUL is no text at all.)
    if (n >= 4 && ((even * 4 >= n && odd * 8 < n) || (odd * 4 >= n && even * 8 < n)))
      return TextProblem{0, "looks like UTF-16 text (every other byte is NUL); save it as UTF-8"};
    const std::size_t line_start = t.rfind('\n', nul) == std::string_view::npos ? 0 : t.rfind('\n', nul) + 1;
    return TextProblem{line_at(t, nul),
                       fmt::format("holds a NUL byte (byte {} of the line): binary data, or text in another "
                                   "encoding than UTF-8?",
                                   nul - line_start + 1)};
  }
  if (const auto bom = t.find("\xEF\xBB\xBF", 1); bom != std::string_view::npos)
    return TextProblem{line_at(t, bom),
                       "holds a byte-order mark (U+FEFF) inside the file, not at its start: were two files "
                       "joined? Remove it"};
  return std::nullopt;
}

}  // namespace chutelab
