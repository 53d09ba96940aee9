#pragma once
// Reads a text file the user named, whole, through one door: a file of more than `max_bytes` is
// refused with its size said (a device such as /dev/zero named as a file ends at once, not in an
// out-of-memory), and the text's encoding is checked (core/message.h: UTF-16, a NUL byte, a
// byte-order mark inside) before any reader splits it. Throws InputError naming the file (and line).
#include <cstddef>
#include <string>
#include <string_view>

namespace chutelab {

// Text data files (CSV tables of a million rows are ~40 MB): far above any real one.
inline constexpr std::size_t kTextFileMaxBytes = std::size_t{1} << 30;

std::string read_text_file(const std::string& file, std::size_t max_bytes = kTextFileMaxBytes,
                           std::string_view field = "");

}  // namespace chutelab
