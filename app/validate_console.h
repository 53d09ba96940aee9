#pragma once
// Lines for the console (the results a command prints): each line escaped as messages are
// (core/message.h one_line: controls, bytes that are not UTF-8, invisible and direction-changing
// code points), so that a name from the data cannot reorder or hide what is printed around it (a
// right-to-left override in a condition name). Line ends are kept.
#include <string>

namespace chutelab::app {

std::string console_text(const std::string& text);

}  // namespace chutelab::app
