#include "app/validate_console.h"

#include <algorithm>
#include <string_view>

#include "core/message.h"

namespace chutelab::app {

std::string console_text(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (std::size_t at = 0; at < text.size();) {
    const std::size_t end = std::min(text.find('\n', at), text.size());
    out += one_line(std::string_view(text).substr(at, end - at), std::string::npos);
    if (end < text.size()) out += '\n';
    at = end + 1;
  }
  return out;
}

}  // namespace chutelab::app
