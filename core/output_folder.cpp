#include "core/output_folder.h"

#include <atomic>

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
#include <mutex>
#include <thread>
#ifndef __EMSCRIPTEN__
#include <pthread.h>
#endif

#include "core/input_error.h"
#include "core/message.h"
#ifndef __EMSCRIPTEN__
#include "core/campaign.h"
#endif

namespace chutelab {
namespace fs = std::filesystem;

namespace {

std::mutex& registry_mutex() {
  static std::mutex m;
  return m;
}
std::vector<fs::path>& registry() {
  static std::vector<fs::path> r;
  return r;
}

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

void register_temporary(const fs::path& p) {
  std::lock_guard lock(registry_mutex());
  registry().push_back(p);
}

void unregister_temporary(const fs::path& p) {
  std::lock_guard lock(registry_mutex());
  auto& r = registry();
  for (auto it = r.begin(); it != r.end(); ++it)
    if (*it == p) {
      r.erase(it);
      return;
    }
}

namespace {
std::atomic<bool>& interrupts_quiet() {
  static std::atomic<bool> quiet{false};
  return quiet;
}

#ifndef __EMSCRIPTEN__
// Every signal whose default action ends the process and that a process may catch. SIGKILL and
// SIGSTOP cannot be caught; a crash (SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT) is a bug whose state
// cannot be trusted: their staging folders, like SIGKILL's, are swept by the next run
// (sweep_dead_staging()).
constexpr int kCleanupSignals[] = {SIGHUP,  SIGINT,  SIGQUIT, SIGTERM, SIGALRM, SIGVTALRM, SIGPROF,
                                   SIGXCPU, SIGXFSZ, SIGUSR1, SIGUSR2, SIGPIPE, SIGIO,     SIGPWR,
#ifdef SIGSTKFLT
                                   SIGSTKFLT,
#endif
};

int& wake_fd() {
  static int fd = -1;
  return fd;
}

// The handler only says which signal came (write(2) is async-signal-safe); the thread below, which
// may use the file system freely, does the cleanup. A handler rather than a blocked mask: masks are
// inherited by the programs chutelab starts (LIGGGHTS, mpirun), handlers are reset by exec.
extern "C" void on_cleanup_signal(int sig) {
  const int saved = errno;
  const auto b = static_cast<unsigned char>(sig);
  [[maybe_unused]] const auto n = ::write(wake_fd(), &b, 1);
  errno = saved;
}

const char* signal_message(int sig) {
  switch (sig) {
    case SIGINT: return "\nchutelab: interrupted; nothing was written\n";
    case SIGTERM: return "\nchutelab: terminated; nothing was written\n";
    case SIGHUP: return "\nchutelab: terminated by SIGHUP (terminal closed); nothing was written\n";
    case SIGQUIT: return "\nchutelab: terminated by SIGQUIT; nothing was written\n";
    case SIGALRM: return "\nchutelab: terminated by SIGALRM; nothing was written\n";
    case SIGXCPU: return "\nchutelab: terminated by SIGXCPU (CPU time limit); nothing was written\n";
    case SIGXFSZ: return "\nchutelab: terminated by SIGXFSZ (file size limit); nothing was written\n";
    case SIGPIPE: return nullptr;  // the reader of the output went away: silent, as every Unix tool
    default: return "\nchutelab: terminated by a signal; nothing was written\n";
  }
}
#endif
}  // namespace

void quiet_interrupts() { interrupts_quiet() = true; }

void install_interrupt_cleanup() {
#ifndef __EMSCRIPTEN__  // the designer's page has no signals and no threads
  static std::once_flag once;
  std::call_once(once, [] {
    int fds[2];
    if (::pipe2(fds, O_CLOEXEC) != 0) return;
    wake_fd() = fds[1];
    std::thread([rd = fds[0]] {
      unsigned char b = 0;
      while (::read(rd, &b, 1) != 1) {
      }
      const int sig = b;
      // Holding the lock also waits for a commit in progress to finish: --out is then complete.
      std::lock_guard lock(registry_mutex());
      std::error_code ec;
      // The other threads go on until _exit: one may be adding a file to a folder being removed
      // (remove_all then fails with "not empty"), so each is removed until it is gone, a few times.
      // What a thread still adds after that is swept by the next run (sweep_dead_staging()).
      for (const auto& p : registry())
        for (int attempt = 0; attempt < 5 && fs::exists(fs::symlink_status(p, ec)); ++attempt) fs::remove_all(p, ec);
      const char* msg = signal_message(sig);
      if (msg && !interrupts_quiet()) [[maybe_unused]] const auto n = ::write(2, msg, std::char_traits<char>::length(msg));
      ::_exit(128 + sig);
    }).detach();
    for (int sig : kCleanupSignals) {
      struct sigaction old {};
      // A signal the parent ignores (SIGINT of a background job in a script, SIGHUP under nohup)
      // stays ignored.
      if (sigaction(sig, nullptr, &old) == 0 && old.sa_handler == SIG_IGN) continue;
      struct sigaction sa {};
      sa.sa_handler = on_cleanup_signal;
      sigemptyset(&sa.sa_mask);
      sa.sa_flags = SA_RESTART;
      sigaction(sig, &sa, nullptr);
    }
  });
#endif
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

OutputFolder::OutputFolder(const fs::path& out, std::vector<fs::path> inputs, std::string_view flag)
    : out_(tidy(out)), flag_(flag) {
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

  fs::path parent = out_.parent_path();
  if (parent.empty()) parent = ".";
  writer_ = writes_files();
  staging_ = parent / fmt::format(".{}.partial-{}", out_.filename().string(), static_cast<long>(::getpid()));
  if (!writer_) return;
  fs::create_directories(parent, ec);
  if (ec) throw InputError(parent.string(), 0, flag_, fmt::format("cannot create the folder: {}", ec.message()));
  sweep_dead_staging(out_);
  fs::remove_all(staging_, ec);  // left by a killed run of the same process id
  register_temporary(staging_);
  fs::create_directory(staging_, ec);
  if (ec && fs::is_directory(st)) {
    // A folder one may write in, inside one that is not (--junit /work/report.xml): stage inside it;
    // the renames stay on one file system either way.
    unregister_temporary(staging_);
    staging_ = out_ / fmt::format(".chutelab.partial-{}", static_cast<long>(::getpid()));
    ec.clear();
    fs::remove_all(staging_, ec);
    register_temporary(staging_);
    fs::create_directory(staging_, ec);
  }
  if (ec) {
    unregister_temporary(staging_);
    throw InputError(parent.string(), 0, flag_, fmt::format("cannot write in this folder: {}", ec.message()));
  }
#ifndef __EMSCRIPTEN__
  // Held while this process lives (the kernel releases it however the process ends): a later run
  // sweeps this folder only when no process holds it (sweep_dead_staging()).
  lock_fd_ = ::open((staging_ / kLockName).c_str(), O_CREAT | O_RDWR | O_CLOEXEC, 0600);
  if (lock_fd_ >= 0) [[maybe_unused]] const int locked = ::flock(lock_fd_, LOCK_EX | LOCK_NB);
#endif
}

OutputFolder::~OutputFolder() {
  if (!writer_) return;
  std::error_code ec;
  if (!committed_) fs::remove_all(staging_, ec);
  unregister_temporary(staging_);
#ifndef __EMSCRIPTEN__
  if (lock_fd_ >= 0) ::close(lock_fd_);
#endif
}

void OutputFolder::owns(std::initializer_list<std::string_view> names) {
  for (auto n : names) owned_.emplace_back(n);
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

bool OutputFolder::check_entry(const std::string& name, bool is_dir) const {
  const fs::path dest = out_ / name;
  check_not_input(dest, is_dir);
  std::error_code ec;
  const auto st = fs::symlink_status(dest, ec);
  if (ec && ec != std::errc::no_such_file_or_directory)
    throw InputError(dest.string(), 0, flag_, fmt::format("cannot replace: {}", ec.message()));
  if (!fs::exists(st)) return false;
  if (fs::is_directory(st) && !is_dir)
    throw InputError(dest.string(), 0, flag_, "is a folder where chutelab writes a file; move it away");
  if (!fs::is_directory(st) && is_dir)
    throw InputError(dest.string(), 0, flag_, "is a file where chutelab writes a folder; move it away");
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

void OutputFolder::commit() {
  if (!writer_) {
    committed_ = true;
    return;
  }
  struct Entry {
    fs::path staged, dest, backup;
    bool replaced = false, placed = false;
  };
  std::vector<Entry> entries;
  std::error_code ec;
  // Check every entry before moving any, so that nothing is half-replaced by a foreseeable problem.
  std::vector<std::string> staged_names;
  for (const auto& e : fs::directory_iterator(staging_, ec)) {
    const std::string n = e.path().filename().string();
    if (n == kLockName || n == ".replaced") continue;
    Entry en{e.path(), out_ / e.path().filename(), staging_ / ".replaced" / e.path().filename()};
    en.replaced = check_entry(n, e.is_directory());
    entries.push_back(std::move(en));
    staged_names.push_back(n);
  }
  if (ec) throw InputError(staging_.string(), 0, flag_, fmt::format("cannot list the staged files: {}", ec.message()));
  // What this command writes and did not write this time is an earlier run's: it goes with the
  // rest of that run (moved aside like a replaced entry, so a failure puts it back). Never an input.
  std::vector<std::string> removed;
  for (const auto& n : owned_) {
    if (std::find(staged_names.begin(), staged_names.end(), n) != staged_names.end()) continue;
    const fs::path dest = out_ / n;
    const auto st = fs::symlink_status(dest, ec);
    if (ec || !fs::exists(st)) continue;
    try {
      check_not_input(dest, fs::is_directory(st));
    } catch (const InputError&) {
      continue;
    }
    Entry en{fs::path(), dest, staging_ / ".replaced" / n};
    en.replaced = true;
    entries.push_back(std::move(en));
    removed.push_back(n);
  }
  ec.clear();

  std::lock_guard lock(registry_mutex());  // an interrupt waits until --out is whole again
  const bool created = !fs::exists(out_);
  fs::create_directories(out_, ec);
  if (ec) throw InputError(out_.string(), 0, flag_, fmt::format("cannot create the folder: {}", ec.message()));
  fs::create_directory(staging_ / ".replaced", ec);
  auto roll_back = [&] {
    std::error_code e2;
    for (auto it = entries.rbegin(); it != entries.rend(); ++it) {
      if (it->placed && !it->staged.empty()) fs::rename(it->dest, it->staged, e2);
      if (it->replaced && fs::exists(it->backup, e2)) fs::rename(it->backup, it->dest, e2);
    }
    if (created) fs::remove(out_, e2);
  };
  for (auto& en : entries) {
    ec.clear();
    if (en.replaced) fs::rename(en.dest, en.backup, ec);
    if (!ec && !en.staged.empty()) fs::rename(en.staged, en.dest, ec);
    if (ec) {
      const std::string why = ec.message();
      if (en.replaced && !fs::exists(en.dest)) {
        std::error_code e2;
        fs::rename(en.backup, en.dest, e2);
      }
      en.replaced = false;
      roll_back();
      throw InputError(en.dest.string(), 0, flag_, fmt::format("cannot write: {}", why));
    }
    en.placed = true;
  }
  committed_ = true;
  if (!removed.empty())
    std::cerr << one_line(fmt::format("chutelab: removed from {} what an earlier run left there and this run does "
                                      "not write: {}",
                                      out_.string(), fmt::join(removed, ", ")))
              << "\n";
  fs::remove_all(staging_, ec);
  auto& r = registry();
  for (auto it = r.begin(); it != r.end(); ++it)
    if (*it == staging_) {
      r.erase(it);
      break;
    }
}

}  // namespace chutelab
