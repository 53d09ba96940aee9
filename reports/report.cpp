// The report rendered twice from one list of blocks (reports/report_doc.h): Markdown for diffs and
// terminals, HTML with inline SVG for reading and printing, and every chart as a file of its own.
// Sections and tables come from the same builders, so the two files never disagree. No clock, no
// random ids, no locale: same inputs, same bytes.
#include "reports/report.h"

#include <algorithm>
#include <cctype>
#include <fmt/format.h>
#include <map>

#include "reports/common.h"
#include "reports/report_doc.h"

namespace chutelab::reports {
namespace {

// report.md cannot put two tables side by side: a pair becomes one table per table with before and
// after columns, one line per figure and the rest once where both say the same. Empty when the
// two columns do not line up (then both are shown, one after the other).
std::vector<Block> merge_for_markdown(const std::vector<Block>& before, const std::vector<Block>& after,
                                      const std::string& after_title) {
  if (before.size() != after.size()) return {};
  std::vector<Block> out;
  for (std::size_t k = 0; k < before.size(); ++k) {
    const Block &b = before[k], &a = after[k];
    if (b.kind != a.kind) return {};
    switch (b.kind) {
      case Block::Kind::heading: break;  // the columns' titles: the merged columns say before/after
      case Block::Kind::table: {
        std::string after_what = after_title;
        if (!after_what.empty() && after_what[0] >= 'A' && after_what[0] <= 'Z') after_what[0] += 'a' - 'A';
        auto t = merge_before_after(b.table, a.table, "before", "after",
                                    "\"before\": the models as they are; \"after\": " + after_what);
        if (!t) return {};
        out.push_back(b);
        out.back().table = std::move(*t);
        break;
      }
      case Block::Kind::figure: {
        std::string what = b.caption.empty() ? std::string("Chart") : b.caption;
        if (what.ends_with('.')) what.pop_back();
        out.push_back(b);
        out.back().caption = what + " — before and after";
        out.back().after_svg_html = a.svg_html;
        break;
      }
      default:
        if (b.text != a.text || b.items != a.items || b.detail != a.detail) return {};
        out.push_back(b);
    }
  }
  return out;
}

}  // namespace

void Doc::pair(std::string id, Doc before, Doc after, const std::string& after_title) {
  Block b{Block::Kind::pair};
  b.id = std::move(id);
  b.merged = merge_for_markdown(before.blocks, after.blocks, after_title);
  b.before = std::move(before.blocks);
  b.after = std::move(after.blocks);
  blocks.push_back(std::move(b));
}

namespace {

constexpr std::string_view kCss = R"(
:root { --ink:#1b1b1b; --muted:#5a5a5a; --rule:#d0d0d0; --fail:#fbd5d5; --failink:#8e1b1b; }
* { box-sizing: border-box; }
body { margin: 0; color: var(--ink); background: #fff;
  font: 14px/1.45 system-ui, -apple-system, "Segoe UI", Roboto, "Helvetica Neue", Arial, sans-serif; }
main { max-width: 1100px; margin: 0 auto; padding: 24px 20px 60px; }
h1 { font-size: 24px; margin: 0 0 10px; }
h2 { font-size: 19px; margin: 34px 0 10px; padding-bottom: 4px; border-bottom: 2px solid var(--ink); }
h3 { font-size: 15px; margin: 22px 0 8px; }
ul { padding-left: 22px; }
nav.toc { font-size: 13px; margin: 10px 0 0; }
nav.toc a { margin-right: 14px; color: #0b5394; text-decoration: none; }
.meta { list-style: none; padding: 0; margin: 0 0 8px; color: var(--muted); }
.verdict { font-weight: 600; font-size: 15px; border-left: 4px solid #D55E00; padding: 8px 12px; background: #fff4ec; }
.warning { border-left: 4px solid #b00020; padding: 6px 12px; background: #fdecee; }
details.fold > summary { cursor: pointer; list-style-position: outside; }
details.fold > summary h2 { display: inline-block; width: calc(100% - 24px); }
dl.effect { margin: 8px 0; } dl.effect dt { font-weight: 600; } dl.effect dd { margin: 2px 0 8px 18px; }
.table-wrap { overflow-x: auto; margin: 8px 0; }
table.data { border-collapse: collapse; font-size: 12.5px; font-variant-numeric: tabular-nums; }
table.data caption { text-align: left; font-weight: 600; padding: 2px 0 6px; }
table.data th, table.data td { padding: 3px 5px; border-bottom: 1px solid var(--rule); white-space: nowrap; }
table.data th { background: #f1f1f1; font-weight: 600; text-align: right; vertical-align: bottom; white-space: normal; }
table.data tr.group th { text-align: center; border-bottom: 1px solid #999; background: #e7e7e7; }
table.data td.num { text-align: right; }
table.data td.left, table.data th.left { text-align: left; white-space: normal; }
table.data td.fail { background: var(--fail); color: var(--failink); }
table.data td.beyond { background: #fff1c9; }
table.data td .mark { font-weight: 700; }
table.data td .u { color: var(--muted); font-size: 11px; }
.table-note { font-size: 12px; color: var(--muted); margin: 2px 0 8px; }
figure { margin: 12px 0 18px; }
figcaption { font-size: 12px; color: var(--muted); margin-top: 4px; }
svg.plot { display: block; max-width: 100%; height: auto; font-family: inherit; background: #fff; }
svg.plot text { font-family: inherit; fill: #1b1b1b; }
.traj-grid { display: flex; flex-wrap: wrap; gap: 10px 14px; align-items: flex-start; }
.traj-grid svg.plot { flex: 0 1 auto; }
/* Before and after adding effects side by side, the pair wider than the text (centred on it) so
   that each column holds a chart drawn for it at full size; one under the other where two columns
   would not fit. */
.before-after { display: grid; grid-template-columns: minmax(0, 1fr) minmax(0, 1fr); gap: 0 28px;
  align-items: start; width: min(1800px, calc(100vw - 48px));
  margin-left: calc((100% - min(1800px, calc(100vw - 48px))) / 2); }
.ba-col { min-width: 0; }
.ba-col > h3:first-child { margin-top: 10px; padding-bottom: 3px; border-bottom: 1px solid var(--rule); }
/* Half the width for the same tables: tighter cells, a measurement's sd under its value. */
.before-after table.data { font-size: 11.5px; }
.before-after table.data th, .before-after table.data td { padding: 3px 4px; }
.before-after table.data td .u { display: block; line-height: 1.1; }
.before-after table.data td.left:first-child { white-space: nowrap; }
/* A table wider than its column scrolls; the row's name stays in view. */
.before-after table.data td:first-child { position: sticky; left: 0; background: #fff; }
.before-after table.data th:first-child { position: sticky; left: 0; }
@media (max-width: 1199px) { .before-after { display: block; width: auto; margin-left: 0; } }
@media (max-width: 1799px) { .before-after.wide { display: block; } }
/* A narrow window still shows Table 5 whole: smaller cells rather than a scroll bar. */
@media (max-width: 999px) {
  table.data, .before-after table.data { font-size: 11px; }
  table.data th, table.data td, .before-after table.data th, .before-after table.data td { padding: 2px 3px; }
}
footer { margin-top: 40px; font-size: 12px; color: var(--muted); }
@media print {
  .before-after { display: block; width: auto; margin-left: 0; }
  body { font-size: 11px; } main { max-width: none; padding: 0; }
  nav.toc { display: none; }
  h2 { break-after: avoid; } figure, .table-wrap, svg.plot { break-inside: avoid; }
  table.data td.fail, table.data td.beyond { -webkit-print-color-adjust: exact; print-color-adjust: exact; }
}
)";

// Columns of a table that still fit one column of a before/after pair on a 1400 px window
// (report.html's cells are 50-65 px wide at the pair's font size).
constexpr std::size_t kColumnsInHalf = 11;

// Every block but the page's own headings (levels 1 and 2, which open the header and the sections).
std::string block_html(const Block& b, bool in_header) {
  std::string o;
  switch (b.kind) {
    case Block::Kind::heading: o += fmt::format("<h{0} id=\"{1}\">{2}</h{0}>\n", b.level, esc(b.id), esc(b.text)); break;
    case Block::Kind::paragraph: o += fmt::format("<p>{}</p>\n", esc(b.text)); break;
    case Block::Kind::verdict: o += fmt::format("<p class=\"verdict\">{}</p>\n", esc(b.text)); break;
    case Block::Kind::warning: o += fmt::format("<p class=\"warning\">{}</p>\n", esc(b.text)); break;
    case Block::Kind::list:
      o += in_header ? "<ul class=\"meta\">\n" : "<ul>\n";
      for (const auto& i : b.items) o += fmt::format("<li>{}</li>\n", esc(i));
      o += "</ul>\n";
      break;
    case Block::Kind::definition:
      o += fmt::format("<dl class=\"effect\"><dt>{}</dt><dd>{}</dd></dl>\n", esc(b.text), esc(b.detail));
      break;
    case Block::Kind::table: o += table_html(b.table); break;
    case Block::Kind::figure:
      if (b.svg_html.starts_with("<figure")) o += b.svg_html;  // a figure of its own (trajectory grid)
      else {
        o += "<figure>\n" + b.svg_html;
        if (!b.caption.empty()) o += fmt::format("<figcaption>{}</figcaption>\n", esc(b.caption));
        o += "</figure>\n";
      }
      break;
    case Block::Kind::pair: {
      // A table of many columns does not fit half of a 1400 px window: such a pair stacks its two
      // columns until the window is wide enough for them side by side.
      std::size_t columns = 0;
      for (const auto* side : {&b.before, &b.after})
        for (const auto& x : *side)
          if (x.kind == Block::Kind::table) columns = std::max(columns, x.table.columns.size());
      o += fmt::format("<div class=\"before-after{}\" id=\"{}\">\n", columns > kColumnsInHalf ? " wide" : "",
                       esc(b.id));
      for (const auto* side : {&b.before, &b.after}) {
        o += fmt::format("<div class=\"ba-col ba-{}\">\n", side == &b.before ? "before" : "after");
        for (const auto& x : *side) o += block_html(x, false);
        o += "</div>\n";
      }
      o += "</div>\n";
      break;
    }
  }
  return o;
}

// ---- The charts as files: report.html keeps them inline, report.md links figures/NN-ID.svg ----

// The figure's name: the id of its first element (the figure's, or its first chart's), letters,
// digits, '-' and '_' kept.
std::string figure_id(std::string_view html) {
  const auto at = html.find("id=\"");
  std::string id = at == std::string_view::npos ? std::string("figure")
                                                : std::string(html.substr(at + 4, html.find('"', at + 4) - at - 4));
  for (auto& ch : id)
    if (!std::isalnum(static_cast<unsigned char>(ch)) && ch != '-' && ch != '_') ch = '-';
  return id;
}

// Every figure of the document as a file, numbered in the order report.html shows them; the name
// report.md links for each chart.
struct Figures {
  std::vector<std::pair<std::string, std::string>> files;  // "figures/01-resid-base.svg", its SVG
  std::map<std::string, std::string> name;                  // figure_id -> file name
};

void collect_figures(const std::vector<Block>& blocks, Figures& f) {
  for (const auto& b : blocks) {
    if (b.kind == Block::Kind::pair) {
      collect_figures(b.before, f);
      collect_figures(b.after, f);
    }
    if (b.kind != Block::Kind::figure) continue;
    const std::string id = figure_id(b.svg_html);
    if (f.name.count(id)) continue;
    std::string svg = svg_file(b.svg_html, b.caption);
    if (svg.empty()) continue;
    const std::string file = fmt::format("figures/{:02d}-{}.svg", f.files.size() + 1, id);
    f.name[id] = file;
    f.files.emplace_back(file, std::move(svg));
  }
}

std::string render_html(const Doc& d, const ReportInput& in) {
  std::string o = "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
                  "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n";
  o += fmt::format("<title>chutelab validation: {}</title>\n<style>{}</style>\n</head>\n<body>\n<main>\n",
                   esc(in.baseline->dataset_folder.empty() ? in.baseline->dataset_name : in.baseline->dataset_folder),
                   kCss);
  // Contents from the level-2 headings.
  std::string toc;
  for (const auto& b : d.blocks)
    if (b.kind == Block::Kind::heading && b.level == 2)
      toc += fmt::format("<a href=\"#{}\">{}</a>", esc(b.id), esc(b.text));
  bool toc_done = false;
  bool in_section = false, in_fold = false;
  for (const auto& b : d.blocks) {
    if (b.kind == Block::Kind::heading && b.level == 2) {
      if (!toc_done) {
        o += fmt::format("<nav class=\"toc\">{}</nav>\n</header>\n", toc);
        toc_done = true;
      }
      if (in_fold) o += "</details>\n";
      if (in_section) o += "</section>\n";
      if (b.folded)
        o += fmt::format("<section id=\"{}\">\n<details class=\"fold\"><summary><h2>{}</h2></summary>\n", esc(b.id),
                         esc(b.text));
      else o += fmt::format("<section id=\"{}\">\n<h2>{}</h2>\n", esc(b.id), esc(b.text));
      in_section = true;
      in_fold = b.folded;
    } else if (b.kind == Block::Kind::heading && b.level == 1) {
      o += fmt::format("<header>\n<h1 id=\"{}\">{}</h1>\n", esc(b.id), esc(b.text));
    } else {
      o += block_html(b, !toc_done);
    }
  }
  if (!toc_done) o += "</header>\n";
  if (in_fold) o += "</details>\n";
  if (in_section) o += "</section>\n";
  o += "<footer>Written by chutelab. E = predicted − measured (ASME V&amp;V 20 sign); u_val = the validation "
       "uncertainty of V&amp;V 20 (measurement, numerical and input uncertainties combined). Values outside "
       "tolerance: red, marked ✗, the limit in the tooltip; values more than 2 u_val off: amber."
       "</footer>\n</main>\n</body>\n</html>\n";
  return o;
}

std::string blocks_markdown(const std::vector<Block>& blocks, const Figures& figures) {
  std::string o;
  for (const auto& b : blocks) {
    switch (b.kind) {
      case Block::Kind::heading:
        o += fmt::format("{} {}\n\n", std::string(static_cast<std::size_t>(b.level), '#'), md_esc(b.text));
        break;
      case Block::Kind::paragraph: o += md_esc(b.text) + "\n\n"; break;
      case Block::Kind::verdict: o += "**" + md_esc(b.text) + "**\n\n"; break;
      case Block::Kind::warning: o += "**Warning:** " + md_esc(b.text) + "\n\n"; break;
      case Block::Kind::list:
        for (const auto& i : b.items) o += "- " + md_esc(i) + "\n";
        o += "\n";
        break;
      case Block::Kind::definition: o += fmt::format("**{}**: {}\n\n", md_esc(b.text), md_esc(b.detail)); break;
      case Block::Kind::table: o += table_markdown(b.table); break;
      case Block::Kind::figure: {
        // The chart as the file written beside report.md, its caption under it.
        const std::string what = b.caption.empty() ? "Chart" : b.caption;
        std::string links;
        for (const auto* svg : {&b.svg_html, &b.after_svg_html}) {
          if (svg->empty()) continue;
          const auto it = figures.name.find(figure_id(*svg));
          if (it == figures.name.end()) continue;
          const std::string alt = b.after_svg_html.empty() ? shorten(what, 80) : svg == &b.svg_html ? "before" : "after";
          links += fmt::format("{}![{}]({})", links.empty() ? "" : " ", md_esc(alt), it->second);
        }
        if (links.empty()) o += fmt::format("*{} (in report.html)*\n\n", md_esc(what));
        else o += fmt::format("{}\n\n*{}*\n\n", links, md_esc(what));
        break;
      }
      case Block::Kind::pair:
        if (!b.merged.empty()) o += blocks_markdown(b.merged, figures);
        else o += blocks_markdown(b.before, figures) + blocks_markdown(b.after, figures);
        break;
    }
  }
  return o;
}

}  // namespace

ReportFiles report_files(const ReportInput& in) {
  const Doc d = assemble(in);
  ReportFiles out;
  Figures figures;
  collect_figures(d.blocks, figures);
  out.markdown = blocks_markdown(d.blocks, figures);
  out.html = render_html(d, in);
  out.figures = std::move(figures.files);
  return out;
}

std::string report_markdown(const ReportInput& in) { return report_files(in).markdown; }

std::string report_html(const ReportInput& in) { return render_html(assemble(in), in); }

}  // namespace chutelab::reports
