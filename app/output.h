#pragma once
// How `estimate` shows its answer: a table for people, CSV and JSON for tools.
#include <string>
#include <utility>
#include <vector>

#include "analytical/transfer_station.h"
#include "core/quantity.h"
#include "effects/registry.h"

namespace chutelab::app {

using ModelValues = std::vector<std::pair<std::string, QuantityValues>>;

std::string estimate_table(const analytical::TransferAnalysis& a, const ModelValues& models,
                           const std::vector<effects::EffectSetting>& fx);
std::string estimate_csv(const analytical::TransferAnalysis& a, const ModelValues& models);
std::string estimate_json(const analytical::TransferAnalysis& a, const ModelValues& models,
                          const std::vector<effects::EffectSetting>& fx);

}  // namespace chutelab::app
