#pragma once
// synthesize: a dataset with known hidden physics, for testing the diagnosis. The analytical
// models' predictions plus hidden effects plus Gaussian noise (validation/synthesize.h).
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "api/output_plan.h"
#include "validation/dataset.h"
#include "validation/output_files.h"

namespace chutelab::api {

// Errors name the keys "dataset", "effect", "input", "seed", "noise_scale", "noise_factor",
// "outliers".
struct SynthesizeOptions {
  std::filesystem::path dataset;          // rig and conditions to use; "" = default_dataset
  std::filesystem::path default_dataset;
  std::vector<std::string> effects;       // hidden effects NAME=VALUE
  std::vector<std::string> inputs;        // wrong records NAME=VALUE (truth minus record)
  std::uint64_t seed = 1;
  double noise_scale = 1.0;               // multiplies every uncertainty
  double noise_factor = 1.0;              // the real scatter in stated uncertainties
  int outliers = 0;                       // gross reading errors among the measurements
  bool allow_out_of_range = false;        // strengths outside their physical range (test data only)
  PrepareOutput prepare_output;           // may be empty
};

// The options alone, before any file is read. Throws InputError naming the key.
void check(const SynthesizeOptions& o);

struct SynthesizeResult {
  validation::Dataset source;     // the dataset the rig and conditions came from
  // The synthetic dataset's files (setup.toml, conditions.csv, measurements.csv, README.md, ...):
  // write them with write_dataset(out, files, source.dir, "synthesize") (api/files.h), which refuses
  // the source, or take them as a dataset with synthesized_dataset.
  std::vector<validation::OutputFile> files;
};

SynthesizeResult synthesize(const SynthesizeOptions& o);
// The same from a dataset already read (o.dataset is not used).
SynthesizeResult synthesize(validation::Dataset source, const SynthesizeOptions& o);

// The synthetic dataset as a dataset: written to the folder `out` (as write_dataset does) and read
// back from there, so that it is the folder's; with `out` empty, read from its files in memory (it
// then has no folder).
validation::Dataset synthesized_dataset(const SynthesizeResult& r, const std::filesystem::path& out);

}  // namespace chutelab::api
