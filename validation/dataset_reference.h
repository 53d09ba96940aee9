#pragma once
// The dataset reference (docs/dataset-reference.md) and `chutelab init`'s skeleton, written from the
// readers' own tables: the CSV columns (validation/dataset_fields.h), the setup's keys (core/rig.h),
// the [dem.wear] keys (dem/station/settings.h) and the tolerance limits (validation/tolerances.h).
#include <string>
#include <vector>

#include "core/rig.h"
#include "validation/output_files.h"

namespace chutelab::validation {

// The whole reference as Markdown (docs/dataset-reference.md is this text, checked by a test).
std::string dataset_reference_markdown();

// A minimal dataset that validates, every line commented, with `example`'s rig (the reference
// study's, as bundled) and five conditions: setup.toml, conditions.csv, measurements.csv,
// README.md. The measured values are placeholders of the right size, to be replaced.
std::vector<OutputFile> dataset_skeleton(const Setup& example);

}  // namespace chutelab::validation
