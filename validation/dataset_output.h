#pragma once
// A dataset folder written by chutelab (synthesize: the command line and the Python package call
// this one function), so that what the command line guarantees holds for every entry point: the new
// folder is staged and placed all at once, may not be the source folder nor replace one of its
// files, and holds no file of an earlier dataset (a stale plate_map.csv would be read as part of it):
// an earlier synthesize's is removed, any other refused (core/output_folder.h).
#include <filesystem>
#include <string_view>
#include <vector>

#include "validation/output_files.h"

namespace chutelab::validation {

// What a command reads from a dataset folder: the folder itself (an output folder may not be it)
// and every file the dataset reader may open in it; nothing for a dataset without a folder.
std::vector<std::filesystem::path> dataset_files(const std::filesystem::path& dir);

// Writes `files` as the dataset folder `out`, made from the dataset in `source_dir` by `command`
// (synthesize, synthesize-logs, import-logs: each takes the others' earlier files for its own).
void write_dataset(const std::filesystem::path& out, const std::vector<OutputFile>& files,
                   const std::filesystem::path& source_dir, std::string_view command);

}  // namespace chutelab::validation
