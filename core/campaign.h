#pragma once
// A campaign: many independent, deterministic jobs (DEM runs of a sensitivity study, a validation,
// a diagnosis, a calibration) spread over MPI ranks when chutelab runs under `mpirun`, or over a
// few worker threads of one process (`--jobs N`), with results that do not depend on either.
//
// Every rank runs the same command (SPMD). A command reaching a campaign calls run_campaign() on
// every rank with the same job list; each job runs on exactly one rank (longest-first by its
// estimated cost, ties in job order: a fixed assignment), and its result text is sent to every
// rank. run_campaign() returns on every rank with all texts in job order, so each rank proceeds
// exactly as a single process would. Only rank 0 prints (other ranks' stdout and stderr go to
// /dev/null, see Session) and writes files (output_rank()).
//
// Jobs must be deterministic: the same job gives the same text on any rank, thread or process,
// whatever ran before it. A job that throws InputError throws it on every rank (in job order,
// after the exchange), so every rank fails the same way.
//
// Built without MPI (CMake found none), ranks are always 1; a binary started by a launcher with
// several processes (OMPI_COMM_WORLD_SIZE, PMI_SIZE > 1) refuses to run instead of writing the
// same files N times.
#include <atomic>
#include <functional>
#include <span>
#include <string>
#include <vector>

namespace chutelab::campaign {

struct JobContext {
  bool progress = false;  // the job may print its own progress (rank 0, one job at a time)
  // OpenMP threads the job may use: 1 when jobs share the cores (worker threads, ranks); 0 when it
  // runs alone and may take its own automatic choice.
  int threads = 0;
  // Workers of the process's pool that have no job left (never fewer as the campaign goes on): a
  // job whose result does not depend on its thread count may take that many more, so the last
  // runs of a campaign do not leave cores idle. Null when there is no such pool (MPI ranks).
  const std::atomic<int>* idle = nullptr;
  // The job sets it when it found its result without running (a cache): the campaign then counts
  // it instead of printing a line for it.
  bool* reused = nullptr;
};

struct Job {
  std::string key;     // what it is, for progress lines ("dem V3-41", "clump"); need not be unique
  double cost = 1.0;   // estimated relative cost (e.g. particles x steps), for balancing only
  std::function<std::string(const JobContext&)> run;  // the work; its complete result as text
};

struct Options {
  // Concurrent jobs in one process (one rank only); 0 or 1: in order. A caller's option, never the
  // process's: the library's functions take it as their `jobs` (api/dem_options.h, resolve_jobs).
  int threads = 0;
  std::string label;      // "sensitivity", "dem": prefix of the campaign's progress lines
  bool progress = true;   // a line per finished job that ran (core/progress.h), and a summary
};

// Results of every job, in job order, on every rank.
std::vector<std::string> run_campaign(std::span<const Job> jobs, const Options& options = {});

// Which rank runs job k of these costs on `ranks` ranks: longest-first onto the least loaded rank
// (ties: lower rank), the jobs taken by decreasing cost, ties in job order. Exposed for tests and
// for the bench's projection.
std::vector<int> assign(std::span<const double> costs, int ranks);

int rank();           // 0 without MPI
int ranks();          // 1 without MPI
bool output_rank();   // rank 0: the one that prints and writes files
bool built_with_mpi();

// Owns MPI for the life of main(). Without MPI it checks the launcher's variables instead. On a
// rank other than 0 it sends stdout and stderr to /dev/null (errors of that rank alone still reach
// the terminal through error_stream()).
class Session {
 public:
  Session(int& argc, char**& argv);
  ~Session();
  Session(const Session&) = delete;
  Session& operator=(const Session&) = delete;
  // Not empty when the process must not run: the message to print (exit code 2).
  const std::string& refusal() const { return refusal_; }

 private:
  std::string refusal_;
  bool mpi_ = false;
};

// Writes a line to the rank's real stderr (even when muted), prefixed with the rank under MPI.
void error_line(const std::string& text);

// Ends every rank at once after an error only some ranks saw (MPI_Abort); without MPI, does nothing.
[[noreturn]] void abort_all(int code);

}  // namespace chutelab::campaign
