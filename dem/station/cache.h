#pragma once
// A finished DEM run stored as a small text file, keyed by everything that affects its result, so
// that a repeated `validate` is instant. The key is a canonical text (station fields, resolved
// settings, STL contents, effect inputs, kStationModelVersion); the file name is its 64-bit
// FNV-1a hash and the file repeats the whole key, which is compared on loading (a hash collision
// or a stale file is a miss, never a wrong answer).
//
// Where: $CHUTELAB_DEM_CACHE if set, else $XDG_CACHE_HOME/chutelab/dem, else ~/.cache/chutelab/dem.
// A per-user cache outlives output folders: validating into a new --out still finds the runs.
#include <optional>
#include <string>

#include "dem/station/run.h"

namespace chutelab::dem::station {

std::string to_text(const StationResult& r);
std::optional<StationResult> from_text(const std::string& text);

std::uint64_t fnv1a64(const std::string& s);

// What added effects change in a run (ExternalInputs), as canonical key text: one line per input
// that is set, none for an input left at its neutral value, so a run without effects keeps the key
// it had before an input existed.
std::string canonical(const ExternalInputs& fx);

class ResultCache {
 public:
  explicit ResultCache(std::string dir);
  static std::string default_dir();
  const std::string& dir() const { return dir_; }
  std::string path_for(const std::string& key) const;
  std::optional<StationResult> load(const std::string& key) const;
  // Writes atomically (temporary file, then rename); a failure to write is not an error of the run.
  bool store(const std::string& key, const StationResult& r) const;

 private:
  // Removes this host's temporaries whose process is gone (killed by SIGKILL while it wrote).
  void sweep_dead_temporaries(const std::string& host) const;
  std::string dir_;
};

}  // namespace chutelab::dem::station
