#pragma once
// Synthetic measurements for testing: the models plus any effects plus Gaussian noise at stated
// uncertainties, written in the dataset format. The effects leave no trace in the files.
#include <cstdint>
#include <string>
#include <vector>

#include "validation/dataset.h"
#include "validation/model.h"
#include "validation/output_files.h"

namespace chutelab::validation {

struct SynthesizeOptions {
  analytical::EffectList effects;
  std::uint64_t seed = 1;
  double noise_scale = 1.0;  // multiplies every uncertainty
};

// Uncertainties: those of the source dataset's measurements where it has them; otherwise 2 % of
// each force (at least 0.2 N), 0.04 m/s for speeds, 2.5 mm for the impact point and 2 mm for
// stream limits (upper, lower, centre every 50 mm from x = 100 mm to 50 mm before the plate).
// The noise is drawn with the uncertainty of the true value; the stated uncertainty is that of the
// written value, to two significant figures, so it says nothing the value does not. Magnitudes
// (QuantityInfo::magnitude) get noise truncated at zero. Each quantity comes from the first model
// (in the order given) that predicts it.
std::vector<OutputFile> synthesize(const Dataset& source, const std::vector<ModelPtr>& models,
                                   const SynthesizeOptions& options);

// Deterministic standard normal deviates from a 64-bit seed (the same on every platform, unlike
// std::normal_distribution).
class NormalStream {
 public:
  explicit NormalStream(std::uint64_t seed);
  double next();

 private:
  std::uint64_t state_;
  bool has_spare_ = false;
  double spare_ = 0.0;
  double uniform();
};

}  // namespace chutelab::validation
