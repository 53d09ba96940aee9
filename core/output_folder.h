#pragma once
// The one way a command writes its --out folder. Everything is written to a staging folder first
// (inside --out when it exists, so on its file system; beside it otherwise); commit() then moves each
// file into --out by rename, after checking that every move can succeed, keeping what it replaces
// until the last move succeeded. So a failure at any point (bad input found late, a folder where a
// file must go, a full disk, Ctrl-C) leaves --out exactly as it was, and no staging file behind.
//
// Files the user named outside --out (--junit FILE; estimate's --svg, --dxf and --points, which have
// no --out) are staged with the rest and placed by the same commit(): a command that fails writes
// none of its outputs, whichever failed. A move that crosses file systems (--out or a named file on
// another disk, a mount point inside --out) is a copy beside the destination renamed over it, so no
// destination is ever seen half-written.
//
// A command replaces or removes only what chutelab wrote: the folder keeps the record
// (core/output_manifest.h, OUT/.chutelab-manifest) of every file chutelab wrote there and which
// command wrote it. A file in the way that the record does not list, or lists with other content
// (the user's own, or one they edited), is refused with exit 2, never overwritten; what an earlier
// run of the same command wrote and this run does not write is removed (a line on stderr names it),
// so --out never holds a mix of two runs of one command; what other commands wrote stays
// (`diagnose` into the folder of a `validate` leaves its report).
//
// Under mpirun only rank 0 stages and commits; the other ranks make the same checks (so all fail
// alike) but write nothing, and their staging() folder does not exist.
//
// No output may land on a file the command reads: the constructor takes the inputs and throws
// InputError when --out is an input folder or an output path resolves to an input file.
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/output_manifest.h"
#include "core/temporaries.h"

namespace chutelab {

class OutputFolder {
 public:
  // `out` is --out; `inputs` are the files and folders the command reads (a folder: --out may not
  // be it); `command` names the writer in the folder's record (validate, diagnose, synthesize, ...).
  // Throws InputError for an unusable --out.
  OutputFolder(const std::filesystem::path& out, std::vector<std::filesystem::path> inputs, std::string_view command,
               std::string_view flag = "out");
  // Without an output folder: only files the user names (write_file()).
  explicit OutputFolder(std::vector<std::filesystem::path> inputs);
  ~OutputFolder();  // removes the staging folder unless committed
  OutputFolder(const OutputFolder&) = delete;
  OutputFolder& operator=(const OutputFolder&) = delete;

  // Where entries are staged; sub-folders (e.g. dem/, vtk/) may be written here directly.
  const std::filesystem::path& staging() const { return staging_; }
  const std::filesystem::path& out() const { return out_; }
  // Writes one file (name relative to --out) into the staging folder.
  void write(const std::string& name, std::string_view content);
  // Stages `content` for `file`, a file the user named with `flag` (--junit, --svg, ...), placed by
  // commit() with everything else; it replaces what is there, keeping no record. Throws InputError
  // naming `flag` when it is a folder, a file this command reads, or the file of another flag.
  void write_file(const std::filesystem::path& file, std::string_view flag, std::string_view content);
  // Whether entry `name` of --out (a file, or a folder when is_dir) can be written: throws the
  // InputError commit() would, so that a command can refuse before its long runs; true when it exists.
  bool check_entry(const std::string& name, bool is_dir) const;
  // Names that readers of the folder take as part of what this command writes (a dataset's files):
  // one this run does not write may be there only when an earlier run of this command wrote it
  // (then it is removed); anything else there is refused, as it would be read as part of the output.
  void read_together(std::initializer_list<std::string_view> names);
  // Other commands whose earlier files in --out this command takes for its own (removes when it does
  // not write them): the writers of one kind of folder (a dataset's).
  void takes_over(std::initializer_list<std::string_view> commands);
  // Moves every staged file into --out, all or none, and updates the folder's record. Throws
  // InputError naming the entry that cannot be placed (then --out is as it was).
  void commit();
  // staging() / name, after checking that name is a relative path of plain components (no "..",
  // no root): a name from the data can never make a command write outside --out.
  std::filesystem::path staged_path(const std::string& name) const;

 private:
  struct Named {
    std::filesystem::path dest, resolved, staged;
    std::string flag;
  };
  void check_not_input(const std::filesystem::path& dest, bool is_dir) const;
  const OutputManifest& manifest() const;
  void open_staging(const std::filesystem::path& dir, bool inside, const std::string& flag);
  // commit()'s steps (output_folder.cpp): what is to be moved, checked before anything moves, then
  // placed all or none, then tidied and said.
  struct CommitPlan;
  std::vector<std::string> staged_files() const;
  void plan_staged_files(CommitPlan& plan) const;
  void plan_earlier_files(CommitPlan& plan) const;
  void check_datasets_whole(const CommitPlan& plan) const;
  void plan_named_files(CommitPlan& plan) const;
  void place(CommitPlan& plan);
  void remove_stale_folders(CommitPlan& plan);
  void say_removed_and_kept(const CommitPlan& plan) const;
  std::filesystem::path out_, staging_;
  bool folder_ = true;  // false: no --out, only named files
  std::vector<Named> named_;
  std::vector<std::filesystem::path> inputs_;  // weakly canonical
  std::vector<std::string> together_, taken_;
  std::string command_, flag_;
  mutable std::optional<OutputManifest> manifest_;  // as read for check_entry(); commit() reads it again
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

}  // namespace chutelab
