#include "core/text_file.h"

#include <fmt/format.h>

#include <fstream>

#include "core/input_error.h"
#include "core/message.h"

namespace chutelab {

std::string read_text_file(const std::string& file, std::size_t max_bytes, std::string_view field) {
  require_readable_file(file, std::string(field));
  std::ifstream in(file, std::ios::binary);
  std::string text;
  constexpr std::size_t kChunk = std::size_t{1} << 16;
  for (;;) {
    const std::size_t at = text.size();
    text.resize(at + kChunk);
    in.read(text.data() + at, static_cast<std::streamsize>(kChunk));
    const auto got = static_cast<std::size_t>(in.gcount());
    text.resize(at + got);
    if (in.bad()) throw InputError(file, 0, std::string(field), "cannot be read");
    // A NUL ends the reading at once: binary data, UTF-16, or a device of zeros or random bytes.
    if (text.find('\0', at) != std::string::npos)
      if (auto p = text_encoding_problem(text)) throw InputError(file, p->line, std::string(field), p->problem);
    if (text.size() > max_bytes)
      throw InputError(file, 0, std::string(field),
                       fmt::format("is larger than {}, the most chutelab reads of such a file", byte_size(max_bytes)));
    if (got < kChunk) break;
  }
  if (auto p = text_encoding_problem(text)) throw InputError(file, p->line, std::string(field), p->problem);
  return text;
}

}  // namespace chutelab
