#pragma once
#include <array>
// What the report's sections share: the conditions in display order, how each model is drawn,
// quantity names for headings, look-ups into a ValidationResult, and a table model that renders
// to both HTML and Markdown (so the two reports cannot disagree on a number or a failing cell).
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <tuple>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include "core/quantity.h"
#include "reports/report.h"
#include "reports/svg.h"

namespace chutelab::reports {

struct ConditionRow {
  std::string name;
  const Station* station = nullptr;  // null when the dataset does not list the condition
  std::string speed_label() const;   // "2 m/s" (or "" without a station)
  std::string flow_label() const;    // "26 t/h"
};

struct Context {
  const ReportInput& in;
  // Ordered by belt speed, then mass flow (stable: ties keep the dataset's order), so a trend
  // with either operating variable reads left to right in every table and chart.
  std::vector<ConditionRow> conditions;
  std::vector<std::string> models;  // the baseline's order; styles follow it in every picture
  // A big dataset is summarised: its tables and charts show the kMaxShownConditions conditions of
  // largest misfit (every value stays in the CSVs and the summary statistics); how many were left out.
  std::size_t conditions_left_out = 0;
  std::unordered_map<std::string, std::size_t> slot;  // condition name -> index in `conditions`
  std::string colour(const std::string& model) const;
  Shape shape(const std::string& model) const;
};

// Beyond this many conditions a per-condition table or chart is unreadable (and 10 000 made a
// 120 MB page): the report shows the worst this many and says so.
inline constexpr std::size_t kMaxShownConditions = 60;

Context make_context(const ReportInput& in);

// Width of a chart drawn for one column of a before/after pair, which report.html lays side by
// side: at 1:1 in a column on a 1400 px screen, so its text keeps the size of a full-width chart's.
inline constexpr double kPairChartWidth = 640.0;

inline constexpr std::string_view kMeasuredColour = "#111111";
// Values drawn as colour use bins of a perceptually uniform ramp (viridis, dark = low).
inline constexpr std::array<std::string_view, 8> kRamp = {"#440154", "#46327e", "#365c8d", "#277f8e",
                                                          "#1fa187", "#4ac16d", "#a0da39", "#fde725"};
inline constexpr std::string_view kBandColour = "#dde6d5";

// Headings for a comparison quantity: the six of DESIGN.md §2 and the trajectory boundaries.
struct QuantityName {
  std::string name;    // boundary name, e.g. "normal_force_N"
  std::string symbol;  // "R_n", "y_upper"
  std::string label;   // words
  std::string unit;    // boundary unit
  double scale = 1.0;  // SI -> boundary unit
  std::optional<Quantity> q;
};
QuantityName quantity_name(std::string_view boundary_name);
// Quantities that occur in a result's comparisons, in the vocabulary's order.
std::vector<std::string> compared_quantities(const validation::ValidationResult& r);

// (condition, model, quantity) -> comparisons (several for trajectory points).
class Lookup {
 public:
  explicit Lookup(const validation::ValidationResult& r);
  const validation::Comparison* one(const std::string& condition, const std::string& model,
                                    const std::string& quantity) const;
  const std::vector<const validation::Comparison*>& all(const std::string& condition,
                                                        const std::string& model,
                                                        const std::string& quantity) const;

