// The campaign facility (core/campaign.h) in one process, and the DEM cache's safety with several
// writers. The MPI side is tested by running chutelab under mpirun (test_mpi_campaign.cpp).
#define BOOST_TEST_MODULE campaign
#include <boost/test/unit_test.hpp>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <filesystem>
#include <thread>

#include "core/campaign.h"
#include "core/free_cores.h"
#include "core/input_error.h"
#include "dem/station/cache.h"

using namespace chutelab;
namespace fs = std::filesystem;

// Longest first onto the least loaded rank: a fixed answer, and a balance within the largest job.
BOOST_AUTO_TEST_CASE(assignment_is_longest_first_and_deterministic) {
  const std::vector<double> cost = {1, 1, 7, 2.7, 2, 2.5, 0.4, 5.2};
  const auto a = campaign::assign(cost, 2);
  BOOST_TEST(a == campaign::assign(cost, 2));
  BOOST_TEST(a == (std::vector<int>{0, 1, 0, 1, 1, 0, 0, 1}));
  std::vector<double> load(2, 0.0);
  for (std::size_t k = 0; k < cost.size(); ++k) load[static_cast<std::size_t>(a[k])] += cost[k];
  BOOST_TEST(std::abs(load[0] - load[1]) <= 7.0);  // LPT's bound: at most the dearest job apart
  BOOST_TEST(campaign::assign(cost, 1) == std::vector<int>(cost.size(), 0));
  const auto many = campaign::assign(cost, 16);  // more ranks than jobs: one job each
  for (std::size_t k = 0; k < many.size(); ++k)
    for (std::size_t j = 0; j < k; ++j) BOOST_TEST(many[k] != many[j]);
}

// Threads give the results in job order whatever finishes first; in order is today's behaviour.
BOOST_AUTO_TEST_CASE(results_come_back_in_job_order) {
  std::vector<campaign::Job> jobs;
  std::atomic<int> running{0}, most{0};
  for (int k = 0; k < 12; ++k)
    jobs.push_back({std::to_string(k), static_cast<double>(k % 4), [k, &running, &most](const campaign::JobContext& ctx) {
                      const int now = ++running;
                      int seen = most.load();
                      while (now > seen && !most.compare_exchange_weak(seen, now)) {}
                      std::this_thread::sleep_for(std::chrono::milliseconds(5 * (12 - k)));
                      --running;
                      return "job " + std::to_string(k) + (ctx.progress ? " p" : "");
                    }});
  campaign::Options o;
  o.progress = false;
  o.threads = 3;
  const auto threaded = campaign::run_campaign(jobs, o);
  BOOST_TEST(most.load() > 1);   // they did run side by side
  BOOST_TEST(most.load() <= 3);
  for (int k = 0; k < 12; ++k) BOOST_TEST(threaded[static_cast<std::size_t>(k)] == "job " + std::to_string(k));
  o.threads = 1;
  const auto serial = campaign::run_campaign(jobs, o);
  for (int k = 0; k < 12; ++k) BOOST_TEST(serial[static_cast<std::size_t>(k)] == "job " + std::to_string(k) + " p");
}

// Jobs side by side share the cores, so each is given one thread; a job run alone (in order, or a
// campaign of one) keeps its own automatic choice (0), whatever the command's --jobs.
BOOST_AUTO_TEST_CASE(jobs_side_by_side_get_one_thread_each) {
  auto threads_of = [](std::size_t count, int workers) {
    std::vector<campaign::Job> jobs;
    for (std::size_t k = 0; k < count; ++k)
      jobs.push_back({"t", 1.0, [](const campaign::JobContext& ctx) { return std::to_string(ctx.threads); }});
    campaign::Options o;
    o.progress = false;
    o.threads = workers;
    return campaign::run_campaign(jobs, o);
  };
  BOOST_TEST(threads_of(4, 2) == std::vector<std::string>(4, "1"));
  BOOST_TEST(threads_of(4, 1) == std::vector<std::string>(4, "0"));
  BOOST_TEST(threads_of(1, 2) == std::vector<std::string>(1, "0"));
}

// A worker with no job left says so through JobContext::idle: the last job running sees the other
// worker's core free (a DEM run then takes it; its results do not depend on the thread count).
BOOST_AUTO_TEST_CASE(a_worker_with_no_job_left_is_counted_idle) {
  std::vector<campaign::Job> jobs;
  jobs.push_back({"long", 2.0, [](const campaign::JobContext& ctx) {
                    if (!ctx.idle) return std::string("none");
                    for (int k = 0; k < 2000 && ctx.idle->load() < 1; ++k)
                      std::this_thread::sleep_for(std::chrono::milliseconds(5));
                    return std::to_string(ctx.idle->load());
                  }});
  jobs.push_back({"short", 1.0, [](const campaign::JobContext&) { return std::string("done"); }});
  campaign::Options o;
  o.progress = false;
  o.threads = 2;
  const auto out = campaign::run_campaign(jobs, o);
  BOOST_TEST(out[0] == "1");
  BOOST_TEST(out[1] == "done");
}

