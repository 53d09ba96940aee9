#pragma once
// The one way a command writes its --out folder. Everything is written to a staging folder beside
// --out first; commit() then moves each entry into --out by rename, after checking that every move
// can succeed, keeping what it replaces until the last move succeeded. So a failure at any point
// (bad input found late, a folder where a file must go, a full disk, Ctrl-C) leaves --out exactly as
// it was, and no staging file behind. Files of --out that the command does not write are untouched.
//
// Under mpirun only rank 0 stages and commits; the other ranks make the same checks (so all fail
// alike) but write nothing, and their staging() folder does not exist.
//
// No output may land on a file the command reads: the constructor takes the inputs and throws
// InputError when --out is an input folder or an output path resolves to an input file.
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace chutelab {

class OutputFolder {
 public:
  // `out` is --out; `inputs` are the files and folders the command reads (a folder: --out may not
  // be it, nor hold it in a sub-folder the command replaces). Throws InputError for an unusable --out.
  OutputFolder(const std::filesystem::path& out, std::vector<std::filesystem::path> inputs = {},
               std::string_view flag = "--out");
  ~OutputFolder();  // removes the staging folder unless committed
  OutputFolder(const OutputFolder&) = delete;
  OutputFolder& operator=(const OutputFolder&) = delete;

  // Where entries are staged; sub-folders (e.g. dem/, vtk/) may be written here directly.
  const std::filesystem::path& staging() const { return staging_; }
  const std::filesystem::path& out() const { return out_; }
  // Writes one file (name relative to --out) into the staging folder.
  void write(const std::string& name, std::string_view content);
  // Whether entry `name` of --out (a file, or a folder when is_dir) can be replaced: throws the
  // InputError commit() would, so that a command can refuse before its long runs; true when it exists.
  bool check_entry(const std::string& name, bool is_dir) const;
  // Moves every staged entry into --out, all or none. Throws InputError naming the entry that
  // cannot be placed (then --out is as it was).
  void commit();

 private:
  void check_not_input(const std::filesystem::path& dest, bool is_dir) const;
  std::filesystem::path out_, staging_;
  std::vector<std::filesystem::path> inputs_;  // weakly canonical
  std::string flag_;
  bool committed_ = false;
  bool writer_ = true;  // rank 0 (or no MPI)
};

// The same path test used by OutputFolder, for commands that must refuse before doing work:
// weakly canonical, symlinks resolved; a symlink loop or unreadable path is an InputError naming it.
std::filesystem::path resolved_path(const std::filesystem::path& p, std::string_view field);

// Temporary paths removed when SIGINT or SIGTERM arrives (install_interrupt_cleanup()).
void register_temporary(const std::filesystem::path& p);
void unregister_temporary(const std::filesystem::path& p);
// Blocks SIGINT/SIGTERM in every thread (call before any thread starts) and handles them on a thread
// of their own: removes the registered temporaries, says so on stderr, exits 130 (SIGINT) or 143.
void install_interrupt_cleanup();
// The command has said in its one line why it ends: a signal from now on still removes the
// temporaries and exits, but adds no second line. (Under mpirun, the launcher kills the ranks still
// finishing once one rank has exited with the same error.)
void quiet_interrupts();

}  // namespace chutelab
