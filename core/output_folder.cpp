#include "core/output_folder.h"

#include <unistd.h>
#ifndef __EMSCRIPTEN__
#include <fcntl.h>
#include <sys/file.h>
#endif

#include <cerrno>

#include <csignal>
#include <fmt/format.h>
#include <fstream>
#include <iostream>
#include <algorithm>
#include <map>
#include <set>
#include <mutex>

#include "core/input_error.h"
#include "core/message.h"
#ifndef __EMSCRIPTEN__
#include "core/campaign.h"
#endif

namespace chutelab {
namespace fs = std::filesystem;

namespace {

bool inside(const fs::path& p, const fs::path& dir) {
  auto pi = p.begin();
  for (auto di = dir.begin(); di != dir.end(); ++di, ++pi) {
    if (di->empty()) continue;  // trailing separator
    if (pi == p.end() || *pi != *di) return false;
  }
  return true;
}

// --out as given, without a trailing separator, so that its name and parent are what they look like.
fs::path tidy(const fs::path& p) {
  fs::path t = p.lexically_normal();
  if (t.filename().empty() && t.has_parent_path()) t = t.parent_path();
  return t;
}

// Under mpirun every rank runs the command with the same inputs and reaches the same writes; rank 0
// alone touches the file system (core/campaign.h). The others check the same things, so that every
// rank fails alike on a bad --out, and stage nothing.
bool writes_files() {
#ifdef __EMSCRIPTEN__
  return true;
#else
  return campaign::output_rank();
#endif
}

}  // namespace

fs::path resolved_path(const fs::path& p, std::string_view field) {
  std::error_code ec;
  fs::path r = fs::weakly_canonical(fs::absolute(p, ec), ec);
  if (ec) throw InputError(p.string(), 0, std::string(field), fmt::format("cannot resolve the path: {}", ec.message()));
  return r;
}

namespace {
constexpr const char* kLockName = ".chutelab-lock";
#ifndef __EMSCRIPTEN__

// "123" -> 123; anything else -> -1.
long pid_of(std::string_view s) {
  if (s.empty() || s.size() > 10) return -1;
  long v = 0;
  for (char c : s) {
    if (c < '0' || c > '9') return -1;
    v = v * 10 + (c - '0');
  }
  return v;
}

// A staging folder whose process is gone: its id names no process here, and no process (on this or
// another machine sharing the folder) holds its lock.
bool owner_gone(const fs::path& staging, long pid) {
  if (pid <= 0 || pid == static_cast<long>(::getpid())) return false;
  if (::kill(static_cast<pid_t>(pid), 0) == 0 || errno != ESRCH) return false;
  const int fd = ::open((staging / kLockName).c_str(), O_RDWR | O_CLOEXEC);
  if (fd < 0) return true;  // never locked (a run of an older chutelab, or killed before locking)
  const bool free = ::flock(fd, LOCK_EX | LOCK_NB) == 0;
  ::close(fd);
  return free;
}
#endif
}  // namespace

void sweep_dead_staging(const fs::path& out) {
#ifndef __EMSCRIPTEN__
  const fs::path t = tidy(out);
  fs::path parent = t.parent_path();
  if (parent.empty()) parent = ".";
  const std::string beside = fmt::format(".{}.partial-", t.filename().string());
  auto sweep = [](const fs::path& dir, const std::string& prefix) {
    std::error_code ec;
    std::vector<fs::path> dead;
    for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
      const std::string n = it->path().filename().string();
      if (n.rfind(prefix, 0) != 0) continue;
      if (owner_gone(it->path(), pid_of(std::string_view(n).substr(prefix.size())))) dead.push_back(it->path());
    }
    for (const auto& d : dead) fs::remove_all(d, ec);
  };
  sweep(parent, beside);
  std::error_code ec;
  if (fs::is_directory(t, ec)) sweep(t, ".chutelab.partial-");
#else
  (void)out;
#endif
}

