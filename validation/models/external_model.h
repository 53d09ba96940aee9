#pragma once
// Another code's results as a model: `--models external:NAME=DIR` (DESIGN.md §6). DIR holds the
// predictions of EDEM, Rocky, LIGGGHTS or a spreadsheet in the dataset's vocabulary:
//   DIR/predictions.csv  condition,quantity,value,uncertainty   (as a dataset's measurements.csv)
//   DIR/trajectory.csv   condition,boundary,x_mm,y_mm,uncertainty_mm   (optional)
//   DIR/README.md        which code made them, how (provenance; required)
// The model is called NAME in every output. Files are read as strictly as a dataset's (one
// InputError naming file, line and field); every condition must be one of the dataset's
// (check_conditions, before anything runs).
//
// It is an expensive model that cannot be re-run: its values are the same whatever effect is
// asked for. The diagnosis therefore always takes its effect signatures from the analytical
// models (DESIGN.md §5) and says so; the instrument's effects (load_cell_offset, ...) are applied
// by the harness as to any model's values.
#include <filesystem>
#include <string>
#include <vector>

#include "validation/dataset.h"
#include "validation/model.h"

namespace chutelab::validation {

class ExternalModel final : public Model {
 public:
  // spec = "NAME=DIR" (after "external:"). Throws InputError (field --models or the file's).
  explicit ExternalModel(const std::string& spec);
  std::string name() const override { return name_; }
  std::string description() const override { return description_; }
  bool expensive() const override { return true; }
  bool runs_with_effects() const override { return false; }
  ModelPrediction predict(const Station& station, const analytical::EffectList& effects,
                          const PredictRequest& request) const override;
  // Throws InputError at the first row whose condition is not one of the dataset's.
  void check_conditions(const Dataset& d) const;
  const std::filesystem::path& dir() const { return dir_; }

 private:
  std::string name_, description_;
  std::filesystem::path dir_;
  std::vector<Measurement> values_;
  std::vector<TrajectoryPoint> trajectory_;
};

// "external:NAME=DIR" entries of --models.
inline constexpr std::string_view kExternalPrefix = "external:";

// check_conditions of every external model among `models`.
void check_external_models(const std::vector<ModelPtr>& models, const Dataset& d);

}  // namespace chutelab::validation
