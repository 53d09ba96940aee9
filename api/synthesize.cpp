#include "api/synthesize.h"

#include "api/effects.h"
#include "api/files.h"
#include "api/record_check.h"
#include "core/option_check.h"
#include "logs/dataset_logs.h"
#include "effects/registry.h"
#include "validation/dataset_output.h"
#include "validation/synthesize.h"

namespace chutelab::api {
namespace {
std::vector<effects::EffectSetting> settings_of(const SynthesizeOptions& o) {
  std::vector<effects::EffectSetting> out;
  for (const auto& e : effects_and_inputs(o.effects, o.inputs, false, o.allow_out_of_range))
    out.push_back(effects::parse_setting(e, false, o.allow_out_of_range));
  return out;
}
}  // namespace

void check(const SynthesizeOptions& o) {
  options::rules::noise_scale.check(o.noise_scale);
  options::rules::noise_factor.check(o.noise_factor);
  options::rules::outliers.check(static_cast<double>(o.outliers));
  settings_of(o);
}

SynthesizeResult synthesize(const SynthesizeOptions& o) {
  check(o);
  const std::filesystem::path dir = o.dataset.empty() ? o.default_dataset : o.dataset;
  return synthesize(logs::read_dataset(dir, validation::MeasurementsRequired::no), o);
}

SynthesizeResult synthesize(validation::Dataset source, const SynthesizeOptions& o) {
  check(o);
  SynthesizeResult res;
  res.source = std::move(source);
  check_records(o.effects, o.inputs, res.source.stations, o.allow_out_of_range);
  if (o.prepare_output) {
    OutputPlan plan;
    plan.inputs = validation::dataset_files(res.source.dir);
    o.prepare_output(plan);
  }
  validation::SynthesizeOptions opt;
  opt.effects = effects::instantiate(settings_of(o));
  opt.seed = o.seed;
  opt.noise_scale = o.noise_scale;
  opt.noise_factor = o.noise_factor;
  opt.outliers = o.outliers;
  opt.out_of_range = o.allow_out_of_range;
  std::vector<validation::ModelPtr> models;
  for (const auto& n : validation::model_names())
    if (auto m = validation::make_model(n); !m->expensive()) models.push_back(m);
  res.files = validation::synthesize(res.source, models, opt);
  return res;
}

}  // namespace chutelab::api

namespace chutelab::api {

validation::Dataset synthesized_dataset(const SynthesizeResult& r, const std::filesystem::path& out) {
  if (!out.empty()) {
    write_dataset(out, r.files, r.source.dir, "synthesize");
    return validation::read_dataset(out);
  }
  validation::DatasetTexts files;
  for (const auto& [name, text] : r.files)
    if (name.ends_with(".csv") || name.ends_with(".toml")) files[name] = {name, text};
  return validation::read_dataset(files, {}, validation::MeasurementsRequired::yes);
}

}  // namespace chutelab::api
