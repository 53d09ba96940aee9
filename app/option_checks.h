#pragma once
// The command line's side of core/option_check.h: its rules attached to CLI11 options, and a generic
// check for every option that has none, so that no option is taken unchecked ("inf", "nan", "",
// "1.5" threads) and every check runs while the command line is read, before any work.
#include <CLI/CLI.hpp>

#include "core/option_check.h"

namespace chutelab::app {

// Checks the option's value (each value, for a repeated one) with `rule` as typed; a whole number
// typed as 2.0 or 2e3 is passed on as 2 / 2000.
CLI::Option* with_rule(CLI::Option* opt, const options::NumberRule& rule);

// For every option of every command that has no rule: a number must be finite, a whole number whole
// (and >= 0 when unsigned), a text non-empty. Call once, after every command has added its options.
void check_every_option(CLI::App& app);

}  // namespace chutelab::app
