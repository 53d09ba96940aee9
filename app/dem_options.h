#pragma once
// The DEM flags that validate and diagnose share (--dem-quality, --dem-threads, --dem-cache,
// --no-dem-cache): both may run "dem" from --models, and a diagnosis after a validate must find
// the validate's runs in the same cache.
#include <optional>
#include <string>

#include <CLI/CLI.hpp>

namespace chutelab::app {

struct DemCli {
  std::string quality, cache;
  std::optional<int> threads;
  bool no_cache = false;
};

void add_dem_options(CLI::App& cmd, DemCli& o);

// Configures the registry's "dem" model for a dataset folder; per-condition output (series, side
// views, VTK) goes under out_dir/dem when out_dir is not empty.
void configure_dem_model(const DemCli& o, const std::string& dataset_dir, const std::string& out_dir);

}  // namespace chutelab::app
