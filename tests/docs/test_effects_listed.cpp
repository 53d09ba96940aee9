// docs/models.md's effect tables against the registry (effects::library()): every registered effect
// has one row, in the table of its kind (physics first, records second), with its physical range and
// its stage as registered; every row names a registered effect. A new effect without its row, or a
// row left behind by a removed one, fails here, so the page cannot again speak of "a ninth effect"
// beside eighteen.
#define BOOST_TEST_MODULE docs_effects
#include <boost/test/unit_test.hpp>
#include <fmt/format.h>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "effects/registry.h"

using namespace chutelab;

namespace {

struct Row {
  int table = 0;  // 0: the first table of the section (physics), 1: the second (records)
  std::string name, range, hook;
};

// The rows of the tables in the "## Effect library" section whose first cell is `name` in backticks.
std::vector<Row> effect_rows(const std::string& page) {
  std::vector<Row> rows;
  std::istringstream in(page);
  std::string line;
  bool inside = false, in_table = false;
  int table = -1;
  static const std::regex row(R"(^\| `([a-z_]+)` \|[^|]*\| ([^|]*) \| ([^|]*) \|.*)");
  while (std::getline(in, line)) {
    if (line.rfind("## ", 0) == 0) inside = line == "## Effect library";
    if (!inside) continue;
    const bool table_line = line.rfind("|", 0) == 0;
    if (table_line && !in_table) ++table;
    in_table = table_line;
    std::smatch m;
    if (std::regex_match(line, m, row)) rows.push_back({table, m[1], m[2], m[3]});
  }
  return rows;
}

// "−0.2–0.5" (a minus sign, an en dash) as the page writes a range.
std::string range_text(double lower, double upper) {
  auto num = [](double v) {
    std::string s = fmt::format("{}", v < 0 ? -v : v);
    return (v < 0 ? std::string("\u2212") : std::string()) + s;
  };
  return num(lower) + "\u2013" + num(upper);
}

// Every problem between the page's rows and the registry, one sentence each.
std::vector<std::string> problems(const std::string& page) {
  std::vector<std::string> out;
  std::map<std::string, int> seen;
  for (const auto& r : effect_rows(page)) {
    ++seen[r.name];
    const effects::EffectInfo* e = effects::find(r.name);
    if (!e) {
      out.push_back("row for unregistered effect " + r.name);
      continue;
    }
    const int table = e->kind == effects::EffectInfo::Kind::physics ? 0 : 1;
    if (r.table != table) out.push_back(r.name + " is in the wrong table");
    if (r.range != range_text(e->lower, e->upper))
      out.push_back(r.name + ": range " + r.range + ", registered " + range_text(e->lower, e->upper));
    if (r.hook != e->stage) out.push_back(r.name + ": hook " + r.hook + ", registered " + e->stage);
  }
  for (const auto& e : effects::library()) {
    if (!seen.count(e.name)) out.push_back("no row for " + e.name);
    else if (seen[e.name] > 1) out.push_back("more than one row for " + e.name);
  }
  return out;
}

std::string read(const std::string& path) {
  std::ifstream f(path);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

}  // namespace

BOOST_AUTO_TEST_CASE(models_md_lists_every_registered_effect) {
  const std::string page = read(CHUTELAB_SOURCE_DIR "/docs/models.md");
  BOOST_REQUIRE(!page.empty());
  BOOST_TEST(effect_rows(page).size() == effects::library().size());
  for (const auto& p : problems(page)) BOOST_ERROR(p);
}

// The check itself fails where it should: a row dropped, a range changed, a row moved to the other
// table and a row for an effect that does not exist are each found.
BOOST_AUTO_TEST_CASE(the_check_finds_planted_problems) {
  const std::string page = read(CHUTELAB_SOURCE_DIR "/docs/models.md");
  auto planted = [&](const std::string& from, const std::string& to) {
    std::string p = page;
    const auto at = p.find(from);
    BOOST_REQUIRE(at != std::string::npos);
    p.replace(at, from.size(), to);
    return problems(p);
  };
  BOOST_TEST(planted("| `air_drag` |", "| air drag |").size() == 1u);              // no row
  BOOST_TEST(planted("| 0–1.5 | flight |", "| 0–2 | flight |").size() == 1u);    // a range
  BOOST_TEST(planted("| `belt_slip` |", "| `belt_slop` |").size() == 2u);         // unknown, and no row
  BOOST_TEST(planted("Records (the strength", "Records\n\n| x |\n\n(the strength").size() >= 13u);  // table shift
}
