#pragma once
// The command line's words for the library's neutral keys (core/input_error.h): "models" is
// --models, "dem.no_cache" is --no-dem-cache. Every message the command line prints goes through
// here, so the library never needs to know how a flag is spelt.
#include <string>
#include <string_view>

#include "core/input_error.h"

namespace chutelab::app {

// The flag of an option's key; a key that is not an option (a column, a TOML key) as it is.
std::string flag_for(std::string_view key);

// An error as the command line says it: its field and every input it mentions named by their flags.
std::string said(const InputError& e);
// Its problem alone, mentions named by their flags.
std::string problem_said(const InputError& e);

}  // namespace chutelab::app
