#pragma once
// The sensitivity study (studies/sensitivity.h) drawn for people: the page `chutelab sensitivity`
// writes (Markdown and HTML) and the chart the report's section shares (reports/studies.cpp).
#include <string>
#include <string_view>

#include "studies/sensitivity.h"

namespace chutelab::reports {

// "grima2010 (path)" — which dataset the study ran on, as the outputs name it.
std::string dataset_text(const studies::SensitivityStudy& s, bool markdown);
// The chart of sensitivity_html: mean R with its standard error and the fluctuation, per variant.
std::string sensitivity_chart(const studies::SensitivityStudy& s, std::string_view id);
std::string sensitivity_md(const studies::SensitivityStudy& s);
std::string sensitivity_html(const studies::SensitivityStudy& s);
// The chart as an SVG file of its own, sensitivity.svg, which sensitivity.md links.
std::string sensitivity_svg(const studies::SensitivityStudy& s);

}  // namespace chutelab::reports
