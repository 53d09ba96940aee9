#pragma once
// The designer's page as built into this executable (absent when the build had no emscripten).
#include <optional>
#include <string_view>

namespace chutelab::app {
std::optional<std::string_view> design_page();
}  // namespace chutelab::app
