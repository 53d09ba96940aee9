#pragma once
// Text placed in markup: the report's HTML pages and inline SVG (reports/svg.h) and the JUnit XML
// file (validation/junit.h). The characters markup gives a meaning to become entities, in one place
// for both, so that the two outputs escape alike; they differ only where their formats do.
#include <string>
#include <string_view>

namespace chutelab {

enum class Markup {
  // HTML and SVG text or attribute values: the apostrophe as &#39; (HTML 4 has no &apos;); a line
  // break stays one (the pages keep it in <pre> blocks and tooltips).
  html,
  // XML 1.0 text content: &apos;, and the control characters XML 1.0 cannot carry at all (below
  // U+0020 but tab and line break) left out.
  xml_text,
  // An XML 1.0 attribute value: as text, and a line break as &#10; (a parser reads a literal one as
  // a space).
  xml_attribute,
};

inline std::string markup_escape(std::string_view s, Markup m) {
  const bool xml = m != Markup::html;
  std::string o;
  o.reserve(s.size());
  for (char c : s) {
    switch (c) {
      case '&': o += "&amp;"; break;
      case '<': o += "&lt;"; break;
      case '>': o += "&gt;"; break;
      case '"': o += "&quot;"; break;
      case '\'': o += xml ? "&apos;" : "&#39;"; break;
      case '\n': o += m == Markup::xml_attribute ? "&#10;" : "\n"; break;
      default:
        if (!xml || static_cast<unsigned char>(c) >= 0x20 || c == '\t') o += c;
    }
  }
  return o;
}

}  // namespace chutelab
