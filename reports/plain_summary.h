#pragma once
// The outcome of a validation in a bulk-handling engineer's words, for the top of the report and
// for validate's console: which quantities the models get wrong and by how much (per cent, mm),
// what an added effect changes, and what to do about it. The statistics (RMS E/u_val, chi^2) are
// quoted as evidence after the words, never instead of them.
#include <string>
#include <string_view>
#include <vector>

#include "reports/report.h"
#include "validation/quantity_misfit.h"

namespace chutelab::reports {

// "air drag (drag coefficient 0.752 ± 0.031, fitted to these measurements)"; brief: "..., fitted)".
std::string effect_words(const EffectDescription& e, bool brief = false);
// "V5-44 (5 m/s, 44 t/h)"
std::string condition_words(const validation::Dataset& d, const std::string& condition);

// One aligned line per quantity beyond the noise (before, or before -> after when effects were
// added; quantities that only fail after are listed too), worst first, at most `max` lines (then
// one line saying how many more). Each line: quantity, judging model, mean error, worst condition.
std::vector<std::string> misfit_lines(const ReportInput& in, std::size_t max);

// Two or three sentences: what the models as they are get wrong, what the added effect (or the
// diagnosis) changes, and what to do. A model that agrees with the measurements on its own values
// is named as agreeing, and one that misses is never covered by "the models agree".
std::vector<std::string> in_short(const ReportInput& in);

// A hint is a command the reader pastes into a shell and runs as printed, whichever front end wrote
// the report: `s` as one shell word (quoted when the shell would split or expand it).
std::string shell_word(const std::string& s);
// "chutelab validate --dataset D FLAG --out out/D-WHAT": the dataset as it was given, a new folder.
std::string validate_command(const ReportInput& in, std::string_view flag, std::string_view what);

// When the effects added are not what the diagnosis points to: one sentence saying so (empty
// otherwise, and without a diagnosis).
std::string effect_choice_warning(const ReportInput& in);

}  // namespace chutelab::reports