 private:
  std::map<std::tuple<std::string, std::string, std::string>,
           std::vector<const validation::Comparison*>>
      map_;
  std::vector<const validation::Comparison*> none_;
};

const validation::Measurement* find_measurement(const validation::Dataset& d,
                                                const std::string& condition, Quantity q);

// ---- Tables -----------------------------------------------------------------------------------

struct Cell {
  std::string text{};   // plain text (escaped by the renderer)
  std::string html{};   // optional rich HTML instead of text (already escaped)
  bool fail = false;    // outside tolerance: marked in both renderers
  std::string tip{};    // HTML title / Markdown footnote (e.g. the tolerance limit)
  bool left = false;    // text column (numbers are right-aligned)
  bool strong = false;
  bool beyond = false;  // |E/u_val| > 2: more than the stated uncertainties explain (highlighted)
};

struct Column {
  std::string group{};      // spanning header above (consecutive equal groups merge)
  std::string text{};       // plain header
  std::string html{};       // optional rich header
  bool left = false;
  std::string group_html{}; // optional rich group header
  bool group_in_markdown = true;  // Markdown has no spanning header: prefix the group to the text
};

struct Table {
  std::string id{};
  std::string caption{};              // plain text
  std::vector<Column> columns{};
  std::vector<std::vector<Cell>> rows{};
  std::vector<std::string> notes{};   // plain text lines under the table
  std::size_t key_columns = 1;        // leading columns that name a row (merge_before_after)
};

std::string table_html(const Table& t);
std::string table_markdown(const Table& t);

// One table from the same table before and after adding effects (for report.md, which cannot lay
// them side by side): a column equal in every row of both is kept once, any other becomes a
// "before" and an "after" column. None when the two do not line up (other columns, or rows that
// name something else). `what` says what the labels stand for, in a note under the table.
std::optional<Table> merge_before_after(const Table& before, const Table& after, std::string_view before_label,
                                        std::string_view after_label, std::string_view what);

inline constexpr std::string_view kDash = "\u2014";   // no value
inline constexpr std::string_view kFailMark = "\u2717";  // outside tolerance
inline constexpr std::string_view kBeyondMark = "!";      // |E/u_val| > 2 (report.md)

// ---- Sections' building blocks (one file each) ------------------------------------------------

// plot_plate_map.cpp: "Plate loading and wear" — the models' pressure and wear maps of the plate
// face on shared colour scales, the analytical impact zone on top, and a table per condition.
// Empty when no model gave a map.
struct PlateSection {
  std::string pressure_svg, wear_svg;
  Table table;
  bool empty() const { return pressure_svg.empty(); }
};
PlateSection plate_section(const Context& c, const validation::ValidationResult& r, std::string_view id,
                           double width);

// tables.cpp
Table force_table(const Context& c, const validation::ValidationResult& r, std::string_view id);
Table velocity_table(const Context& c, const validation::ValidationResult& r, std::string_view id);
Table summary_table(const validation::ValidationResult& r, std::string_view id);
Table rms_change_table(const Context& c, const validation::ValidationResult& before,
                       const validation::ValidationResult& after);
Table effects_table(const std::vector<EffectDescription>& effects);
// The physical effects (and pairs) or, with `records`, the recorded inputs tried as candidates.
Table ranking_table(const validation::DiagnosisResult& d, bool records = false);
Table statistics_table(const validation::DiagnosisResult& d);
Table model_notes_table(const Context& c, const validation::ValidationResult& r, std::string_view id);

// vv20_table.cpp: the parts of u_val per prediction, and which parts were not estimated.
Table vv20_table(const Context& c, const validation::ValidationResult& r, std::string_view id);
std::vector<std::string> vv20_not_estimated(const validation::Dataset& d, const validation::ValidationResult& r);

// findings.cpp: the claims this dataset could test, one row each; the rest named in a note.
Table findings_table(const std::vector<validation::ReferenceFinding>& findings);
// Whether any claim could be tested: without one the section does not apply to the rig.
bool any_testable(const std::vector<validation::ReferenceFinding>& findings);


// plot_bars.cpp (`width`, `other`: as residual_chart's)
std::string force_bar_chart(const Context& c, const validation::ValidationResult& r, std::string_view id,
                            double width = 960.0, const validation::ValidationResult* other = nullptr);
std::string rms_bar_chart(const Context& c, const validation::ValidationResult& before,
                          const validation::ValidationResult& after, std::string_view id);
std::string ranking_chart(const validation::DiagnosisResult& d, std::string_view id);

// plot_trajectory.cpp: HTML (a shared legend `legend_width` wide and one SVG panel per condition).
std::string trajectory_grid(const Context& c, const validation::ValidationResult& r, std::string_view id,
                            double legend_width = 980.0);

// plot_residuals.cpp. `other`: the other result of a before/after pair; the chart's panels, range
// and legend then cover both, so two charts side by side line up and compare.
std::string residual_chart(const Context& c, const validation::ValidationResult& r, std::string_view id,
                           double width = 980.0, const validation::ValidationResult* other = nullptr);
// Every E/u before (hollow) and after (filled) adding effects, small panels: for "What is missing".
std::string residual_change_chart(const Context& c, const validation::ValidationResult& before,
                                  const validation::ValidationResult& after, std::string_view id);
// Pearson r of E/u with belt speed and with mass flow per model and quantity.
Table trend_table(const Context& c, const validation::ValidationResult& r, std::string_view id);

}  // namespace chutelab::reports
