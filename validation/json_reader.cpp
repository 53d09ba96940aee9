#include "validation/json_reader.h"

#include <fmt/format.h>
#include <fstream>
#include <sstream>

#include "core/input_error.h"
#include "core/number.h"
#include "core/text_file.h"

namespace chutelab::validation {

const JsonArray* JsonValue::array() const {
  auto p = std::get_if<std::shared_ptr<JsonArray>>(&value);
  return p ? p->get() : nullptr;
}

const JsonObject* JsonValue::object() const {
  auto p = std::get_if<std::shared_ptr<JsonObject>>(&value);
  return p ? p->get() : nullptr;
}

const JsonValue* JsonValue::member(const std::string& key) const {
  const JsonObject* o = object();
  if (!o) return nullptr;
  for (const auto& [k, v] : *o)
    if (k == key) return &v;
  return nullptr;
}

namespace {

class Parser {
 public:
  Parser(const std::string& text, std::string file) : s_(text), file_(std::move(file)) {}

  JsonValue document() {
    JsonValue v = value(0);
    space();
    if (pos_ != s_.size()) fail("unexpected text after the JSON value");
    return v;
  }

 private:
  const std::string& s_;
  std::string file_;
  std::size_t pos_ = 0;
  long line_ = 1;

  [[noreturn]] void fail(const std::string& why) const {
    throw InputError(file_, line_, "", "malformed JSON: " + why);
  }

  void space() {
    while (pos_ < s_.size()) {
      const char c = s_[pos_];
      if (c == '\n') ++line_;
      else if (c != ' ' && c != '\t' && c != '\r') break;
      ++pos_;
    }
  }

  bool literal(const char* word) {
    const std::string w(word);
    if (s_.compare(pos_, w.size(), w) != 0) return false;
    pos_ += w.size();
    return true;
  }

  JsonValue value(int depth) {
    if (depth > 200) fail("nested too deeply");
    space();
    if (pos_ >= s_.size()) fail("unexpected end of file");
    JsonValue v;
    v.line = line_;
    const char c = s_[pos_];
    if (c == '{') {
      auto obj = std::make_shared<JsonObject>();
      ++pos_;
      space();
      if (pos_ < s_.size() && s_[pos_] == '}') {
        ++pos_;
      } else {
        while (true) {
          space();
          if (pos_ >= s_.size() || s_[pos_] != '"') fail("expected a \"key\"");
          std::string key = string();
          space();
          if (pos_ >= s_.size() || s_[pos_] != ':') fail("expected ':' after a key");
          ++pos_;
          obj->emplace_back(std::move(key), value(depth + 1));
          space();
          if (pos_ < s_.size() && s_[pos_] == ',') { ++pos_; continue; }
          if (pos_ < s_.size() && s_[pos_] == '}') { ++pos_; break; }
          fail("expected ',' or '}' in an object");
        }
      }
      v.value = obj;
    } else if (c == '[') {
      auto arr = std::make_shared<JsonArray>();
      ++pos_;
      space();
      if (pos_ < s_.size() && s_[pos_] == ']') {
        ++pos_;
      } else {
        while (true) {
          arr->push_back(value(depth + 1));
          space();
          if (pos_ < s_.size() && s_[pos_] == ',') { ++pos_; continue; }
          if (pos_ < s_.size() && s_[pos_] == ']') { ++pos_; break; }
          fail("expected ',' or ']' in an array");
        }
      }
      v.value = arr;
    } else if (c == '"') {
      v.value = string();
    } else if (literal("true")) {
      v.value = true;
    } else if (literal("false")) {
      v.value = false;
    } else if (literal("null")) {
      v.value = nullptr;
    } else {
      const std::size_t start = pos_;
      while (pos_ < s_.size() && std::string_view("+-0123456789.eE").find(s_[pos_]) != std::string_view::npos)
        ++pos_;
      const auto n = parse_number(std::string_view(s_).substr(start, pos_ - start));
      if (pos_ == start || !n) fail("expected a value");
      v.value = *n;
    }
    return v;
  }

  std::string string() {
    ++pos_;  // opening quote
    std::string out;
    while (true) {
      if (pos_ >= s_.size()) fail("unterminated string");
      const char c = s_[pos_++];
      if (c == '"') return out;
      if (c == '\n') fail("line break inside a string");
      if (c != '\\') { out += c; continue; }
      if (pos_ >= s_.size()) fail("unterminated string");
      const char e = s_[pos_++];
      switch (e) {
        case '"': out += '"'; break;
        case '\\': out += '\\'; break;
        case '/': out += '/'; break;
        case 'b': out += '\b'; break;
        case 'f': out += '\f'; break;
        case 'n': out += '\n'; break;
        case 'r': out += '\r'; break;
        case 't': out += '\t'; break;
        case 'u': {
          if (pos_ + 4 > s_.size()) fail("short \\u escape");
          unsigned cp = 0;
          for (int i = 0; i < 4; ++i) {
            const char h = s_[pos_++];
            cp <<= 4;
            if (h >= '0' && h <= '9') cp |= static_cast<unsigned>(h - '0');
            else if (h >= 'a' && h <= 'f') cp |= static_cast<unsigned>(h - 'a' + 10);
            else if (h >= 'A' && h <= 'F') cp |= static_cast<unsigned>(h - 'A' + 10);
            else fail("bad \\u escape");
          }
          // UTF-8 of the basic plane (names in WebPlotDigitizer files are plain text).
          if (cp < 0x80) out += static_cast<char>(cp);
          else if (cp < 0x800) {
            out += static_cast<char>(0xC0 | (cp >> 6));
            out += static_cast<char>(0x80 | (cp & 0x3F));
          } else {
            out += static_cast<char>(0xE0 | (cp >> 12));
            out += static_cast<char>(0x80 | ((cp >> 6) & 0x3F));
            out += static_cast<char>(0x80 | (cp & 0x3F));
          }
          break;
        }
        default: fail(fmt::format("bad escape '\\{}'", e));
      }
    }
  }
};

}  // namespace

JsonValue parse_json(const std::string& text, const std::string& file) { return Parser(text, file).document(); }

JsonValue read_json(const std::filesystem::path& path) {
  return parse_json(read_text_file(path.string(), std::size_t{1} << 28), path.string());
}

}  // namespace chutelab::validation
