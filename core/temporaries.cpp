#include "core/temporaries.h"

#include <atomic>
#include <cerrno>
#include <csignal>
#include <string>
#include <thread>
#include <vector>

#include <unistd.h>
#ifndef __EMSCRIPTEN__
#include <fcntl.h>
#endif

namespace chutelab {
namespace fs = std::filesystem;

namespace {
std::vector<fs::path>& registry() {
  static std::vector<fs::path> r;
  return r;
}
}  // namespace

std::mutex& temporaries_mutex() {
  static std::mutex m;
  return m;
}

void register_temporary(const fs::path& p) {
  std::lock_guard lock(temporaries_mutex());
  registry().push_back(p);
}

void unregister_temporary(const fs::path& p) {
  std::lock_guard lock(temporaries_mutex());
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
      std::lock_guard lock(temporaries_mutex());
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

}  // namespace chutelab
