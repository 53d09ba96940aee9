#pragma once
// A small CSV table: header by name, every cell kept with its line number so that each error can
// name file, line and column. The file is read whole and its encoding checked first (core/message.h).
#include <filesystem>
#include <initializer_list>
#include <optional>
#include <string>
#include <vector>

namespace chutelab::validation {

struct CsvRow {
  long line = 0;
  std::vector<std::string> cells;
};

class CsvTable {
 public:
  // Columns in `required` are checked as soon as the header is read, so a missing column is
  // reported as such rather than as every row being too long; `layout`, when given, says the file's
  // header with an example row, shown with a missing column (a wide table sent where a long one is
  // read learns the layout from the message).
  static CsvTable read(const std::filesystem::path& file,
                       std::initializer_list<std::string_view> required = {});
  static CsvTable read(const std::filesystem::path& file, const std::vector<std::string_view>& required,
                       std::string layout);
  // The same for a text already in memory (a dataset's file as read, a table from Python); `file`
  // names it in messages. Its encoding is checked as a file's is.
  static CsvTable parse(std::string_view content, std::string file,
                        std::initializer_list<std::string_view> required = {});
  static CsvTable parse(std::string_view content, std::string file, const std::vector<std::string_view>& required,
                        std::string layout);

  const std::string& file() const { return file_; }
  const std::vector<std::string>& header() const { return header_; }
  const std::vector<CsvRow>& rows() const { return rows_; }
  std::optional<std::size_t> column(std::string_view name) const;
  // Throws InputError naming the file and the missing column.
  std::size_t require(std::string_view name) const;

  const std::string& text(const CsvRow& row, std::size_t col) const;
  // A finite number; throws InputError (file, line, column) for empty, non-numeric, NaN or inf.
  double number(const CsvRow& row, std::size_t col) const;
  // Empty cell -> nullopt; otherwise as number().
  std::optional<double> optional_number(const CsvRow& row, std::size_t col) const;

 private:
  [[noreturn]] void explain_missing(std::string_view name, long line) const;
  std::string file_, layout_;
  std::vector<std::string> header_;
  std::vector<CsvRow> rows_;
};

}  // namespace chutelab::validation
