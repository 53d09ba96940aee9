#pragma once
// Text placed in markup: the report's HTML pages and inline SVG (reports/svg.h) and the JUnit XML
// file (validation/junit.h). The characters markup gives a meaning to become entities, in one place
// for both, so that the two outputs escape alike; they differ only where their formats do.
#include <string>
#include <string_view>

#include "core/utf8.h"

namespace chutelab {

enum class Markup {
  // HTML and SVG text or attribute values: the apostrophe as &#39; (HTML 4 has no &apos;); a line
  // break stays one (the pages keep it in <pre> blocks and tooltips).
  html,
  // XML 1.0 text content: &apos;, and a carriage return as &#13; (a parser reads a literal one as a
  // line break).
  xml_text,
  // An XML 1.0 attribute value: as text, and a line break and a tab as &#10; and &#9; (a parser
  // reads a literal one as a space).
  xml_attribute,
};

// For XML the text is first made UTF-8 as core/utf8.h does (bytes that are not UTF-8 read as
// Latin-1, control characters XML 1.0 cannot carry as U+FFFD), and U+FFFE and U+FFFF, which are no
// characters of XML 1.0 at all, become U+FFFD too: the file stays well-formed whatever a name holds.
inline std::string markup_escape(std::string_view raw, Markup m) {
  const bool xml = m != Markup::html;
  const std::string utf8 = xml ? to_utf8(raw) : std::string();
  const std::string_view s = xml ? std::string_view(utf8) : raw;
  std::string o;
  o.reserve(s.size());
  for (std::size_t i = 0; i < s.size(); ++i) {
    const char c = s[i];
    switch (c) {
      case '&': o += "&amp;"; break;
      case '<': o += "&lt;"; break;
      case '>': o += "&gt;"; break;
      case '"': o += "&quot;"; break;
      case '\'': o += xml ? "&apos;" : "&#39;"; break;
      case '\n': o += m == Markup::xml_attribute ? "&#10;" : "\n"; break;
      case '\t': o += m == Markup::xml_attribute ? "&#9;" : "\t"; break;
      case '\r': o += xml ? "&#13;" : "\r"; break;
      default:
        if (xml && static_cast<unsigned char>(c) == 0xEF && i + 2 < s.size() &&
            static_cast<unsigned char>(s[i + 1]) == 0xBF && (static_cast<unsigned char>(s[i + 2]) & 0xFE) == 0xBE) {
          o += "\xEF\xBF\xBD";  // U+FFFE or U+FFFF
          i += 2;
        } else {
          o += c;
        }
    }
  }
  return o;
}

}  // namespace chutelab
