#include "validation/csv_table.h"

#include <cmath>
#include <fmt/format.h>
#include <fstream>
#include <sstream>

#include "core/csv_field.h"
#include "core/input_error.h"
#include "core/message.h"
#include "core/text_file.h"
#include "core/number.h"
#include "core/utf8.h"


namespace chutelab::validation {
namespace {

std::string trim(std::string_view s) {
  const auto b = s.find_first_not_of(" \t\r");
  if (b == std::string_view::npos) return {};
  const auto e = s.find_last_not_of(" \t\r");
  return std::string(s.substr(b, e - b + 1));
}

// RFC 4180 fields: commas separate, double quotes protect commas, "" is a literal quote.
std::vector<std::string> split(std::string_view line, const std::string& file, long line_no) {
  std::vector<std::string> out;
  std::string cell;
  bool quoted = false, was_quoted = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (quoted) {
      if (c == '"') {
        if (i + 1 < line.size() && line[i + 1] == '"') {
          cell += '"';
          ++i;
        } else {
          quoted = false;
        }
      } else {
        cell += c;
      }
    } else if (c == '"') {
      quoted = was_quoted = true;
    } else if (c == ',') {
      out.push_back(csv_unescape(was_quoted ? cell : trim(cell)));
      cell.clear();
      was_quoted = false;
    } else {
      cell += c;
    }
  }
  if (quoted) throw InputError(file, line_no, "", "unterminated quoted field");
  out.push_back(csv_unescape(was_quoted ? cell : trim(cell)));
  return out;
}

}  // namespace

CsvTable CsvTable::read(const std::filesystem::path& path,
                       std::initializer_list<std::string_view> required) {
  return read(path, std::vector<std::string_view>(required), {});
}

CsvTable CsvTable::read(const std::filesystem::path& path, const std::vector<std::string_view>& required,
                        std::string layout) {
  // Checked before any line is split (core/text_file.h): a NUL would end a line early ("row has 1
  // fields"), UTF-16 reads as NULs, and a byte-order mark in mid-file would stick to the first cell
  // of its line.
  return parse(read_text_file(path.string()), path.string(), required, std::move(layout));
}

CsvTable CsvTable::parse(std::string_view content, std::string file, std::initializer_list<std::string_view> required) {
  return parse(content, std::move(file), std::vector<std::string_view>(required), {});
}

CsvTable CsvTable::parse(std::string_view content, std::string file, const std::vector<std::string_view>& required,
                         std::string layout) {
  CsvTable t;
  t.file_ = std::move(file);
  t.layout_ = std::move(layout);
  if (auto p = text_encoding_problem(content)) throw InputError(t.file_, p->line, "", p->problem);
  bool warned_latin1 = false;
  bool have_header = false;
  long line_no = 0;
  for (std::size_t start = 0; start < content.size();) {
    const std::size_t nl = content.find('\n', start);
    const std::size_t end = nl == std::string::npos ? content.size() : nl;
    std::string_view line(content.data() + start, end - start);
    start = end + 1;
    ++line_no;
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    if (line_no == 1 && line.size() >= 3 && line.substr(0, 3) == "\xEF\xBB\xBF")
      line.remove_prefix(3);  // UTF-8 byte-order mark from spreadsheet exports
    if (trim(line).empty() || trim(line)[0] == '#') continue;  // blank lines and comments
    // A CR inside a line: the file ends its lines with CR alone (classic Mac OS, some loggers),
    // so the whole file arrived as one line; the columns would be reported missing otherwise.
    if (const auto cr = line.find('\r'); cr != std::string_view::npos)
      throw InputError(t.file_, line_no, "",
                       "lines end with CR only (classic Mac OS line ends); save the file with LF or CRLF "
                       "line ends");
    auto cells = split(line, t.file_, line_no);
    for (auto& c : cells)
      if (!valid_utf8(c)) {
        if (!warned_latin1) warn(fmt::format("{}:{}: text is not UTF-8; read as Latin-1", t.file_, line_no));
        warned_latin1 = true;
        c = to_utf8(c);
      }
    if (!have_header) {
      t.header_ = std::move(cells);
      for (std::size_t i = 0; i < t.header_.size(); ++i)
        for (std::size_t j = 0; j < i; ++j)
          if (t.header_[i] == t.header_[j])
            throw InputError(t.file_, line_no, t.header_[i], "column appears twice in the header");
      have_header = true;
      for (std::string_view r : required)
        if (!t.column(r)) t.explain_missing(r, line_no);
      continue;
    }
    if (cells.size() != t.header_.size())
      throw InputError(t.file_, line_no, "",
                       fmt::format("row has {} fields, the header has {}", cells.size(), t.header_.size()));
    t.rows_.push_back({line_no, std::move(cells)});
  }
  if (!have_header) throw InputError(t.file_, 0, "", "file is empty (no header line)");
  return t;
}

std::optional<std::size_t> CsvTable::column(std::string_view name) const {
  for (std::size_t i = 0; i < header_.size(); ++i)
    if (header_[i] == name) return i;
  return std::nullopt;
}

void CsvTable::explain_missing(std::string_view name, long line) const {
  // The header may hold the column behind another separator (European spreadsheets write ';',
  // others tabs): saying "missing" would send the user looking for a column that is there.
  if (header_.size() == 1)
    for (auto [sep, what] : {std::pair{';', "semicolons"}, {'\t', "tabs"}, {'|', "'|'"}})
      if (header_[0].find(sep) != std::string::npos && header_[0].find(name) != std::string::npos)
        throw InputError(file_, line, std::string(name),
                         fmt::format("the header is separated by {}, not commas; save the file as comma-separated "
                                     "CSV (decimal point '.')",
                                     what));
  if (!layout_.empty())
    throw InputError(file_, line, std::string(name),
                     fmt::format("required column is missing from the header; {}", layout_));
  throw InputError(file_, line, std::string(name), "required column is missing from the header");
}

std::size_t CsvTable::require(std::string_view name) const {
  if (auto c = column(name)) return *c;
  explain_missing(name, 1);
  return 0;
}

const std::string& CsvTable::text(const CsvRow& row, std::size_t col) const {
  return row.cells.at(col);
}

double CsvTable::number(const CsvRow& row, std::size_t col) const {
  const std::string& s = row.cells.at(col);
  const std::string& field = header_.at(col);
  if (s.empty()) throw InputError(file_, row.line, field, "value is missing");
  const std::optional<double> parsed = parse_number(s);
  if (!parsed) throw InputError(file_, row.line, field, fmt::format("{} is not a number", shown(s)));
  const double v = *parsed;
  if (!std::isfinite(v))
    throw InputError(file_, row.line, field, fmt::format("{} is not a finite number", shown(s)));
  return v;
}

std::optional<double> CsvTable::optional_number(const CsvRow& row, std::size_t col) const {
  if (row.cells.at(col).empty()) return std::nullopt;
  return number(row, col);
}

}  // namespace chutelab::validation