OutputFolder::OutputFolder(const fs::path& out, std::vector<fs::path> inputs, std::string_view command,
                           std::string_view flag)
    : out_(tidy(out)), command_(command), flag_(flag) {
  if (out.empty()) throw InputError("", 0, flag_, "no output folder given");
  std::error_code ec;
  const auto st = fs::status(out_, ec);
  if (ec && ec != std::errc::no_such_file_or_directory)
    throw InputError(out_.string(), 0, flag_, fmt::format("cannot use this folder: {}", ec.message()));
  if (fs::exists(st) && !fs::is_directory(st)) throw InputError(out_.string(), 0, flag_, "exists and is not a folder");
  const fs::path out_resolved = resolved_path(out_, flag_);
  for (const auto& i : inputs) {
    inputs_.push_back(resolved_path(i, flag_));
    if (inputs_.back() == out_resolved)
      throw InputError(out_.string(), 0, flag_,
                       fmt::format("is the input folder {}; its files would be overwritten, choose another folder",
                                   i.string()));
  }
  writer_ = writes_files();
  // Inside an existing --out, so that every rename stays on its file system (--out may be a mount
  // point, or a link to another disk); beside a new one, on the file system it will be made on.
  if (fs::is_directory(st)) {
    open_staging(out_, true, flag_);
  } else {
    fs::path parent = out_.parent_path();
    if (parent.empty()) parent = ".";
    if (writer_) fs::create_directories(parent, ec);
    if (ec) throw InputError(parent.string(), 0, flag_, fmt::format("cannot create the folder: {}", ec.message()));
    open_staging(parent, false, flag_);
  }
}

OutputFolder::OutputFolder(std::vector<fs::path> inputs) : folder_(false), flag_("out") {
  for (const auto& i : inputs) inputs_.push_back(resolved_path(i, flag_));
  writer_ = writes_files();
}

// The staging folder in `dir`: dir/.chutelab.partial-PID inside --out (or, with no --out, in the
// folder of the first file named), dir/.OUT.partial-PID beside a new --out.
void OutputFolder::open_staging(const fs::path& dir, bool in_dir, const std::string& flag) {
  const auto pid = static_cast<long>(::getpid());
  staging_ = in_dir ? dir / fmt::format(".chutelab.partial-{}", pid)
                    : dir / fmt::format(".{}.partial-{}", out_.filename().string(), pid);
  if (!writer_) return;
  std::error_code ec;
  sweep_dead_staging(in_dir ? dir : out_);
  fs::remove_all(staging_, ec);  // left by a killed run of the same process id
  register_temporary(staging_);
  fs::create_directory(staging_, ec);
  if (ec) {
    unregister_temporary(staging_);
    throw InputError(dir.string(), 0, flag, fmt::format("cannot write in this folder: {}", ec.message()));
  }
#ifndef __EMSCRIPTEN__
  // Held while this process lives (the kernel releases it however the process ends): a later run
  // sweeps this folder only when no process holds it (sweep_dead_staging()).
  lock_fd_ = ::open((staging_ / kLockName).c_str(), O_CREAT | O_RDWR | O_CLOEXEC, 0600);
  if (lock_fd_ >= 0) [[maybe_unused]] const int locked = ::flock(lock_fd_, LOCK_EX | LOCK_NB);
#endif
}

OutputFolder::~OutputFolder() {
  if (!writer_ || staging_.empty()) return;
  std::error_code ec;
  if (!committed_) fs::remove_all(staging_, ec);
  unregister_temporary(staging_);
#ifndef __EMSCRIPTEN__
  if (lock_fd_ >= 0) ::close(lock_fd_);
#endif
}

void OutputFolder::read_together(std::initializer_list<std::string_view> names) {
  for (auto n : names) together_.emplace_back(n);
}

void OutputFolder::takes_over(std::initializer_list<std::string_view> commands) {
  for (auto c : commands) taken_.emplace_back(c);
}

fs::path OutputFolder::staged_path(const std::string& name) const {
  // Every file a command writes lies under --out: a name is a relative path of plain components.
  const fs::path p(name);
  bool plain = !name.empty() && p.is_relative() && !p.has_root_name();
  for (const auto& c : p) plain = plain && !c.empty() && c != "." && c != "..";
  if (!plain)
    throw InputError(name, 0, flag_, "is not a plain file name inside the output folder (internal error: a name from the data was used as a path)");
  return staging_ / p;
}

void OutputFolder::check_not_input(const fs::path& dest, bool is_dir) const {
  const fs::path r = resolved_path(dest, flag_);
  for (const auto& i : inputs_) {
    if (r == i)
      throw InputError(dest.string(), 0, flag_, "is a file this command reads; choose another output folder");
    if (is_dir && inside(i, r))
      throw InputError(dest.string(), 0, flag_,
                       fmt::format("would replace a folder holding the input {}; choose another output folder",
                                   i.string()));
  }
}

