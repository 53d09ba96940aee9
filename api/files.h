#pragma once
// Datasets in and result files out, as every command reads and writes them: a dataset folder read
// whole (one of rig logs with its logs read into means, logs/dataset_logs.h), and result files
// placed all or none (core/output_folder.h), never onto an input, recorded as a command's in the
// folder. The front ends call these rather than the readers and writers behind them.
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "api/output_plan.h"
#include "validation/dataset.h"

namespace chutelab::api {

// A dataset as read, and its files as kept in memory (name -> shown name, text, unread), under the
// library's names: a front end reaches them through api/, never through validation/.
using Dataset = validation::Dataset;
using DatasetTexts = validation::DatasetTexts;

// A dataset folder; with measurements_required, one without measurements is bad input.
validation::Dataset read_dataset(const std::filesystem::path& dir, bool measurements_required);
// The same from its files in memory (validation::Dataset::sources); `dir` is the folder they stand
// for, empty for none.
validation::Dataset read_dataset(const validation::DatasetTexts& files, const std::filesystem::path& dir,
                                 bool measurements_required);

// What a run reads from a dataset folder: the folder itself (an output folder may not be it) and
// every file the reader may open in it (OutputPlan::inputs).
std::vector<std::filesystem::path> dataset_files(const std::filesystem::path& dir);

// A result's files (ValidateResult::files(), ...) into the folder `out`, all or none, never onto one
// of `inputs`, recorded as `command`'s.
void write_files(const std::filesystem::path& out, const std::vector<OutputFile>& files,
                 const std::vector<std::filesystem::path>& inputs, std::string_view command);
// A CSV text's header and rows of cells, as chutelab's reader splits them (quotes, the writer's
// apostrophe before a formula character, trimmed edges); `file` names it in errors.
struct CsvCells {
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;
};
CsvCells csv_cells(std::string_view text, const std::string& file);

// A new dataset to fill with a rig's numbers, as the folder `out`: setup.toml, five conditions,
// placeholder measurements and README.md, every line commented, the rig of the dataset `example`.
void write_dataset_skeleton(const std::filesystem::path& out, const std::filesystem::path& example);
// The reference of every dataset file, column and key (Markdown), from the readers' own tables.
std::string dataset_reference();

// A dataset's files (SynthesizeResult::files, ...) as the dataset folder `out`, made from the one in
// `source_dir` by `command`.
void write_dataset(const std::filesystem::path& out, const std::vector<OutputFile>& files,
                   const std::filesystem::path& source_dir, std::string_view command);

}  // namespace chutelab::api
