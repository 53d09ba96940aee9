#pragma once
// How `estimate` shows its answer: a table for people, CSV and JSON for tools.
#include <string>
#include <utility>
#include <vector>

#include "analytical/stream_catch.h"
#include "analytical/transfer_station.h"
#include "core/quantity.h"
#include "effects/registry.h"

namespace chutelab::api {

using ModelValues = std::vector<std::pair<std::string, QuantityValues>>;

// JSON text for a string and a number (non-finite numbers are null).
std::string json_string(const std::string& s);
std::string json_number(double v);

// One flat list of named values in boundary units (names with units): the CSV view and the sweep
// table share it.
std::vector<std::pair<std::string, double>> estimate_scalars(const analytical::TransferAnalysis& a);
// "" when the whole stream meets the plate; else how much passes over the top edge or falls past
// the foot and the forces of the part the plate takes (estimate's table and JSON, sweeps' notes).
std::string stream_miss_note(const analytical::StreamCatch& c);

std::string estimate_table(const analytical::TransferAnalysis& a, const ModelValues& models,
                           const std::vector<effects::EffectSetting>& fx);
std::string estimate_csv(const analytical::TransferAnalysis& a, const ModelValues& models);
// The streamlines' points (analytical/streamline_path.h) as CSV: condition,streamline,point,x_mm,y_mm.
std::string streamline_points_csv(const analytical::TransferAnalysis& a);
std::string estimate_json(const analytical::TransferAnalysis& a, const ModelValues& models,
                          const std::vector<effects::EffectSetting>& fx);

}  // namespace chutelab::api
