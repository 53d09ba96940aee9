#include "api/import_digitised.h"

#include <algorithm>
#include <fmt/format.h>
#include <fstream>
#include <map>
#include <sstream>

#include "api/files.h"
#include "core/csv_field.h"
#include "core/input_error.h"
#include "core/output_folder.h"
#include "validation/dataset.h"
#include "validation/digitised.h"
#include "validation/output_files.h"

namespace chutelab::api {
namespace {
namespace fs = std::filesystem;

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::vector<std::string> header_of(const std::string& text) {
  std::vector<std::string> cols;
  std::string line = text.substr(0, text.find('\n'));
  if (!line.empty() && line.back() == '\r') line.pop_back();
  if (line.rfind("\xEF\xBB\xBF", 0) == 0) line.erase(0, 3);  // a spreadsheet's byte-order mark
  std::stringstream ss(line);
  for (std::string c; std::getline(ss, c, ',');) {
    const auto b = c.find_first_not_of(" \t"), e = c.find_last_not_of(" \t");
    cols.push_back(b == std::string::npos ? std::string() : c.substr(b, e - b + 1));
  }
  return cols;
}

// Where each appended row came from: (file name, line in the new file) -> the digitised point.
using Origins = std::map<std::pair<std::string, long>, validation::SourceLine>;

// Appends rows to a dataset CSV (created with `columns` when absent), in the existing file's
// column order; columns the rows do not have stay empty. Text through the one CSV writer
// (core/csv_field.h); numbers were written by it already.
std::string append_rows(std::string text, const std::string& file_name, const std::vector<std::string>& columns,
                        const std::vector<std::vector<std::string>>& rows,
                        const std::vector<validation::SourceLine>& where, Origins& origins) {
  if (rows.empty()) return text;
  if (text.empty()) text = fmt::format("{}\n", fmt::join(columns, ","));
  if (text.back() != '\n') text += '\n';
  const auto header = header_of(text);
  long line = static_cast<long>(std::count(text.begin(), text.end(), '\n'));
  for (std::size_t k = 0; k < rows.size(); ++k) {
    std::vector<std::string> cells(header.size());
    for (std::size_t i = 0; i < header.size(); ++i)
      for (std::size_t j = 0; j < columns.size(); ++j)
        if (header[i] == columns[j]) cells[i] = rows[k][j];
    text += fmt::format("{}\n", fmt::join(cells, ","));
    origins[{file_name, ++line}] = where[k];
  }
  return text;
}

}  // namespace

ImportDigitisedResult import_digitised(const ImportDigitisedOptions& o) {
  const fs::path src(o.dataset), out_dir(o.out);
  const auto d = validation::read_dataset(src, validation::MeasurementsRequired::no);
  std::vector<validation::DigitisedCurve> curves;
  for (const auto& in : o.inputs) {
    auto c = validation::read_digitised(in);
    curves.insert(curves.end(), std::make_move_iterator(c.begin()), std::make_move_iterator(c.end()));
  }
  const auto imp = validation::import_digitised(d, o.mapping, curves);

  // The source is copied into the new folder, so the new folder cannot be (or lie inside) it.
  const fs::path csrc = fs::weakly_canonical(src), cdst = fs::weakly_canonical(out_dir);
  const auto [mismatch, rest] = std::mismatch(csrc.begin(), csrc.end(), cdst.begin(), cdst.end());
  if (mismatch == csrc.end())
    throw InputError(o.out.string(), 0, "out", "is or lies inside the source dataset; the import writes a new dataset folder");
  if (fs::exists(out_dir) && !(fs::is_directory(out_dir) && fs::is_empty(out_dir)))
    throw InputError(o.out.string(), 0, "out", "exists and is not an empty folder; give a new folder");

  // The new dataset is put together in the one staging folder of every command (core/output_folder.h:
  // removed on any failure or signal, swept after a SIGKILL) and read back by the strict reader
  // before it becomes OUT.
  auto inputs = dataset_files(src);
  inputs.push_back(o.mapping);
  inputs.insert(inputs.end(), o.inputs.begin(), o.inputs.end());
  OutputFolder out(out_dir, inputs, "import-digitised");
  for (const auto& e : fs::directory_iterator(src)) {
    const std::string n = e.path().filename().string();
    // The source's record of what chutelab wrote there, or a run's staging, is not part of the dataset.
    if (n == OutputManifest::kFileName || n.find(".partial-") != std::string::npos) continue;
    fs::copy(e.path(), out.staged_path(n), fs::copy_options::recursive);
  }
  std::vector<std::vector<std::string>> mrows, trows;
  std::vector<validation::SourceLine> mwhere, twhere;
  for (const auto& m : imp.measurements) {
    const double s = info(m.quantity).to_boundary;
    mrows.push_back({csv_field(m.condition), std::string(name(m.quantity)), csv_number(m.value * s),
                     m.uncertainty ? csv_number(*m.uncertainty * s) : ""});
    mwhere.push_back(m.where);
  }
  for (const auto& p : imp.trajectory) {
    trows.push_back({csv_field(p.condition), std::string(name(p.boundary)), csv_number(p.x * 1e3), csv_number(p.y * 1e3),
                     p.uncertainty ? csv_number(*p.uncertainty * 1e3) : ""});
    twhere.push_back(p.where);
  }
  Origins origins;
  auto existing = [&](const char* f) {
    const fs::path p = src / f;
    return fs::exists(p) ? slurp(p) : std::string();
  };
  // A file the source has not and no row goes into stays absent (an empty one would not read).
  if (const auto m = append_rows(existing("measurements.csv"), "measurements.csv",
                                 {"condition", "quantity", "value", "uncertainty"}, mrows, mwhere, origins);
      !m.empty())
    out.write("measurements.csv", m);
  if (const auto t = append_rows(existing("trajectory.csv"), "trajectory.csv",
                                 {"condition", "boundary", "x_mm", "y_mm", "uncertainty_mm"}, trows, twhere, origins);
      !t.empty())
    out.write("trajectory.csv", t);
  std::vector<std::string> given;
  for (const auto& in : o.inputs) given.push_back(in.string());
  std::string readme = existing("README.md");
  if (!readme.empty() && readme.back() != '\n') readme += '\n';
  readme += fmt::format("\n## Digitised data (chutelab import-digitised)\n\nSource: {}\nMapping: {}\nInputs: {}\n\n",
                        imp.source.empty() ? "not stated in the mapping" : imp.source, o.mapping.string(),
                        fmt::join(given, ", "));
  for (const auto& s : imp.summary) readme += "- " + s + "\n";
  out.write("README.md", readme);
  try {
    validation::read_dataset(out.staging(), validation::MeasurementsRequired::no);
  } catch (const InputError& e) {
    // Said against the user's file: an appended row is its digitised point (file and line of the
    // input), anything else a file copied unchanged from the source dataset.
    const fs::path f(e.file());
    const std::string rel = f.parent_path() == out.staging() ? f.filename().string() : std::string();
    if (auto it = origins.find({rel, e.line()}); !rel.empty() && it != origins.end())
      throw InputError(it->second.file, it->second.line, e.field(),
                       fmt::format("{} (the row it became, {} line {}, would not read back; nothing written)",
                                   e.problem(), rel, e.line()));
    if (!rel.empty() && fs::exists(src / rel))
      throw InputError((src / rel).string(), e.line(), e.field(), e.problem() + " (with the imported rows; nothing written)");
    throw;
  }
  out.commit();
  return {imp.summary, imp.unmapped, imp.measurements.size(), imp.trajectory.size()};
}

}  // namespace chutelab::api
