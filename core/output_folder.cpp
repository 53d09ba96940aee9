#include "core/output_folder.h"

#include <atomic>

#include <unistd.h>

#include <csignal>
#include <fmt/format.h>
#include <fstream>
#include <mutex>
#include <thread>
#ifndef __EMSCRIPTEN__
#include <pthread.h>
#endif

#include "core/input_error.h"
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
}  // namespace

void quiet_interrupts() { interrupts_quiet() = true; }

void install_interrupt_cleanup() {
#ifndef __EMSCRIPTEN__  // the designer's page has no signals and no threads
  static std::once_flag once;
  std::call_once(once, [] {
    sigset_t set;
    sigemptyset(&set);
    // A signal the parent ignores (SIGINT of a background job in a script) stays ignored.
    for (int sig : {SIGINT, SIGTERM}) {
      struct sigaction old {};
      if (sigaction(sig, nullptr, &old) == 0 && old.sa_handler == SIG_IGN) continue;
      sigaddset(&set, sig);
    }
    // Blocked here, before any worker thread exists, so that every thread inherits the mask and the
    // signal is taken only by the thread below, which may use the file system freely.
    pthread_sigmask(SIG_BLOCK, &set, nullptr);
    std::thread([set] {
      int sig = 0;
      while (sigwait(&set, &sig) != 0) {
      }
      // Holding the lock also waits for a commit in progress to finish: --out is then complete.
      std::lock_guard lock(registry_mutex());
      std::error_code ec;
      for (const auto& p : registry()) fs::remove_all(p, ec);
      const char* msg = sig == SIGINT ? "\nchutelab: interrupted; nothing was written\n"
                                      : "\nchutelab: terminated; nothing was written\n";
      if (!interrupts_quiet()) [[maybe_unused]] const auto n = ::write(2, msg, std::char_traits<char>::length(msg));
      ::_exit(128 + sig);
    }).detach();
  });
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
}

OutputFolder::~OutputFolder() {
  if (!writer_) return;
  std::error_code ec;
  if (!committed_) fs::remove_all(staging_, ec);
  unregister_temporary(staging_);
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
  check_not_input(out_ / name, false);
  if (!writer_) return;
  const fs::path p = staging_ / name;
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
  for (const auto& e : fs::directory_iterator(staging_, ec)) {
    Entry en{e.path(), out_ / e.path().filename(), staging_ / ".replaced" / e.path().filename()};
    en.replaced = check_entry(e.path().filename().string(), e.is_directory());
    entries.push_back(std::move(en));
  }
  if (ec) throw InputError(staging_.string(), 0, flag_, fmt::format("cannot list the staged files: {}", ec.message()));

  std::lock_guard lock(registry_mutex());  // an interrupt waits until --out is whole again
  const bool created = !fs::exists(out_);
  fs::create_directories(out_, ec);
  if (ec) throw InputError(out_.string(), 0, flag_, fmt::format("cannot create the folder: {}", ec.message()));
  fs::create_directory(staging_ / ".replaced", ec);
  auto roll_back = [&] {
    std::error_code e2;
    for (auto it = entries.rbegin(); it != entries.rend(); ++it) {
      if (it->placed) fs::rename(it->dest, it->staged, e2);
      if (it->replaced && fs::exists(it->backup, e2)) fs::rename(it->backup, it->dest, e2);
    }
    if (created) fs::remove(out_, e2);
  };
  for (auto& en : entries) {
    ec.clear();
    if (en.replaced) fs::rename(en.dest, en.backup, ec);
    if (!ec) fs::rename(en.staged, en.dest, ec);
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
  fs::remove_all(staging_, ec);
  auto& r = registry();
  for (auto it = r.begin(); it != r.end(); ++it)
    if (*it == staging_) {
      r.erase(it);
      break;
    }
}

}  // namespace chutelab