const OutputManifest& OutputFolder::manifest() const {
  if (!manifest_) manifest_ = OutputManifest::read(out_);
  return *manifest_;
}

namespace {

enum class Kind { none, folder, file, other };  // other: a link, FIFO, device, ... (never followed)

Kind kind_of(const fs::path& p) {
  std::error_code ec;
  const auto st = fs::symlink_status(p, ec);
  if (ec || !fs::exists(st)) return Kind::none;
  if (fs::is_directory(st)) return Kind::folder;
  if (fs::is_regular_file(st)) return Kind::file;
  return Kind::other;
}

// Why chutelab may not replace `dest` (relative path `rel` of --out) with a file: empty when it may
// (absent, or a file chutelab wrote there and nobody changed since).
std::string not_ours(const fs::path& dest, const std::string& rel, const OutputManifest& m) {
  const Kind k = kind_of(dest);
  if (k == Kind::none) return {};
  if (k == Kind::folder) return "is a folder where chutelab writes a file; move it away";
  const auto it = m.records.find(rel);
  if (it == m.records.end() || it->second.folder)
    return fmt::format("chutelab did not write it (no earlier run recorded it in {}); it is left as it is: move it "
                       "away or choose another folder",
                       OutputManifest::kFileName);
  if (!OutputManifest::intact(dest, it->second))
    return "was changed since chutelab wrote it; it is left as it is: move it away or choose another folder";
  return {};
}

// "dem/V3-41/a.csv" -> {"dem", "dem/V3-41"}: the folders a relative path passes through.
std::vector<std::string> parents_of(const std::string& rel) {
  std::vector<std::string> p;
  for (auto at = rel.find('/'); at != std::string::npos; at = rel.find('/', at + 1)) p.push_back(rel.substr(0, at));
  return p;
}

// The folders from the first one missing down to `dir` (none when it exists).
std::vector<fs::path> missing_folders(const fs::path& dir) {
  std::vector<fs::path> m;
  for (fs::path d = dir; !d.empty() && kind_of(d) == Kind::none; d = d.parent_path()) {
    m.insert(m.begin(), d);
    if (d == d.parent_path()) break;
  }
  return m;
}

// A name beside `p` in its own folder (so on its file system): .NAME.what-PID.
fs::path beside(const fs::path& p, const char* what) {
  return p.parent_path() / fmt::format(".{}.{}-{}", p.filename().string(), what, static_cast<long>(::getpid()));
}

// Moves the file `from` to `to` (replacing it): by rename; across file systems (--out, or a file
// the user named, on another disk or under a mount point), by a copy beside `to` renamed over it, so
// that `to` is never seen half-written. (A process killed during the copy leaves that copy.)
std::error_code move_file(const fs::path& from, const fs::path& to) {
  std::error_code ec;
  fs::rename(from, to, ec);
  if (ec != std::errc::cross_device_link) return ec;
  ec.clear();
  const fs::path tmp = beside(to, "partial");
  fs::copy_file(from, tmp, fs::copy_options::overwrite_existing, ec);
  if (!ec) fs::rename(tmp, to, ec);
  std::error_code e2;
  if (ec) fs::remove(tmp, e2);
  else fs::remove(from, e2);
  return ec;
}

}  // namespace

bool OutputFolder::check_entry(const std::string& name, bool is_dir) const {
  const fs::path dest = out_ / name;
  check_not_input(dest, is_dir);
  const Kind k = kind_of(dest);
  if (k == Kind::none) return false;
  if (is_dir) {
    if (k != Kind::folder) throw InputError(dest.string(), 0, flag_, "is a file where chutelab writes a folder; move it away");
    return true;
  }
  if (const std::string why = not_ours(dest, name, manifest()); !why.empty())
    throw InputError(dest.string(), 0, flag_, why);
  return true;
}

void OutputFolder::write(const std::string& name, std::string_view content) {
  const fs::path p = staged_path(name);
  check_not_input(out_ / name, false);
  if (!writer_) return;
  std::error_code ec;
  if (p.has_parent_path()) fs::create_directories(p.parent_path(), ec);
  std::ofstream f(p, std::ios::binary | std::ios::trunc);
  f.write(content.data(), static_cast<std::streamsize>(content.size()));
  f.close();
  if (!f) throw InputError((out_ / name).string(), 0, flag_, "cannot write the file (disk full or no permission?)");
}

