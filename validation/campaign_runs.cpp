#include "validation/campaign_runs.h"

#include <algorithm>
#include <fmt/format.h>
#include <set>

#include "core/input_error.h"
#include "core/progress.h"

namespace chutelab::validation {
namespace {

// Why there are more runs than conditions: said once, before they start.
void explain(const std::vector<ModelJob>& jobs, const RunModelsOptions& options) {
  std::size_t main_runs = 0;
  std::vector<std::string> rungs;
  for (const auto& j : jobs) {
    if (j.ladder_rung.empty()) {
      ++main_runs;
      continue;
    }
    if (std::find(rungs.begin(), rungs.end(), j.ladder_rung) == rungs.end()) rungs.push_back(j.ladder_rung);
  }
  const std::string head = options.label.empty() ? std::string() : options.label + ": ";
  if (rungs.empty() || main_runs == 0) return;
  if (rungs.size() > 4) rungs.resize(4);
  progress::line(fmt::format(
      "{}{} model runs: {} predictions, and {} more at coarser settings ({}) whose differences estimate the "
      "discretisation uncertainty u_num of each prediction (ASME V&V 20; {} off leaves them out)",
      head, jobs.size(), main_runs, jobs.size() - main_runs, fmt::join(rungs, "; "), mention("dem.ladder")));
}

}  // namespace

void run_models(std::span<const ModelRun> runs, const RunModelsOptions& options) {
  std::vector<ModelJob> jobs;
  std::set<std::string> seen;
  for (const auto& r : runs) {
    if (!r.model) continue;
    PredictRequest request;
    request.signature = r.signature;
    request.discretisation = r.discretisation;
    for (ModelJob& j : r.model->campaign_jobs(r.station, r.effects, request)) {
      if (!seen.insert(j.id).second) continue;
      if (!r.file.empty())
        j.job.run = [run = std::move(j.job.run), file = r.file, line = r.line](const campaign::JobContext& ctx) {
          try {
            return run(ctx);
          } catch (const InputError& e) {
            throw e.located(file, line);
          }
        };
      jobs.push_back(std::move(j));
    }
  }
  if (jobs.empty()) return;
  if (!options.purpose.empty())
    progress::line(fmt::format("{}{} ({} runs)", options.label.empty() ? std::string() : options.label + ": ",
                               options.purpose, jobs.size()));
  explain(jobs, options);
  std::vector<campaign::Job> work;
  for (const auto& j : jobs) work.push_back(j.job);
  campaign::Options o;
  o.label = options.label;
  o.threads = options.jobs;
  const std::vector<std::string> texts = campaign::run_campaign(work, o);
  for (std::size_t k = 0; k < jobs.size(); ++k) jobs[k].accept(texts[k]);
}

}  // namespace chutelab::validation
