#include "validation/model.h"

#include <fmt/format.h>
#include <functional>
#include <utility>

#include "core/input_error.h"
#include "core/message.h"
#include "validation/models/dem_model.h"
#include "validation/models/external_model.h"
#include "validation/models/liggghts_model.h"
#include "validation/models/models.h"

namespace chutelab::validation {
namespace {

// The registry: the analytical models (models/analytical_models.cpp), then the expensive ones.
// Adding a model is one factory and one line here or there. The order matters where models
// overlap: fits and synthetic data take each quantity from the first model that predicts it.
const std::vector<ModelFactory>& registry() {
  static const std::vector<ModelFactory> models = [] {
    auto all = analytical_model_registry();
    all.push_back({"dem", [] { return make_dem_model(); }});
    all.push_back({"liggghts", [] { return make_liggghts_model(); }});
    return all;
  }();
  return models;
}

}  // namespace

std::vector<std::string> model_names() {
  std::vector<std::string> out;
  for (const auto& [n, f] : registry()) out.push_back(n);
  return out;
}

ModelPtr make_model(const std::string& name) {
  if (name.rfind(kExternalPrefix, 0) == 0) return std::make_shared<ExternalModel>(name.substr(kExternalPrefix.size()));
  for (const auto& [n, f] : registry())
    if (n == name) return f();
  throw InputError("", 0, "--models",
                   fmt::format("unknown model {} (known: {}, external:NAME=DIR)", shown(name),
                               fmt::join(model_names(), ", ")));
}

std::vector<ModelPtr> make_models(const std::vector<std::string>& names) {
  std::vector<ModelPtr> out;
  for (std::size_t i = 0; i < names.size(); ++i) {
    // "korzen,,booth-cema": an empty item is a typo, not a gap to skip (every entry point alike).
    if (names[i].empty())
      throw InputError("", 0, "--models", fmt::format("model {} of the list is empty", i + 1));
    // Twice the same model would double every row and count every value twice in the statistics.
    for (std::size_t j = 0; j < i; ++j)
      if (names[j] == names[i])
        throw InputError("", 0, "--models", fmt::format("model {} is listed twice", shown(names[i])));
    out.push_back(make_model(names[i]));
  }
  return out;
}

}  // namespace chutelab::validation