void OutputFolder::write_file(const fs::path& file, std::string_view flag, std::string_view content) {
  const std::string fl(flag);
  if (file.empty()) throw InputError("", 0, fl, "is empty; give a file name");
  std::error_code ec;
  if (fs::is_directory(file, ec)) throw InputError(file.string(), 0, fl, "is a folder; give a file name");
  const fs::path r = resolved_path(file, fl);
  for (const auto& i : inputs_)
    if (r == i) throw InputError(file.string(), 0, fl, "is an input of this run; choose another file");
  for (const auto& n : named_)
    if (n.resolved == r)
      throw InputError(file.string(), 0, fl, fmt::format("is also the file of {}; give each its own file", n.flag));
  if (staging_.empty()) {  // no --out: staged in the nearest folder of the file that exists
    fs::path dir = fs::absolute(file, ec).parent_path();
    while (dir.has_parent_path() && dir != dir.parent_path() && kind_of(dir) != Kind::folder) dir = dir.parent_path();
    open_staging(dir, true, fl);
  }
  Named n{file, r, staging_ / ".named" / std::to_string(named_.size()), fl};
  if (writer_) {
    fs::create_directories(n.staged.parent_path(), ec);
    std::ofstream f(n.staged, std::ios::binary | std::ios::trunc);
    f.write(content.data(), static_cast<std::streamsize>(content.size()));
    f.close();
    if (!f) throw InputError(file.string(), 0, fl, "cannot write the file (disk full or no permission?)");
  }
  named_.push_back(std::move(n));
}

// commit()'s plan: the staged files, what moves where, what goes aside and what the record forgets.
struct OutputFolder::CommitPlan {
  // A move: the staged file `from` to `dest`, named by `flag` in messages.
  struct Move {
    fs::path from, dest;
    std::string flag;
  };
  std::vector<std::string> files;  // the staged files of --out, by their path relative to it, sorted
  std::set<std::string> staged;
  std::set<std::string> needed_folders;  // every folder a staged file lies in
  OutputManifest manifest;
  fs::path record_path;
  std::vector<Move> moves;
  std::vector<std::pair<fs::path, std::string>> aside;  // files to move aside (replaced or removed), their flag
  std::vector<std::string> removed, kept, dropped, stale_folders;
  std::vector<fs::path> backups_beside;  // backups kept beside their file (another file system)
  std::vector<std::string> made;         // folders of --out this run made, relative to it
};

namespace {

#ifndef __EMSCRIPTEN__
// One commit at a time into one folder: two commands finishing together would each write a record
// without the other's files (which then count as the user's: refused later, never removed).
class FolderLock {
 public:
  // Nothing locked when dir is empty.
  explicit FolderLock(const fs::path& dir)
      : fd_(dir.empty() ? -1 : ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC)) {
    if (fd_ >= 0) [[maybe_unused]] const int locked = ::flock(fd_, LOCK_EX);
  }
  FolderLock(const FolderLock&) = delete;
  FolderLock& operator=(const FolderLock&) = delete;
  ~FolderLock() {
    if (fd_ >= 0) ::close(fd_);
  }

 private:
  int fd_ = -1;
};
#endif

// What commit() did, undone in reverse order when a later step fails.
class Undo {
 public:
  Undo(const fs::path& out, bool created) : out_(out), created_(created) {}
  void moved_aside(const fs::path& from, const fs::path& backup) { done_.push_back({Step::moved_aside, from, backup}); }
  void placed(const fs::path& p) { done_.push_back({Step::placed, p, {}}); }
  void made_folder(const fs::path& p) { done_.push_back({Step::made_folder, p, {}}); }
  // Undoes everything and throws the error of `where`.
  [[noreturn]] void fail(const fs::path& where, const std::string& flag, const std::string& why) {
    roll_back();
    throw InputError(where.string(), 0, flag, fmt::format("cannot write: {}", why));
  }

 private:
  struct Step {
    enum { moved_aside, placed, made_folder } what;
    fs::path a, b;
  };
  void roll_back() {
    std::error_code e2;
    for (auto it = done_.rbegin(); it != done_.rend(); ++it) {
      switch (it->what) {
        case Step::moved_aside: fs::rename(it->b, it->a, e2); break;  // backup -> where it was
        case Step::placed: fs::remove(it->a, e2); break;
        case Step::made_folder: fs::remove(it->a, e2); break;
      }
    }
    if (created_) fs::remove(out_, e2);
  }
  fs::path out_;
  bool created_;
  std::vector<Step> done_;
};

