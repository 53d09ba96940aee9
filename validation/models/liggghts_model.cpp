#include "validation/models/liggghts_model.h"

#include <filesystem>
#include <fstream>

#include <fmt/format.h>

#include "core/file_name.h"
#include "core/rig_needs.h"
#include "core/message.h"
#include "dem/liggghts/run.h"
#include "dem/station/cache.h"
#include "dem/station/progress.h"

namespace chutelab::validation {
namespace {

namespace st = dem::station;
namespace lg = dem::liggghts;

class LiggghtsModel final : public Model {
 public:
  explicit LiggghtsModel(LiggghtsModelConfig c) : c_(std::move(c)) {}
  std::string name() const override { return "liggghts"; }
  std::string description() const override {
    return "LIGGGHTS-PUBLIC run of chutelab's station deck (Hertz-Mindlin, cdt rolling friction), measured by "
           "chutelab's sensors";
  }
  bool expensive() const override { return true; }

  ModelPrediction predict(const Station& station, const analytical::EffectList& effects,
                          const PredictRequest& request) const override {
    namespace fs = std::filesystem;
    const DemModelConfig& dc = c_.dem;
    require_dem_keys(station, dc.setup_file.empty() ? std::string("setup.toml") : dc.setup_file, "LIGGGHTS");
    const st::DemTable& table = dc.dem_table();
    lg::Options o;
    o.settings = st::resolve(table, dc.overrides);
    o.geometry = table;
    o.ranks = c_.ranks;
    o.command = c_.command;
    o.sim_time = c_.sim_time;
    DemEffectInputs fx = dem_effect_inputs(station, effects);
    std::vector<std::string> ignored;
    if (!fx.external.flight_key.empty()) ignored.push_back("the body force in flight");
    if (fx.external.belt_adhesive_stress > 0.0) ignored.push_back("the belt adhesion");
    fx.external.flight = {};
    fx.external.flight_key.clear();
    fx.external.belt_adhesive_stress = 0.0;
    o.external = fx.external;

    // The key: the deck and its meshes are the run; the rest is what chutelab does with its output.
    const lg::Deck deck = lg::deck_for(fx.station, o);
    const std::string launcher = lg::launcher(o);
    const std::string ver = lg::version(lg::program_of(launcher));
    std::string key = fmt::format("{}\n{}\nliggghts {}\nlauncher {}\n", st::kStationModelVersion,
                                  lg::kLiggghtsEngineVersion, ver.empty() ? "(not found)" : ver, launcher);
    key += st::canonical(o.settings);
    key += fmt::format("sim_time = {:.17g}\n", o.sim_time);
    key += "deck\n" + deck.input;
    for (const auto& [file, text] : deck.files) key += fmt::format("mesh {} {:016x}\n", file, st::fnv1a64(text));
    key += fx.key;

    const st::ResultCache cache(dc.cache_dir.empty() ? st::ResultCache::default_dir() : dc.cache_dir);
    st::CacheEntry entry = dc.use_cache ? cache.lookup(key) : st::CacheEntry{};
    std::optional<st::StationResult>& cached = entry.result;
    std::string unwritten = dc.use_cache ? "" : "the cache is off";
    if (entry.refused)
      warn(fmt::format("DEM cache entry refused, running condition {} in LIGGGHTS again: {}", station.condition,
                       entry.said()));
    st::StationResult r;
    if (cached) {
      r = std::move(*cached);
    } else {
      // The run's folder beside the cache file: deck, meshes, log and plate series stay as the
      // record of the run; the particle dump (large) goes once it is measured.
      const fs::path work = fs::path(cache.path_for(key)).replace_extension(".liggghts");
      o.work_dir = work.string();
      if (dc.progress) o.progress = st::ProgressPrinter(fmt::format("liggghts {}", station.condition));
      r = lg::run_station(fx.station, o);
      std::error_code ec;
      fs::remove(work / lg::Deck::dump_file, ec);
      if (dc.use_cache)
        if (const st::CacheWrite w = cache.store(key, r); !w) {
          unwritten = w.problem;
          warn(fmt::format("LIGGGHTS run of condition {} not cached: {}", station.condition, w.problem));
        }
    }
    if (!dc.output_dir.empty()) {
      const auto dir = fs::path(dc.output_dir) / "liggghts" / file_name_for(station.condition);
      st::write_result_files(dir.string(), r);
      st::write_side_view_vtk((dir / "side_view.vtk").string(), r.side_view);
      lg::write_deck(deck, dir.string());
    }
    ModelPrediction p = dem_station_prediction(r, fx, request);
    if (!ignored.empty())
      p.notes.push_back(fmt::format("not written to the LIGGGHTS deck: {}", fmt::join(ignored, ", ")));
    if (entry.refused) p.notes.push_back(fmt::format("DEM cache entry refused and run again: {}", entry.said()));
    p.notes.push_back(cached ? fmt::format("from the DEM cache ({})", cache.path_for(key))
                      : unwritten.empty()
                          ? fmt::format("LIGGGHTS run of {:.0f} s wall time, cached as {}", r.wall_seconds, cache.path_for(key))
                          : fmt::format("LIGGGHTS run of {:.0f} s wall time, not cached ({})", r.wall_seconds, unwritten));
    return p;
  }

 private:
  LiggghtsModelConfig c_;
};

}  // namespace

ModelPtr make_liggghts_model(const LiggghtsModelConfig& c) { return std::make_shared<LiggghtsModel>(c); }

}  // namespace chutelab::validation
