#pragma once
// The CSV files of `validate` (DESIGN.md §3) and a writer that never leaves half a result behind.
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "validation/harness.h"

namespace chutelab::validation {

std::string predictions_csv(const ValidationResult& r);
std::string errors_csv(const ValidationResult& r);
std::string summary_csv(const ValidationResult& r);

using OutputFile = std::pair<std::string, std::string>;  // file name, content

// Writes every file through an OutputFolder (core/output_folder.h): all or nothing, never onto one
// of `inputs` (the files and folders the command read), recorded as `command`'s in the folder.
void write_outputs(const std::filesystem::path& dir, const std::vector<OutputFile>& files,
                   const std::vector<std::filesystem::path>& inputs, std::string_view command);

// Number formatting shared by every CSV (core/csv_field.h): the shortest decimal that reads back as
// the same double; empty for a value that is not finite.
std::string csv_number(double v);
std::string csv_number(const std::optional<double>& v);

}  // namespace chutelab::validation
