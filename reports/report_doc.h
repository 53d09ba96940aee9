#pragma once
// The report as one list of blocks (headings, paragraphs, lists, tables, figures, verdicts, before/after
// pairs), which reports/report_sections.cpp assembles and reports/report.cpp renders twice: report.md
// and report.html. Inside reports/ only.
#include <string>
#include <utility>
#include <vector>

#include "reports/common.h"
#include "reports/report.h"

namespace chutelab::reports {

// Both renderers walk the same list of blocks.
struct Block {
  enum class Kind { heading, paragraph, list, table, figure, verdict, warning, definition, pair } kind{};
  int level = 2;                    // headings
  std::string id{};                 // headings: anchor
  std::string text{};               // plain text (headings, paragraphs, verdict, definition term)
  std::string detail{};             // definition body (plain)
  std::vector<std::string> items{}; // lists (plain)
  Table table{};
  std::string svg_html{};           // figures: ready HTML (inline SVG)
  std::string caption{};            // figures: plain
  std::string after_svg_html{};     // a figure of report.md's merged pair: the "after" column's chart
  // pair: the same blocks for the models as they are and with effects, which report.html shows
  // side by side; `merged` is what report.md shows instead (empty: the two one after the other).
  std::vector<Block> before{}, after{}, merged{};
  bool folded = false;              // level-2 headings: report.html shows the section closed
};

class Doc {
 public:
  void h(int level, std::string id, std::string text) {
    blocks.push_back({Block::Kind::heading, level, std::move(id), std::move(text)});
  }
  void p(std::string text) {
    if (!text.empty()) blocks.push_back({Block::Kind::paragraph, 0, {}, std::move(text)});
  }
  void list(std::vector<std::string> items) {
    if (items.empty()) return;
    Block b{Block::Kind::list};
    b.items = std::move(items);
    blocks.push_back(std::move(b));
  }
  void table(Table t) {
    if (t.rows.empty()) return;
    Block b{Block::Kind::table};
    b.table = std::move(t);
    blocks.push_back(std::move(b));
  }
  void figure(std::string html, std::string caption) {
    Block b{Block::Kind::figure};
    b.svg_html = std::move(html);
    b.caption = std::move(caption);
    blocks.push_back(std::move(b));
  }
  void verdict(std::string text) { blocks.push_back({Block::Kind::verdict, 0, {}, std::move(text)}); }
  void warning(std::string text) {
    if (!text.empty()) blocks.push_back({Block::Kind::warning, 0, {}, std::move(text)});
  }
  // A section whose detail the reader opens when wanted (report.html: a closed <details>).
  void folded_h2(std::string id, std::string text) {
    h(2, std::move(id), std::move(text));
    blocks.back().folded = true;
  }
  // `id`: the HTML element holding both columns.
  void pair(std::string id, Doc before, Doc after, const std::string& after_title);
  void definition(std::string term, std::string body) {
    Block b{Block::Kind::definition};
    b.text = std::move(term);
    b.detail = std::move(body);
    blocks.push_back(std::move(b));
  }
  std::vector<Block> blocks;
};

// The report's blocks in the order it tells the story (docs/DESIGN.md §10). Throws
// std::invalid_argument without a dataset or a baseline.
Doc assemble(const ReportInput& in);

}  // namespace chutelab::reports