// The record of --out, through a staged file.
std::error_code write_record(const fs::path& staging, const OutputManifest& m, const fs::path& record_path) {
  const fs::path next = staging / ".manifest";
  std::ofstream f(next, std::ios::binary | std::ios::trunc);
  const std::string text = m.text();
  f.write(text.data(), static_cast<std::streamsize>(text.size()));
  f.close();
  if (!f) return std::make_error_code(std::errc::no_space_on_device);
  return move_file(next, record_path);
}

}  // namespace

void OutputFolder::commit() {
  if (!writer_ || staging_.empty()) {  // another rank's, or nothing named
    committed_ = true;
    return;
  }
  CommitPlan plan;
  plan.files = staged_files();
  plan.staged = {plan.files.begin(), plan.files.end()};
  for (const auto& f : plan.files)
    for (auto& p : parents_of(f)) plan.needed_folders.insert(std::move(p));
#ifndef __EMSCRIPTEN__
  std::error_code ec;
  const FolderLock lock_folder(folder_ && fs::is_directory(out_, ec) ? out_ : fs::path());
#endif
  plan.manifest = folder_ ? OutputManifest::read(out_) : OutputManifest{};
  plan.record_path = out_ / OutputManifest::kFileName;
  // Check every file before moving any, so that nothing is half-replaced by a foreseeable problem.
  plan_staged_files(plan);
  plan_earlier_files(plan);
  check_datasets_whole(plan);
  if (folder_ && kind_of(plan.record_path) == Kind::folder)
    throw InputError(plan.record_path.string(), 0, flag_,
                     "is a folder where chutelab keeps the record of what it wrote here; move it away");
  plan_named_files(plan);

  {
    std::lock_guard lock(temporaries_mutex());  // an interrupt waits until every output is whole again
    place(plan);
    committed_ = true;
    std::error_code ignored;
    for (const auto& b : plan.backups_beside) fs::remove(b, ignored);
    remove_stale_folders(plan);
    say_removed_and_kept(plan);
    fs::remove_all(staging_, ignored);
  }
  unregister_temporary(staging_);
}

std::vector<std::string> OutputFolder::staged_files() const {
  std::vector<std::string> files;
  if (folder_) {
    std::error_code ec;
    for (auto it = fs::recursive_directory_iterator(staging_, ec); !ec && it != fs::recursive_directory_iterator();
         it.increment(ec)) {
      const fs::path rel = it->path().lexically_relative(staging_);
      if (it.depth() == 0 && (rel == kLockName || rel == ".replaced" || rel == ".named")) {
        it.disable_recursion_pending();
        continue;
      }
      if (!it->is_directory()) files.push_back(rel.generic_string());
    }
    if (ec) throw InputError(staging_.string(), 0, flag_, fmt::format("cannot list the staged files: {}", ec.message()));
  }
  std::sort(files.begin(), files.end());
  return files;
}

// Each staged file to its place in --out, what is there moved aside.
void OutputFolder::plan_staged_files(CommitPlan& plan) const {
  for (const auto& f : plan.files) {
    const fs::path dest = out_ / f;
    check_not_input(dest, false);
    for (const auto& p : parents_of(f)) {
      const Kind k = kind_of(out_ / p);
      if (k == Kind::none) break;
      if (k != Kind::folder)
        throw InputError((out_ / p).string(), 0, flag_, "is a file where chutelab writes a folder; move it away");
    }
    if (const std::string why = not_ours(dest, f, plan.manifest); !why.empty())
      throw InputError(dest.string(), 0, flag_, why);
    if (kind_of(dest) != Kind::none) plan.aside.emplace_back(dest, flag_);
    plan.moves.push_back({staging_ / f, dest, flag_});
  }
}

