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
               std::string_view flag = "out");
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
  // The entries (files or folders) this command may write in --out: those it does not write this
  // time are an earlier run's and are removed by commit() (all or none, like the rest; never an
  // input; a line on stderr names them), so --out never holds a mix of two runs' outputs.
  void owns(std::initializer_list<std::string_view> names);
  // staging() / name, after checking that name is a relative path of plain components (no "..",
  // no root): a name from the data can never make a command write outside --out.
  std::filesystem::path staged_path(const std::string& name) const;

 private:
  void check_not_input(const std::filesystem::path& dest, bool is_dir) const;
  std::filesystem::path out_, staging_;
  std::vector<std::filesystem::path> inputs_;  // weakly canonical
  std::vector<std::string> owned_;
  std::string flag_;
  bool committed_ = false;
  bool writer_ = true;  // rank 0 (or no MPI)
  [[maybe_unused]] int lock_fd_ = -1;  // held while the staging folder is in use (sweep_dead_staging())
};

// Removes the staging folders beside `out` (and inside it) that a process left when it was killed
// by a signal it could not catch (SIGKILL), crashed or lost power: those whose process id is gone and
// whose lock nobody holds. Every OutputFolder does it before it stages.
void sweep_dead_staging(const std::filesystem::path& out);

// The same path test used by OutputFolder, for commands that must refuse before doing work:
// weakly canonical, symlinks resolved; a symlink loop or unreadable path is an InputError naming it.
std::filesystem::path resolved_path(const std::filesystem::path& p, std::string_view field);

// Temporary paths removed when a signal ends the process (install_interrupt_cleanup()).
void register_temporary(const std::filesystem::path& p);
void unregister_temporary(const std::filesystem::path& p);
// Catches every signal that would end the process and can be caught (SIGHUP, SIGINT, SIGQUIT,
// SIGTERM, SIGALRM, SIGXCPU, SIGPIPE, ...; call before any thread starts) and handles it on a thread
// of its own: removes the registered temporaries, says so on stderr, exits 128 + the signal's number
// (130 for SIGINT, 143 for SIGTERM). SIGKILL's leftovers are swept by the next run (above).
void install_interrupt_cleanup();
// The command has said in its one line why it ends: a signal from now on still removes the
// temporaries and exits, but adds no second line. (Under mpirun, the launcher kills the ranks still
// finishing once one rank has exited with the same error.)
void quiet_interrupts();

}  // namespace chutelab
