#include "validation/model.h"

#include <fmt/format.h>
#include <functional>
#include <utility>

#include "core/input_error.h"
#include "core/message.h"
#include "validation/models/dem_model.h"
#include "validation/models/external_model.h"
#include "validation/models/liggghts_model.h"
#include "validation/models/model_settings.h"
#include "validation/models/models.h"

namespace chutelab::validation {
namespace {

// The registry: the analytical models (models/analytical_models.cpp), then the expensive ones.
// Adding a model is one factory and one line here or there. The order matters where models
// overlap: fits and synthetic data take each quantity from the first model that predicts it.
using SettingsFactory = std::pair<std::string, std::function<ModelPtr(const ModelSettings&)>>;
const std::vector<SettingsFactory>& registry() {
  static const std::vector<SettingsFactory> models = [] {
    std::vector<SettingsFactory> all;
    for (const auto& entry : analytical_model_registry()) {
      auto make = entry.second;
      all.push_back({entry.first, [make](const ModelSettings&) { return make(); }});
    }
    all.push_back({"dem", [](const ModelSettings& s) { return make_dem_model(s.dem); }});
    all.push_back({"liggghts", [](const ModelSettings& s) { return make_liggghts_model(s.liggghts); }});
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

ModelPtr make_model(const std::string& name) { return make_model(name, ModelSettings{}); }

ModelPtr make_model(const std::string& name, const ModelSettings& settings) {
  if (name.rfind(kExternalPrefix, 0) == 0) return std::make_shared<ExternalModel>(name.substr(kExternalPrefix.size()));
  for (const auto& [n, f] : registry())
    if (n == name) return f(settings);
  throw InputError("", 0, "models",
                   fmt::format("unknown model {} (known: {}, external:NAME=DIR)", shown(name),
                               fmt::join(model_names(), ", ")));
}

std::vector<ModelPtr> make_models(const std::vector<std::string>& names) { return make_models(names, ModelSettings{}); }

void check_model_names(const std::vector<std::string>& names) {
  if (names.empty()) throw InputError("", 0, "models", "no model given");
  for (std::size_t i = 0; i < names.size(); ++i) {
    // "korzen,,booth-cema": an empty item is a typo, not a gap to skip (every entry point alike).
    if (names[i].empty())
      throw InputError("", 0, "models", fmt::format("model {} of the list is empty", i + 1));
    // Twice the same model would double every row and count every value twice in the statistics.
    for (std::size_t j = 0; j < i; ++j)
      if (names[j] == names[i])
        throw InputError("", 0, "models", fmt::format("model {} is listed twice", shown(names[i])));
  }
}

std::vector<ModelPtr> make_models(const std::vector<std::string>& names, const ModelSettings& settings) {
  check_model_names(names);
  std::vector<ModelPtr> out;
  for (const auto& n : names) out.push_back(make_model(n, settings));
  return out;
}

}  // namespace chutelab::validation
