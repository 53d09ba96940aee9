#include "app/output_hook.h"

#include <utility>

namespace chutelab::app {

api::PrepareOutput place_output(std::optional<OutputFolder>& out, const std::string& dir, std::string command,
                                MorePlanned more) {
  return [&out, dir, command = std::move(command), more = std::move(more)](const api::OutputPlan& plan) {
    out.emplace(dir, plan.inputs, command);
    for (const auto& f : plan.files) out->check_entry(f, false);
    for (const auto& f : plan.folders) out->check_entry(f, true);
    return more ? more(*out, plan) : std::filesystem::path();
  };
}

api::PrepareOutput check_output(const std::string& dir, std::string command) {
  return [dir, command = std::move(command)](const api::OutputPlan& plan) {
    const OutputFolder check(dir, plan.inputs, command);
    return std::filesystem::path();
  };
}

}  // namespace chutelab::app
