#include "validation/campaign_runs.h"

#include <set>

#include "core/input_error.h"

namespace chutelab::validation {

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
  std::vector<campaign::Job> work;
  for (const auto& j : jobs) work.push_back(j.job);
  campaign::Options o;
  o.label = options.label;
  const std::vector<std::string> texts = campaign::run_campaign(work, o);
  for (std::size_t k = 0; k < jobs.size(); ++k) jobs[k].accept(texts[k]);
}

}  // namespace chutelab::validation
