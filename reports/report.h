#pragma once
// The validation report as Markdown and as one self-contained HTML page (inline SVG, no network).
// The report knows no physics: it draws what the harness and the diagnosis give it.
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "reports/log_chart.h"
#include "validation/dataset.h"
#include "validation/diagnosis.h"
#include "validation/harness.h"
#include "validation/reference_findings.h"

namespace chutelab::reports {

// An effect added, in the words of the effect registry (effects/registry.h), which the caller
// looks up: the report reads no registry.
struct EffectDescription {
  std::string name, parameter, unit, physics, source;
  double value = 0.0;                 // boundary unit
  std::optional<double> uncertainty;  // when fitted
  bool fitted = false;
  bool record = false;                // a corrected record of the rig, not physics (EffectInfo::Kind::record)
  std::string check = {};             // the measurement that confirms it ("" = none named)
};

struct StudySection;  // reports/studies.h

struct ReportInput {
  const validation::Dataset* dataset = nullptr;             // required
  const validation::ValidationResult* baseline = nullptr;   // required: models as they are
  const validation::ValidationResult* with_effects = nullptr;  // optional: after adding effects
  std::vector<EffectDescription> effects;                   // what with_effects added
  // The registry's physics paragraph of each effect the diagnosis recommends and with_effects does
  // not add, by name (absent: none said).
  std::map<std::string, std::string> candidate_physics;
  const validation::DiagnosisResult* diagnosis = nullptr;   // optional: "What is missing"
  const std::vector<validation::ReferenceFinding>* findings = nullptr;  // optional: the reference study's findings checked
  std::vector<std::string> notes;                           // provenance of numbers, warnings
  const std::vector<StudySection>* studies = nullptr;       // optional: calibrate / sensitivity sections
  std::vector<LogChart> log_charts;                         // optional: the rig's logs, one chart a condition
  std::vector<std::string> log_lines;                       // optional: what each log gave and said, in words
  // Which result the acceptance judges: the models as delivered (baseline), unless this is set and
  // with_effects exists. The other is reported beside it.
  bool accepted_with_effects = false;
  const validation::ValidationResult& accepted() const {
    return accepted_with_effects && with_effects ? *with_effects : *baseline;
  }
  const validation::ValidationResult* beside_acceptance() const {
    if (!with_effects) return nullptr;
    return accepted_with_effects ? baseline : with_effects;
  }
};

// report.md links each chart as an SVG file beside it, "figures/NN-ID.svg" (NN: the chart's place in
// the report, ID: its element's id); report.html draws them inline. report_files gives all three from
// one assembly: the figures by name relative to the report's folder, in the order they appear.
struct ReportFiles {
  std::string markdown, html;
  std::vector<std::pair<std::string, std::string>> figures;
};
ReportFiles report_files(const ReportInput& in);
std::string report_markdown(const ReportInput& in);  // report_files(in).markdown
std::string report_html(const ReportInput& in);

}  // namespace chutelab::reports
