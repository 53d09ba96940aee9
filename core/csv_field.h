#pragma once
// The one CSV writer's cells, for every CSV chutelab writes (the designer's page calls the same
// function through WebAssembly):
//
// - Text (RFC 4180): a cell that holds a comma, a quote, a line end or edge spaces (which readers
//   trim) is quoted, quotes doubled, so the file reads back column for column.
// - Spreadsheet formulas (CSV injection): a text cell a spreadsheet would evaluate, one that starts
//   with '=', '+', '-', '@', a tab or a carriage return (a condition named "=HYPERLINK(...)"), is
//   written with a leading apostrophe, as OWASP recommends: Excel, LibreOffice and Google Sheets
//   show it as text. chutelab's readers (validation/csv_table.h, the Python package) remove exactly
//   that apostrophe again, so every name reads back unchanged; a text that itself starts with an
//   apostrophe followed by one of those characters or by another apostrophe gets one more, so the
//   mapping is one-to-one. Numbers are not text: -50 is written as -50.
// - Numbers: the shortest decimal that reads back as the same double (round-trip precision), since
//   any CSV chutelab writes may be read again (a synthetic or imported dataset, predictions.csv of an
//   external:NAME=DIR model, a sweep, a study); non-finite values are empty cells.
#include <cmath>
#include <string>
#include <string_view>

#include <fmt/format.h>

namespace chutelab {

inline bool csv_formula_start(char c) { return c == '=' || c == '+' || c == '-' || c == '@' || c == '\t' || c == '\r'; }

// Whether a cell as written starts with the apostrophe the writer put there (and the reader removes).
inline bool csv_escaped_formula(std::string_view cell) {
  return cell.size() >= 2 && cell[0] == '\'' && (csv_formula_start(cell[1]) || cell[1] == '\'');
}

inline std::string csv_field(std::string_view s) {
  std::string text;
  if (!s.empty() && (csv_formula_start(s.front()) || csv_escaped_formula(s))) text = "'";
  text += s;
  const bool edge_space = !text.empty() && (text.front() == ' ' || text.front() == '\t' || text.back() == ' ' ||
                                            text.back() == '\t');
  if (!edge_space && text.find_first_of(",\"\r\n") == std::string::npos) return text;
  std::string out = "\"";
  for (char c : text) {
    if (c == '"') out += '"';
    out += c;
  }
  return out + '"';
}

// The text of a cell as read (after unquoting): the writer's apostrophe removed.
inline std::string csv_unescape(std::string cell) {
  if (csv_escaped_formula(cell)) cell.erase(0, 1);
  return cell;
}

inline std::string csv_number(double v) { return std::isfinite(v) ? fmt::format("{}", v) : std::string(); }

}  // namespace chutelab
