// `chutelab import-digitised`: curves digitised from published figures (WebPlotDigitizer's CSV
// export or project JSON) become trajectory.csv / measurements.csv rows of a dataset.
#include <algorithm>
#include <fmt/format.h>
#include <fstream>
#include <iostream>
#include <sstream>
#include <unistd.h>

#include "app/commands.h"
#include "core/campaign.h"
#include "core/csv_field.h"
#include "core/input_error.h"
#include "core/output_folder.h"
#include "validation/dataset.h"
#include "validation/digitised.h"
#include "validation/output_files.h"

namespace chutelab::app {
namespace {
namespace fs = std::filesystem;

struct ImportCli {
  std::string dataset, mapping, out;
  std::vector<std::string> inputs;
};

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

void write_text(const fs::path& file, const std::string& text) {
  std::ofstream out(file, std::ios::binary);
  out << text;
  out.close();
  if (!out) throw InputError(file.string(), 0, "--out", "cannot write the file");
}

std::vector<std::string> header_of(const std::string& text) {
  std::vector<std::string> cols;
  std::string line = text.substr(0, text.find('\n'));
  if (!line.empty() && line.back() == '\r') line.pop_back();
  std::stringstream ss(line);
  for (std::string c; std::getline(ss, c, ',');) cols.push_back(c);
  return cols;
}

// Appends rows to a dataset CSV (created with `columns` when absent), in the existing file's
// column order; columns the rows do not have stay empty.
void append_rows(const fs::path& file, const std::vector<std::string>& columns,
                 const std::vector<std::vector<std::string>>& rows) {
  if (rows.empty()) return;
  std::string text = fs::exists(file) ? slurp(file) : fmt::format("{}\n", fmt::join(columns, ","));
  if (!text.empty() && text.back() != '\n') text += '\n';
  const auto header = header_of(text);
  for (const auto& r : rows) {
    std::vector<std::string> cells(header.size());
    for (std::size_t i = 0; i < header.size(); ++i)
      for (std::size_t j = 0; j < columns.size(); ++j)
        if (header[i] == columns[j]) cells[i] = csv_field(r[j]);  // RFC 4180: "V3,41" stays one field
    text += fmt::format("{}\n", fmt::join(cells, ","));
  }
  write_text(file, text);
}

int run_import(const ImportCli& o) {
  if (campaign::ranks() > 1)  // every rank would write the same new folder
    throw InputError("", 0, "mpirun", "import-digitised writes one dataset folder: run it as one process");
  const fs::path src(o.dataset), out(o.out);
  const auto d = validation::read_dataset(src, validation::MeasurementsRequired::no);
  std::vector<validation::DigitisedCurve> curves;
  for (const auto& in : o.inputs) {
    auto c = validation::read_digitised(in);
    curves.insert(curves.end(), std::make_move_iterator(c.begin()), std::make_move_iterator(c.end()));
  }
  const auto imp = validation::import_digitised(d, o.mapping, curves);

  // The source is copied into the new folder, so the new folder cannot be (or lie inside) it.
  const fs::path csrc = fs::weakly_canonical(src), cdst = fs::weakly_canonical(out);
  const auto [mismatch, rest] = std::mismatch(csrc.begin(), csrc.end(), cdst.begin(), cdst.end());
  if (mismatch == csrc.end())
    throw InputError(o.out, 0, "--out", "is or lies inside the source dataset; the import writes a new dataset folder");
  if (fs::exists(out) && !(fs::is_directory(out) && fs::is_empty(out)))
    throw InputError(o.out, 0, "--out", "exists and is not an empty folder; give a new folder");

  // The new dataset is put together beside OUT and read back by the strict reader before it
  // becomes OUT: a failure leaves nothing behind.
  const fs::path abs_out = fs::absolute(out);
  const fs::path stage = abs_out.parent_path() / fmt::format(".{}.partial-{}", abs_out.filename().string(), ::getpid());
  std::error_code ec;
  fs::remove_all(stage, ec);
  register_temporary(stage);  // Ctrl-C removes it (core/output_folder.h)
  try {
    fs::create_directories(abs_out.parent_path());
    fs::copy(src, stage, fs::copy_options::recursive);
    std::vector<std::vector<std::string>> mrows, trows;
    for (const auto& m : imp.measurements) {
      const double s = info(m.quantity).to_boundary;
      mrows.push_back({m.condition, std::string(name(m.quantity)), validation::csv_number(m.value * s),
                       m.uncertainty ? validation::csv_number(*m.uncertainty * s) : ""});
    }
    for (const auto& p : imp.trajectory)
      trows.push_back({p.condition, std::string(name(p.boundary)), validation::csv_number(p.x * 1e3),
                       validation::csv_number(p.y * 1e3),
                       p.uncertainty ? validation::csv_number(*p.uncertainty * 1e3) : ""});
    append_rows(stage / "measurements.csv", {"condition", "quantity", "value", "uncertainty"}, mrows);
    append_rows(stage / "trajectory.csv", {"condition", "boundary", "x_mm", "y_mm", "uncertainty_mm"}, trows);
    std::string readme = fs::exists(stage / "README.md") ? slurp(stage / "README.md") : std::string();
    if (!readme.empty() && readme.back() != '\n') readme += '\n';
    readme += fmt::format("\n## Digitised data (chutelab import-digitised)\n\nSource: {}\nMapping: {}\nInputs: {}\n\n",
                          imp.source.empty() ? "not stated in the mapping" : imp.source, o.mapping,
                          fmt::join(o.inputs, ", "));
    for (const auto& s : imp.summary) readme += "- " + s + "\n";
    write_text(stage / "README.md", readme);
    try {
      validation::read_dataset(stage, validation::MeasurementsRequired::no);
    } catch (const InputError& e) {
      std::string file = e.file();
      if (file.rfind(stage.string(), 0) == 0) file = abs_out.string() + file.substr(stage.string().size());
      throw InputError(file, e.line(), e.field(), e.problem() + " (in the imported dataset; nothing written)");
    }
    if (fs::exists(abs_out)) fs::remove(abs_out);  // an empty folder
    fs::rename(stage, abs_out);
    unregister_temporary(stage);
  } catch (...) {
    fs::remove_all(stage, ec);
    unregister_temporary(stage);
    throw;
  }
  for (const auto& n : imp.unmapped)
    std::cerr << fmt::format("warning: curve '{}' is not in the mapping and was not imported\n", n);
  for (const auto& s : imp.summary) std::cout << s << "\n";
  std::cout << fmt::format("dataset: {} ({} measurements, {} trajectory points imported)\n", o.out,
                           imp.measurements.size(), imp.trajectory.size());
  return kExitOk;
}

}  // namespace

void add_import_digitised(CLI::App& app, Action& action) {
  auto o = std::make_shared<ImportCli>();
  auto* cmd = app.add_subcommand(
      "import-digitised",
      "Turn curves digitised from figures (WebPlotDigitizer CSV export or project JSON) into trajectory.csv "
      "and measurements.csv rows: writes a new dataset folder (the source dataset plus the imported rows), "
      "checked by the dataset reader.");
  cmd->add_option("--dataset", o->dataset, "dataset whose setup.toml and conditions.csv the curves belong to")
      ->required();
  cmd->add_option("--mapping", o->mapping, "TOML file: which curve is which condition and boundary or quantity, "
                                           "axis units, digitising uncertainty (README, import-digitised)")
      ->required();
  cmd->add_option("--input", o->inputs, "WebPlotDigitizer CSV export or project .json (repeatable)")->required();
  cmd->add_option("--out", o->out, "new dataset folder (must not exist, or be empty)")->required();
  cmd->callback([o, &action] { action = [o] { return run_import(*o); }; });
}

}  // namespace chutelab::app
