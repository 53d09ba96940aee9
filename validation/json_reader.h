#pragma once
// A small JSON reader that remembers the line of every value, so that a bad entry in a file from
// another tool (WebPlotDigitizer's project JSON) is reported at its line. Strict RFC 8259: no
// comments, no trailing commas; a malformed file throws InputError naming file and line.
#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <variant>
#include <vector>

namespace chutelab::validation {

struct JsonValue;
using JsonArray = std::vector<JsonValue>;
using JsonObject = std::vector<std::pair<std::string, JsonValue>>;  // in file order

struct JsonValue {
  std::variant<std::nullptr_t, bool, double, std::string, std::shared_ptr<JsonArray>,
               std::shared_ptr<JsonObject>>
      value = nullptr;
  long line = 0;

  bool is_number() const { return std::holds_alternative<double>(value); }
  bool is_string() const { return std::holds_alternative<std::string>(value); }
  const JsonArray* array() const;
  const JsonObject* object() const;
  const JsonValue* member(const std::string& key) const;  // null when absent or not an object
};

JsonValue read_json(const std::filesystem::path& file);
JsonValue parse_json(const std::string& text, const std::string& file_for_errors);

}  // namespace chutelab::validation
