// write_outputs apart from the CSV formatting, so that a build without the file system's output
// folder (the designer's WebAssembly page formats CSV but writes nothing) links without it.
#include "core/output_folder.h"
#include "validation/output_files.h"

namespace chutelab::validation {

void write_outputs(const std::filesystem::path& dir, const std::vector<OutputFile>& files,
                   const std::vector<std::filesystem::path>& inputs, std::string_view command) {
  OutputFolder out(dir, inputs, command);
  for (const auto& [name, content] : files) out.write(name, content);
  out.commit();
}

}  // namespace chutelab::validation