// What an earlier run of this command wrote and this run does not write describes another run: it
// goes with the rest of that run (moved aside like a replaced file, so a failure puts it back).
// A file changed since it was written is the user's now: kept, and no longer in the record.
void OutputFolder::plan_earlier_files(CommitPlan& plan) const {
  for (const auto& [rel, r] : plan.manifest.records) {
    if (plan.staged.count(rel)) continue;
    const fs::path dest = out_ / rel;
    bool plain_path = true;  // never through a link or a file (a record cannot reach outside --out)
    for (const auto& p : parents_of(rel)) plain_path = plain_path && kind_of(out_ / p) == Kind::folder;
    const Kind k = kind_of(dest);
    if (!plain_path || k == Kind::none || (r.folder && k != Kind::folder)) {
      plan.dropped.push_back(rel);
      continue;
    }
    if (r.command != command_ && std::find(taken_.begin(), taken_.end(), r.command) == taken_.end()) continue;
    if (r.folder) {
      if (!plan.needed_folders.count(rel)) plan.stale_folders.push_back(rel);
      continue;
    }
    if (!OutputManifest::intact(dest, r)) {
      plan.kept.push_back(rel);
      plan.dropped.push_back(rel);
      continue;
    }
    try {
      check_not_input(dest, false);
    } catch (const InputError&) {
      continue;
    }
    plan.aside.emplace_back(dest, flag_);
    plan.removed.push_back(rel);
  }
}

// A dataset's file this run does not write would be read as part of the new dataset (in a folder
// of them, such as logs/, every file).
void OutputFolder::check_datasets_whole(const CommitPlan& plan) const {
  const std::set<std::string> going(plan.removed.begin(), plan.removed.end());
  for (const auto& name : together_) {
    std::vector<std::string> there;
    if (kind_of(out_ / name) == Kind::folder) {
      std::error_code ec;
      for (auto it = fs::recursive_directory_iterator(out_ / name, ec); !ec && it != fs::recursive_directory_iterator();
           it.increment(ec))
        if (!it->is_directory()) there.push_back(it->path().lexically_relative(out_).generic_string());
    } else if (kind_of(out_ / name) != Kind::none) {
      there.push_back(name);
    }
    const auto foreign = std::find_if(there.begin(), there.end(), [&](const std::string& n) {
      return !plan.staged.count(n) && !going.count(n);
    });
    if (foreign == there.end()) continue;
    const std::string n = *foreign;
    const fs::path dest = out_ / n;
    const auto it = plan.manifest.records.find(n);
    const bool changed = std::find(plan.kept.begin(), plan.kept.end(), n) != plan.kept.end();
    throw InputError(dest.string(), 0, flag_,
                     fmt::format("{}, and it would be read as part of what {} writes here; move it away or choose "
                                 "another folder",
                                 changed ? std::string("was changed since chutelab wrote it")
                                 : it == plan.manifest.records.end() || it->second.folder
                                     ? std::string("chutelab did not write it")
                                     : fmt::format("chutelab {} wrote it", it->second.command),
                                 command_));
  }
}

// Files the user named: never one --out writes or keeps its record in, never a folder, their
// folders made as needed.
void OutputFolder::plan_named_files(CommitPlan& plan) const {
  for (const auto& n : named_) {
    if (folder_) {
      for (const auto& f : plan.files)
        if (resolved_path(out_ / f, n.flag) == n.resolved)
          throw InputError(n.dest.string(), 0, n.flag, fmt::format("is {}, which --out gets from this run; "
                                                                   "choose another file", (out_ / f).string()));
      for (const auto& [rel, r] : plan.manifest.records)
        if (resolved_path(out_ / rel, n.flag) == n.resolved)
          throw InputError(n.dest.string(), 0, n.flag,
                           fmt::format("is {}, a file chutelab keeps in --out; choose another file", (out_ / rel).string()));
      if (resolved_path(plan.record_path, n.flag) == n.resolved)
        throw InputError(n.dest.string(), 0, n.flag, "is the record chutelab keeps in --out; choose another file");
    }
    std::error_code ec;
    fs::path up = n.dest.parent_path();
    for (; !up.empty() && kind_of(up) == Kind::none; up = up.parent_path())
      if (up == up.parent_path()) break;
    if (!up.empty() && kind_of(up) != Kind::folder && fs::is_directory(up, ec) == false)
      throw InputError(up.string(), 0, n.flag, "is a file where a folder is needed for this file");
    const Kind k = kind_of(n.dest);
    if (k == Kind::folder) throw InputError(n.dest.string(), 0, n.flag, "is a folder; give a file name");
    if (k != Kind::none) plan.aside.emplace_back(n.dest, n.flag);
    plan.moves.push_back({n.staged, n.dest, n.flag});
  }
}

