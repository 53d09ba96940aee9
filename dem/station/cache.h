#pragma once
// A finished DEM run stored as a small text file, keyed by everything that affects its result, so
// that a repeated `validate` is instant. The key is a canonical text (station fields, resolved
// settings, STL contents, effect inputs, kStationModelVersion); the file name is its 64-bit
// FNV-1a hash and the file repeats the whole key, which is compared on loading (a hash collision
// or a stale file is a miss, never a wrong answer).
//
// An entry is trusted only whole: format 6 ends with a check sum of everything before it, every
// line is parsed strictly (each number in full, finite or NaN only where the writer writes NaN, in
// its range, every required line once), and only a regular file is opened. A file that fails any
// of this is refused, with the line and field that failed, never read as numbers; the caller runs
// again (or, told never to run, stops naming the file). Format 5 (an end line, no check sum; the
// recorded runs of tests/peer/dem-cache) is still read under the same strict parse.
//
// Where: $CHUTELAB_DEM_CACHE if set, else $XDG_CACHE_HOME/chutelab/dem, else ~/.cache/chutelab/dem.
// A per-user cache outlives output folders: validating into a new --out still finds the runs.
#include <optional>
#include <string>
#include <string_view>

#include "dem/station/run.h"

namespace chutelab::dem::station {

// Why a text or a cache entry was refused: its line (1 = the first, 0 = the file as a whole), the
// line's tag and the problem.
struct TextProblem {
  long line = 0;
  std::string field;
  std::string problem;
};

std::string to_text(const StationResult& r);
// No result for a text with any line that is not whole and in range; `why`, when given, says which.
std::optional<StationResult> from_text(const std::string& text, TextProblem* why = nullptr);

// What a look-up found: a checked result, nothing (no file, or another key's), or a file refused.
struct CacheEntry {
  std::string file;
  std::optional<StationResult> result;
  // A file that is there but cannot be used: damaged, cut short, of another format, not a regular
  // file, unreadable. Unset for a missing file or another key's entry (a stale or colliding one).
  std::optional<TextProblem> refused;
  std::string said() const;  // "FILE:LINE: field: problem"
};

// Whether an entry was written, and when not, why (the file system's words).
struct CacheWrite {
  bool written = false;
  std::string problem;
  explicit operator bool() const { return written; }
};

std::uint64_t fnv1a64(std::string_view s);

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
  CacheEntry lookup(const std::string& key) const;
  std::optional<StationResult> load(const std::string& key) const { return lookup(key).result; }
  // Writes atomically (temporary file flushed to the disk, then rename). A failure to write is not
  // an error of the run, but the caller says so (the run is not cached).
  CacheWrite store(const std::string& key, const StationResult& r) const;

 private:
  // Removes this host's temporaries whose process is gone (killed by SIGKILL while it wrote).
  void sweep_dead_temporaries(const std::string& host) const;
  std::string dir_;
};

}  // namespace chutelab::dem::station
