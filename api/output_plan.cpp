#include "api/output_plan.h"

namespace chutelab::api {

std::vector<std::filesystem::path> model_inputs(const std::vector<std::string>& models) {
  std::vector<std::filesystem::path> out;
  for (const auto& m : models)
    if (m.rfind("external:", 0) == 0)
      if (const auto eq = m.find('='); eq != std::string::npos) {
        const std::filesystem::path d = m.substr(eq + 1);
        for (const char* f : {"", "predictions.csv", "trajectory.csv", "README.md"}) out.push_back(*f ? d / f : d);
      }
  return out;
}

}  // namespace chutelab::api
