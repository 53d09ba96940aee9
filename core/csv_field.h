#pragma once
// RFC 4180 fields for every CSV chutelab writes: a text cell that holds a comma, a quote, a line end
// or edge spaces (which readers trim) is quoted, quotes doubled, so the file reads back column for
// column. Numbers and the vocabulary's names never need it; names from the user's files may.
#include <string>
#include <string_view>

namespace chutelab {

inline std::string csv_field(std::string_view s) {
  const bool edge_space = !s.empty() && (s.front() == ' ' || s.front() == '\t' || s.back() == ' ' || s.back() == '\t');
  if (!edge_space && s.find_first_of(",\"\r\n") == std::string_view::npos) return std::string(s);
  std::string out = "\"";
  for (char c : s) {
    if (c == '"') out += '"';
    out += c;
  }
  return out + '"';
}

}  // namespace chutelab
