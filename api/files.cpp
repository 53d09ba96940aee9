#include "api/files.h"

#include "logs/dataset_logs.h"
#include "validation/csv_table.h"
#include "validation/dataset_fields.h"
#include "validation/dataset_output.h"
#include "validation/dataset_reference.h"
#include "validation/output_files.h"

namespace chutelab::api {
namespace {
validation::MeasurementsRequired need(bool required) {
  return required ? validation::MeasurementsRequired::yes : validation::MeasurementsRequired::no;
}
}  // namespace

validation::Dataset read_dataset(const std::filesystem::path& dir, bool measurements_required) {
  return logs::read_dataset(dir, need(measurements_required));
}

validation::Dataset read_dataset(const validation::DatasetTexts& files, const std::filesystem::path& dir,
                                 bool measurements_required) {
  return validation::read_dataset(files, dir, need(measurements_required));
}

std::vector<std::filesystem::path> dataset_files(const std::filesystem::path& dir) {
  return validation::dataset_files(dir);
}

void write_files(const std::filesystem::path& out, const std::vector<OutputFile>& files,
                 const std::vector<std::filesystem::path>& inputs, std::string_view command) {
  validation::write_outputs(out, files, inputs, command);
}

CsvCells csv_cells(std::string_view text, const std::string& file) {
  const validation::CsvTable t = validation::CsvTable::parse(text, file);
  CsvCells out{t.header(), {}};
  for (const auto& r : t.rows()) out.rows.push_back(r.cells);
  return out;
}

void write_dataset_skeleton(const std::filesystem::path& out, const std::filesystem::path& example) {
  const Setup rig = validation::read_setup(example / "setup.toml");
  validation::write_dataset(out, validation::dataset_skeleton(rig), example, "init");
}

std::string dataset_reference() { return validation::dataset_reference_markdown(); }

void write_dataset(const std::filesystem::path& out, const std::vector<OutputFile>& files,
                   const std::filesystem::path& source_dir, std::string_view command) {
  validation::write_dataset(out, files, source_dir, command);
}

}  // namespace chutelab::api