// A job's bad input reaches the caller whole (file, line, field), whichever thread ran it.
BOOST_AUTO_TEST_CASE(a_failing_job_throws_its_input_error) {
  for (int threads : {1, 2}) {
    std::vector<campaign::Job> jobs;
    jobs.push_back({"fine", 1.0, [](const campaign::JobContext&) { return std::string("ok"); }});
    jobs.push_back({"bad", 1.0, [](const campaign::JobContext&) -> std::string {
                      throw InputError("conditions.csv", 7, "belt_speed_mps", "must be > 0");
                    }});
    campaign::Options o;
    o.threads = threads;
    o.progress = false;
    try {
      campaign::run_campaign(jobs, o);
      BOOST_FAIL("no error");
    } catch (const InputError& e) {
      BOOST_TEST(e.file() == "conditions.csv");
      BOOST_TEST(e.line() == 7);
      BOOST_TEST(e.field() == "belt_speed_mps");
      BOOST_TEST(e.problem() == "must be > 0");
    }
  }
}

// Ranks sharing a cache folder: several writers of one key and a reader at the same time. The
// reader sees nothing or a whole result, never part of one; no temporary file is left behind.
BOOST_AUTO_TEST_CASE(cache_tolerates_concurrent_writers) {
  const fs::path dir = fs::temp_directory_path() / ("chutelab-test-cache-" + std::to_string(::getpid()));
  fs::remove_all(dir);
  const dem::station::ResultCache cache(dir.string());
  dem::station::StationResult r;
  r.condition = "V3-41";
  r.quality = "quick";
  r.diameter = 0.0136;
  r.dt = 1.0 / 3.0;
  r.normal_force = {35.123456789012345, 0.1, 3};
  for (int k = 0; k < 4000; ++k) r.forces.push_back({k * 1e-3, 1.0 / (k + 1), 0.5, 0.25, 0, 0, 0, 0});
  const std::string want = dem::station::to_text(r);
  std::atomic<bool> stop{false};
  std::atomic<int> bad{0}, hits{0};
  std::thread reader([&] {
    while (!stop) {
      if (auto got = cache.load("key")) {
        ++hits;
        if (dem::station::to_text(*got) != want) ++bad;
      }
    }
  });
  std::vector<std::thread> writers;
  for (int w = 0; w < 4; ++w)
    writers.emplace_back([&] {
      for (int k = 0; k < 20; ++k) BOOST_CHECK(cache.store("key", r));
    });
  for (auto& t : writers) t.join();
  stop = true;
  reader.join();
  BOOST_TEST(bad.load() == 0);
  BOOST_TEST(hits.load() > 0);
  // A text round trip is exact (17 significant digits): what a campaign sends is what ran.
  BOOST_TEST(dem::station::to_text(*dem::station::from_text(want)) == want);
  BOOST_TEST(dem::station::from_text(want)->normal_force.value == r.normal_force.value);
  // A file cut short is a miss.
  const std::string path = cache.path_for("key");
  const auto size = fs::file_size(path);
  fs::resize_file(path, size / 2);
  BOOST_TEST(!cache.load("key"));
  int left = 0;
  for (const auto& e : fs::directory_iterator(dir)) left += e.path().extension() == ".tmp";
  BOOST_TEST(left == 0);
  fs::remove_all(dir);
}

// The default thread and job counts leave out our own process's work: a thread of ours spinning
// while the machine is sampled must not count as someone else's (the 1-minute load average counted
// it, and a command after another got one job on an idle machine). Other processes come and go on a
// shared machine (ctest starts the MPI test beside this one), so a sample without the spin and one
// with it are taken side by side, four times: a counted spin would add about 1 to every pair's
// difference, while another process starting between two samples moves one pair only.
BOOST_AUTO_TEST_CASE(free_cores_leave_out_our_own_work) {
  using namespace std::chrono_literals;
  double least_gap = 1e9, quiet = 0.0, busy_self = 0.0;
  std::atomic<unsigned long> spins{0};
  for (int pair = 0; pair < 4; ++pair) {
    const double q = busy_cores_of_others(200ms);
    std::atomic<bool> stop{false};
    std::thread spinner([&] {
      while (!stop.load(std::memory_order_relaxed)) spins.fetch_add(1, std::memory_order_relaxed);
    });
    std::this_thread::sleep_for(50ms);
    const double b = busy_cores_of_others(200ms);
    stop = true;
    spinner.join();
    if (b - q < least_gap) {
      least_gap = b - q;
      quiet = q;
      busy_self = b;
    }
  }
  BOOST_TEST(spins.load() > 0u);
  BOOST_TEST(least_gap < 0.5, "our own spinning thread counted as another process's: " << busy_self << " vs "
                                                                                         << quiet);
  const int cores = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  BOOST_TEST(free_cores() >= 1);
  BOOST_TEST(free_cores() <= cores);
}
