#pragma once
// An expensive model's own responses to one effect, one per condition, read together. A DEM probe
// run is short (the signature quality) and its window can catch a fluctuation of the feed that
// moves a force by many times what the effect does; its own standard error says so. Taken alone,
// that one difference would be read as exact and drag a fitted strength (bench/log/PEER_DIAGNOSIS.md,
// 2026-12-07). Read together, the responses of one quantity across conditions share a shape, the
// cheap models' response scaled by a factor the precise probes fix, and each response is the
// precision-weighted mean of its own value and that shape (a random-effects model, its spread about
// the shape estimated as Paule and Mandel do in meta-analysis): a precise probe keeps its own
// response whatever the shape says, a probe whose noise exceeds that spread moves toward the shape.
#include <optional>
#include <span>
#include <vector>

namespace chutelab::validation {

struct PooledResponse {
  std::vector<double> response;  // per entry: the response read together with the others
  double scale = 0.0;            // the factor on the shape (where the cheap models respond nowhere: the common response)
  double spread = 0.0;           // sd of the own responses about the scaled shape, beyond their noise
  bool pooled = false;           // false: each response kept as it is (too few, or none noisy)
};

// `own`: the own responses (probe minus base); `sd`: their standard errors (0: exact or not
// stated); `shape`: the cheap models' response at the same strength (absent: none predicted there).
PooledResponse pool_responses(std::span<const double> own, std::span<const double> sd,
                              std::span<const std::optional<double>> shape);

}  // namespace chutelab::validation