// Moves the replaced files aside and the staged ones into place, then writes the record: all or
// none (a failure puts back what was there).
void OutputFolder::place(CommitPlan& plan) {
  std::error_code ec;
  const bool created = folder_ && !fs::exists(out_);
  if (folder_) {
    fs::create_directories(out_, ec);
    if (ec) throw InputError(out_.string(), 0, flag_, fmt::format("cannot create the folder: {}", ec.message()));
  }
  const fs::path replaced = staging_ / ".replaced";
  fs::create_directory(replaced, ec);
  ec.clear();
  Undo undo(out_, created);
  for (std::size_t k = 0; k < plan.aside.size(); ++k) {
    const auto& [dest, flag] = plan.aside[k];
    // Into the staging folder when it is on the same file system, else beside the file.
    fs::path backup = replaced / std::to_string(k);
    fs::rename(dest, backup, ec);
    if (ec == std::errc::cross_device_link) {
      ec.clear();
      backup = beside(dest, "replaced");
      fs::rename(dest, backup, ec);
      if (!ec) plan.backups_beside.push_back(backup);
    }
    if (ec) undo.fail(dest, flag, ec.message());
    undo.moved_aside(dest, backup);
  }
  for (const auto& mv : plan.moves) {
    for (const auto& dir : missing_folders(mv.dest.parent_path())) {
      fs::create_directory(dir, ec);
      if (ec) undo.fail(dir, mv.flag, ec.message());
      undo.made_folder(dir);
      if (folder_ && mv.flag == flag_ && inside(dir, out_) && dir != out_)
        plan.made.push_back(dir.lexically_relative(out_).generic_string());
    }
    ec = move_file(mv.from, mv.dest);
    if (ec) undo.fail(mv.dest, mv.flag, ec.message());
    undo.placed(mv.dest);
  }
  // The record: last, so that a process killed before it leaves files unrecorded (refused later,
  // never removed) rather than records of files that are not there.
  if (folder_) {
    OutputManifest& m = plan.manifest;
    for (const auto& rel : plan.removed) m.records.erase(rel);
    for (const auto& rel : plan.dropped) m.records.erase(rel);
    for (const auto& f : plan.files) m.records[f] = OutputManifest::of_file(out_ / f, command_);
    for (const auto& p : plan.made) {
      OutputRecord r;
      r.command = command_;
      r.folder = true;
      m.records[p] = r;
    }
    if ((ec = write_record(staging_, m, plan.record_path))) undo.fail(plan.record_path, flag_, ec.message());
  }
}

// Folders this command made and no longer uses, once empty (a user's file inside keeps one), and
// the record again without them.
void OutputFolder::remove_stale_folders(CommitPlan& plan) {
  std::sort(plan.stale_folders.begin(), plan.stale_folders.end(), [](const std::string& a, const std::string& b) {
    return a.size() > b.size();  // the deepest first
  });
  bool emptied = false;
  std::error_code ec;
  for (const auto& rel : plan.stale_folders) {
    if (fs::remove(out_ / rel, ec)) {
      plan.manifest.records.erase(rel);
      emptied = true;
    }
    ec.clear();
  }
  // A failure here leaves records of folders that are gone: dropped next time.
  if (emptied) (void)write_record(staging_, plan.manifest, plan.record_path);
}

void OutputFolder::say_removed_and_kept(const CommitPlan& plan) const {
  if (!plan.removed.empty()) {
    // Said by the top entries of --out: "dem/ (12 files)" rather than every file under it.
    std::vector<std::string> said;
    std::map<std::string, int> under;
    for (const auto& rel : plan.removed) {
      const auto slash = rel.find('/');
      if (slash == std::string::npos) said.push_back(rel);
      else if (under[rel.substr(0, slash)]++ == 0) said.push_back(rel.substr(0, slash) + "/");
    }
    for (auto& s : said)
      if (s.back() == '/') s += fmt::format(" ({} file{})", under[s.substr(0, s.size() - 1)],
                                            under[s.substr(0, s.size() - 1)] == 1 ? "" : "s");
    std::cerr << one_line(fmt::format("chutelab: removed from {} what an earlier {} wrote there and this run does "
                                      "not write: {}",
                                      out_.string(), command_, fmt::join(said, ", ")))
              << "\n";
  }
  for (const auto& rel : plan.kept)
    std::cerr << one_line(fmt::format("chutelab: kept {}: an earlier {} wrote it, but it was changed since, so it is "
                                      "left as it is",
                                      (out_ / rel).string(), command_))
              << "\n";
}

}  // namespace chutelab
