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
  double noise_scale = 1.0;  // multiplies every uncertainty, stated and real
  // The real scatter in units of the stated uncertainty: 2 makes data whose stated uncertainties
  // are half the truth (the stated values do not change).
  double noise_factor = 1.0;
  // Gross reading errors (a transcription slip, a stuck cell): this many readings, chosen at random
  // among the measurements, are off by 8 to 15 stated uncertainties. They come from a stream of
  // their own, so the other readings are those of the same seed without them.
  int outliers = 0;
  // The hidden effects include strengths outside their physical range (for testing only): the
  // dataset's README says so.
  bool out_of_range = false;
};

// Uncertainties: those of the source dataset's measurements where it has them; otherwise 2 % of
// each force (at least 0.2 N), 0.04 m/s for speeds, 2.5 mm for the impact point and 2 mm for
// stream limits (upper, lower, centre every 50 mm from x = 100 mm to 50 mm before the plate).
// The default ones are the instrument's for the value the rig's record predicts (the models
// without the hidden effects), stated to two significant figures and used to draw the noise: they
// carry neither the hidden effect nor the noise, so that weighted fits on the data are unbiased and
// the data stay a blind test. Magnitudes
// (QuantityInfo::magnitude) get noise truncated at zero. Each quantity comes from the first model
// (in the order given) that predicts it.
std::vector<OutputFile> synthesize(const Dataset& source, const std::vector<ModelPtr>& models,
                                   const SynthesizeOptions& options);

// A replica of a dataset's own design in memory: the same conditions, the same measured values and
// trajectory points with their stated uncertainties, read anew from the models with these effects
// plus noise (the diagnosis's self-check, and tests). `truth` (optional, parallel to the design's
// stations) is what the rig really was when it differs from its record (a plate further than
// drawn): the readings come from it, the replica keeps the record. Values without a stated
// uncertainty are dropped (nothing could judge them).
Dataset replica(const Dataset& design, const std::vector<ModelPtr>& models, const SynthesizeOptions& options,
                const std::vector<Station>* truth = nullptr);

// Deterministic standard normal deviates from a 64-bit seed (the same on every platform, unlike
// std::normal_distribution).
class NormalStream {
 public:
  explicit NormalStream(std::uint64_t seed);
  double next();
  double uniform();  // in (0, 1)

 private:
  std::uint64_t state_;
  bool has_spare_ = false;
  double spare_ = 0.0;
};

}  // namespace chutelab::validation
