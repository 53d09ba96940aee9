#include "core/campaign.h"

#include "core/message.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <exception>
#include <fcntl.h>
#include <iostream>
#include <mutex>
#include <numeric>
#include <optional>
#include <thread>
#include <unistd.h>

#include <fmt/format.h>

#include "core/input_error.h"
#include "core/interrupt.h"
#include "core/progress.h"

#ifdef CHUTELAB_HAVE_MPI
#include <mpi.h>
#endif

namespace chutelab::campaign {
namespace {

int g_rank = 0, g_ranks = 1;
int g_error_fd = 2;  // the rank's real stderr, kept when the rank is muted

// A job's outcome travels as text: "ok\n" + result, or the error that every rank rethrows.
std::string ok_text(std::string result) { return "ok\n" + result; }

std::string error_text(const std::exception_ptr& e) {
  try {
    std::rethrow_exception(e);
  } catch (const interrupt::Interrupted&) {
    return "interrupted\n";
  } catch (const InputError& x) {
    return fmt::format("input-error\n{}\n{}\n{}\n", x.file().size(), x.line(), x.field().size()) + x.file() +
           x.field() + x.problem();
  } catch (const std::exception& x) {
    return std::string("error\n") + x.what();
  } catch (...) {
    return "error\nunknown exception in a campaign job";
  }
}

// The result, or the job's exception rethrown.
std::string unwrap(std::string text) {
  if (text.rfind("ok\n", 0) == 0) return text.substr(3);
  if (text == "interrupted\n") throw interrupt::Interrupted();
  if (text.rfind("input-error\n", 0) == 0) {
    std::size_t at = 12;
    auto next = [&] {
      const std::size_t nl = text.find('\n', at);
      const std::string s = text.substr(at, nl - at);
      at = nl + 1;
      return s;
    };
    const std::size_t file_len = std::stoull(next());
    const long line = std::stol(next());
    const std::size_t field_len = std::stoull(next());
    const std::string file = text.substr(at, file_len);
    const std::string field = text.substr(at + file_len, field_len);
    const std::string problem = text.substr(at + file_len + field_len);
    throw InputError(file, line, field, problem);
  }
  throw std::runtime_error(text.substr(text.find('\n') + 1));
}

std::string run_one(const Job& job, const JobContext& ctx) {
  const progress::CampaignJobScope scope;
  try {
    interrupt::point();
    return ok_text(job.run(ctx));
  } catch (...) {
    return error_text(std::current_exception());
  }
}

std::string prefix(const Options& o) { return o.label.empty() ? std::string() : o.label + ": "; }

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

std::string clock(double s) {
  const long t = std::lround(std::max(0.0, s));
  return t < 60 ? fmt::format("{} s", t) : fmt::format("{}:{:02d} min", t / 60, t % 60);
}

// One line per job that ran, a running count on the terminal's status line, and a closing line.
struct Tally {
  const Options& o;
  std::size_t total, done = 0, reused = 0;
  std::chrono::steady_clock::time_point t0 = std::chrono::steady_clock::now();
  void show() const {
    if (o.progress) progress::status_prefix(fmt::format("{}{}/{} runs done", prefix(o), done, total));
  }
  void finished(const Job& job, const std::string& out, bool was_reused, double seconds) {
    ++done;
    if (was_reused) ++reused;
    if (!o.progress) return;
    const bool ok = out.rfind("ok\n", 0) == 0;
    if (!was_reused || !ok)
      progress::line(fmt::format("{}[{}/{}] {} {} in {}", prefix(o), done, total, one_line(job.key, 120),
                                 ok ? "done" : out == "interrupted\n" ? "stopped" : "failed", clock(seconds)));
    show();
  }
  void close(const std::string& how) const {
    if (!o.progress) return;
    progress::clear();
    const std::size_t ran = done - reused;
    if (ran == 0) progress::line(fmt::format("{}{} runs, all from the cache", prefix(o), done));
    else
      progress::line(fmt::format("{}{} runs ({} ran{}{}) in {}{}", prefix(o), done, ran, how,
                                 reused ? fmt::format(", {} from the cache", reused) : std::string(),
                                 clock(seconds_since(t0)), std::string()));
  }
};

// One process, `threads` jobs at a time, dearest first (the last job to start is a cheap one).
std::vector<std::string> run_threads(std::span<const Job> jobs, const Options& o) {
  std::vector<std::string> out(jobs.size());
  std::vector<std::size_t> order(jobs.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return jobs[a].cost > jobs[b].cost; });
  std::atomic<std::size_t> next{0};
  std::atomic<int> idle{0};
  std::atomic<std::size_t> finished{0};
  std::mutex print;
  const int n = std::min<int>(o.threads, static_cast<int>(jobs.size()));
  Tally tally{o, jobs.size()};
  tally.show();
  auto worker = [&] {
    for (std::size_t i; (i = next.fetch_add(1)) < order.size();) {
      const std::size_t k = order[i];
      const auto t = std::chrono::steady_clock::now();
      bool reused = false;
      JobContext ctx{false, 1, &idle};
      ctx.reused = &reused;
      out[k] = run_one(jobs[k], ctx);
      const std::lock_guard<std::mutex> lock(print);
      tally.finished(jobs[k], out[k], reused, seconds_since(t));
    }
    idle.fetch_add(1);  // no job left for this worker: its core is free for the jobs still running
    finished.fetch_add(1);
  };
  std::vector<std::thread> pool;
  for (int t = 0; t < n; ++t) pool.emplace_back(worker);
  interrupt::join(pool, finished);
  tally.close(fmt::format(", {} side by side", n));
  return out;
}

#ifdef CHUTELAB_HAVE_MPI
std::vector<std::string> run_mpi(std::span<const Job> jobs, const Options& o) {
  std::vector<double> costs;
  for (const auto& j : jobs) costs.push_back(j.cost);
  const std::vector<int> owner = assign(costs, g_ranks);
  std::vector<std::string> out(jobs.size());
  const auto t0 = std::chrono::steady_clock::now();
  double busy = 0.0;
  int mine = 0;
  for (std::size_t k = 0; k < jobs.size(); ++k) {
    if (owner[k] != g_rank) continue;
    const auto t = std::chrono::steady_clock::now();
    out[k] = run_one(jobs[k], JobContext{g_rank == 0, 1});
    busy += seconds_since(t);
    ++mine;
    if (g_rank == 0 && o.progress)
      progress::line(fmt::format("{}{} done in {} ({}/{}, rank 0 of {})", prefix(o), one_line(jobs[k].key, 120), clock(seconds_since(t)),
                                 k + 1, jobs.size(), g_ranks));
  }
  const double local = seconds_since(t0);
  // Every result to every rank, in job order. Lengths first: a rank cannot know another's text size.
  for (std::size_t k = 0; k < jobs.size(); ++k) {
    std::uint64_t len = out[k].size();
    MPI_Bcast(&len, 1, MPI_UINT64_T, owner[k], MPI_COMM_WORLD);
    out[k].resize(len);
    std::size_t at = 0;
    while (at < len) {  // counts are int: large texts go in pieces
      const int piece = static_cast<int>(std::min<std::uint64_t>(len - at, 1u << 30));
      MPI_Bcast(out[k].data() + at, piece, MPI_CHAR, owner[k], MPI_COMM_WORLD);
      at += static_cast<std::size_t>(piece);
    }
  }
  // How the work fell, so a user can judge the balance: per rank, jobs and busy seconds.
  std::vector<double> all_busy(static_cast<std::size_t>(g_ranks)), all_local(static_cast<std::size_t>(g_ranks));
  std::vector<int> all_jobs(static_cast<std::size_t>(g_ranks));
  MPI_Gather(&busy, 1, MPI_DOUBLE, all_busy.data(), 1, MPI_DOUBLE, 0, MPI_COMM_WORLD);
  MPI_Gather(&local, 1, MPI_DOUBLE, all_local.data(), 1, MPI_DOUBLE, 0, MPI_COMM_WORLD);
  MPI_Gather(&mine, 1, MPI_INT, all_jobs.data(), 1, MPI_INT, 0, MPI_COMM_WORLD);
  if (g_rank == 0 && o.progress) {
    std::string s = fmt::format("{}{} jobs on {} MPI ranks in {:.0f} s:", o.label.empty() ? "" : o.label + ": ", jobs.size(),
                                g_ranks, seconds_since(t0));
    for (int r = 0; r < g_ranks; ++r)
      s += fmt::format(" rank {} {} jobs {:.0f} s;", r, all_jobs[static_cast<std::size_t>(r)],
                       all_busy[static_cast<std::size_t>(r)]);
    s.pop_back();
    progress::line(s);
  }
  return out;
}
#endif

// Launchers' variables for the size of the job: OpenMPI, MPICH/Intel (PMI), PMIx, Slurm's srun.
[[maybe_unused]] int launcher_size() {
  for (const char* v : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_SIZE", "MPI_LOCALNRANKS"})
    if (const char* s = std::getenv(v); s && *s) return std::max(1, std::atoi(s));
  return 1;
}

[[maybe_unused]] bool under_launcher() {
  for (const char* v : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMI_RANK", "PMIX_RANK"})
    if (const char* s = std::getenv(v); s && *s) return true;
  return false;
}

}  // namespace

std::vector<int> assign(std::span<const double> costs, int n_ranks) {
  std::vector<int> owner(costs.size(), 0);
  if (n_ranks <= 1) return owner;
  std::vector<std::size_t> order(costs.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return costs[a] > costs[b]; });
  std::vector<double> load(static_cast<std::size_t>(n_ranks), 0.0);
  for (std::size_t k : order) {
    const auto r = static_cast<std::size_t>(std::min_element(load.begin(), load.end()) - load.begin());
    owner[k] = static_cast<int>(r);
    load[r] += std::max(0.0, costs[k]);
  }
  return owner;
}

std::vector<std::string> run_campaign(std::span<const Job> jobs, const Options& options) {
  std::vector<std::string> wrapped;
  if (g_ranks > 1) {
#ifdef CHUTELAB_HAVE_MPI
    wrapped = run_mpi(jobs, options);
#endif
  } else if (const int t = options.threads > 0 ? options.threads : 1; t > 1 && jobs.size() > 1) {
    Options o = options;
    o.threads = t;
    wrapped = run_threads(jobs, o);
  } else {
    // In order, each job with its own progress on the status line. The first failure ends it.
    Tally tally{options, jobs.size()};
    tally.show();
    for (const auto& j : jobs) {
      const auto t = std::chrono::steady_clock::now();
      bool reused = false;
      JobContext ctx{true, 0};
      ctx.reused = &reused;
      wrapped.push_back(run_one(j, ctx));
      tally.finished(j, wrapped.back(), reused, seconds_since(t));
      if (wrapped.back().rfind("ok\n", 0) != 0) break;
    }
    if (jobs.size() > 1) tally.close(", one at a time");
    else if (options.progress) progress::clear();
  }
  std::vector<std::string> out;
  out.reserve(wrapped.size());
  for (auto& w : wrapped) out.push_back(unwrap(std::move(w)));
  return out;
}

int rank() { return g_rank; }
int ranks() { return g_ranks; }
bool output_rank() { return g_rank == 0; }

bool built_with_mpi() {
#ifdef CHUTELAB_HAVE_MPI
  return true;
#else
  return false;
#endif
}

Session::Session(int& argc, char**& argv) {
#ifdef CHUTELAB_HAVE_MPI
  // MPI starts only under a launcher: a designer's `estimate` must not pay for MPI_Init.
  if (under_launcher()) {
    MPI_Init(&argc, &argv);
    mpi_ = true;
    MPI_Comm_rank(MPI_COMM_WORLD, &g_rank);
    MPI_Comm_size(MPI_COMM_WORLD, &g_ranks);
    if (g_rank != 0) {
      std::cout.flush();
      std::cerr.flush();
      g_error_fd = ::dup(2);
      const int null = ::open("/dev/null", O_WRONLY);
      if (null >= 0) {
        ::dup2(null, 1);
        ::dup2(null, 2);
        ::close(null);
      }
    }
  }
#else
  (void)argc;
  (void)argv;
  if (const int n = launcher_size(); n > 1)
    refusal_ = fmt::format(
        "started as one of {} processes by an MPI launcher, but this chutelab was built without MPI: every copy "
        "would run the whole command and write the same files. Install libopenmpi-dev and rebuild (CMake finds "
        "MPI), or run one process",
        n);
#endif
}

Session::~Session() {
#ifdef CHUTELAB_HAVE_MPI
  if (mpi_) {
    std::cout.flush();
    std::cerr.flush();
    MPI_Finalize();
  }
#endif
}

void error_line(const std::string& text) {
  const std::string line = (g_ranks > 1 ? fmt::format("chutelab (rank {}): ", g_rank) : std::string("chutelab: ")) + text + "\n";
  std::cerr.flush();
  [[maybe_unused]] const auto n = ::write(g_error_fd, line.data(), line.size());
}

void abort_all(int code) {
#ifdef CHUTELAB_HAVE_MPI
  if (g_ranks > 1) MPI_Abort(MPI_COMM_WORLD, code);
#endif
  std::_Exit(code);
}

}  // namespace chutelab::campaign
