#pragma once
// Whether two names print the same. A condition named "V3-41" and one named "V3-41 " (a quoted
// trailing space), "V3-41" with a no-break space or a zero-width space inside, or "Köln" typed with
// a precomposed ö and with o plus a combining diaeresis (NFC against NFD), are different strings
// that every report, terminal and spreadsheet shows alike: as two conditions they would be
// compared, plotted and tabled as two without anyone seeing why. printed_form() maps a UTF-8 name
// to what a reader sees: invisible format characters (zero-width spaces and joiners, direction
// marks and overrides, the byte-order mark, variation selectors, the soft hyphen) left out, every
// Unicode space as a plain space, spaces at either end trimmed, and the canonical decomposition
// (NFD, Unicode's tables in core/unicode_tables.inc) so that both spellings of an accent agree.
#include <string>
#include <string_view>

namespace chutelab {

std::string printed_form(std::string_view utf8);

}  // namespace chutelab
