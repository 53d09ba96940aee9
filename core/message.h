#pragma once
// The one formatter for what the user gave, inside a message. A value from a file or the command
// line may be 10 MB long, hold a NUL, a line end, a terminal escape, a right-to-left override or a
// zero-width space: echoed raw it floods the terminal, breaks the one-line promise or hides what is
// wrong. So every value is shown through here: invisible characters escaped and named, long values
// cut with their size said; and whole messages are made one line by the same rules (InputError does
// that for every message it carries, so no caller can forget it).
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

namespace chutelab {

// At most this many bytes of a value are shown.
inline constexpr std::size_t kShownValueBytes = 80;
// A whole one-line message never exceeds this (its start and end are kept).
inline constexpr std::size_t kMessageBytes = 1000;

// The value quoted: 'abc'. NUL is <NUL>, a tab \t, a line end \n or \r, other controls \x1b,
// bytes that are not UTF-8 \xff, invisible or direction-changing code points (zero-width spaces,
// bidirectional overrides, the byte-order mark, the no-break space) \u200b; beyond `max` bytes the
// value is cut at a character boundary and its length is said: 'abcd…' (10485760 bytes).
std::string shown(std::string_view value, std::size_t max = kShownValueBytes);

// The same escaping without quotes, for a whole message: one line, at most `max` bytes (the middle
// of a longer one is replaced by "… [N bytes left out] …").
std::string one_line(std::string_view message, std::size_t max = kMessageBytes);

// Prints "warning: MESSAGE" on stderr, the message made one line by one_line().
void warn(std::string_view message);

// "512 bytes", "1 MiB", "12.3 MiB".
std::string byte_size(std::size_t n);

// Why a text file cannot be read as UTF-8 text, when it cannot: UTF-16/UTF-32 (by byte-order mark or
// by the NUL bytes of ASCII in UTF-16), a NUL byte (binary data), or a byte-order mark in the middle
// of the file (two files joined; it would otherwise stick to the first name of its line).
struct TextProblem {
  long line = 0;  // 1-based; 0 for the whole file
  std::string problem;
};
std::optional<TextProblem> text_encoding_problem(std::string_view text);

}  // namespace chutelab
