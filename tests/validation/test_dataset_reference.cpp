// The dataset reference (docs/dataset-reference.md) is the readers' own tables: the page is what
// `chutelab init --reference` prints, and a dataset holding every field the page lists is read with
// every value taken and nothing warned about; a required column left out is refused by name, an
// optional one is not missed. `chutelab init` writes a dataset that validates; a wide table's message
// shows the long layout; a value without uncertainty is warned about.
#include <boost/test/unit_test.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <regex>
#include <set>
#include <sstream>

#include <fmt/format.h>

#include "../cli/cli_runner.h"
#include "core/input_error.h"
#include "core/rig.h"
#include "validation/dataset.h"
#include "validation/dataset_fields.h"
#include "validation/dataset_reference.h"

namespace fs = std::filesystem;
using namespace chutelab;
using namespace chutelab::validation;

namespace {

const fs::path kSource(CHUTELAB_SOURCE_DIR);

// What the code under test printed on stderr (warnings go there, core/message.h).
struct Stderr {
  std::stringstream text;
  std::streambuf* old;
  Stderr() : old(std::cerr.rdbuf(text.rdbuf())) {}
  ~Stderr() { std::cerr.rdbuf(old); }
  std::string str() const { return text.str(); }
};

// The skeleton `chutelab init` writes, in a fresh folder.
fs::path skeleton(const std::string& name) {
  const fs::path d = test::fresh_dir(name);
  for (const auto& [file, text] : dataset_skeleton(read_setup(kSource / "datasets/grima2010/setup.toml")))
    test::write_file(d / file, text);
  return d;
}

// A CSV of one example row holding the given columns (the tables' own examples), for condition V2-26.
std::string csv_of(std::span<const ColumnSpec> columns, const std::set<std::string_view>& leave_out = {}) {
  std::vector<std::string> head, row;
  for (const auto& c : columns) {
    if (leave_out.count(c.name)) continue;
    head.emplace_back(c.name);
    row.emplace_back(c.example);
  }
  return fmt::format("{}\n{}\n", fmt::join(head, ","), fmt::join(row, ","));
}

// The backquoted names in the rows of the Markdown table that follows `heading` in the page.
std::set<std::string> names_under(const std::string& page, const std::string& heading) {
  const auto at = page.find("\n" + heading + "\n");
  BOOST_REQUIRE_MESSAGE(at != std::string::npos, heading);
  const auto end = std::min(page.find("\n## ", at + 1), page.find("\n### ", at + 1));
  const std::string part = page.substr(at, end == std::string::npos ? std::string::npos : end - at);
  std::set<std::string> names;
  std::istringstream in(part);
  static const std::regex first_cell(R"(^\| `([^`]+)` \|)");
  for (std::string line; std::getline(in, line);) {
    std::smatch m;
    if (std::regex_search(line, m, first_cell)) names.insert(m[1]);
  }
  return names;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(dataset_reference)

BOOST_AUTO_TEST_CASE(the_page_is_the_readers_tables) {
  std::ifstream in(kSource / "docs/dataset-reference.md");
  std::stringstream page;
  page << in.rdbuf();
  BOOST_TEST(page.str() == dataset_reference_markdown(),
             "docs/dataset-reference.md differs from `chutelab init --reference`: regenerate it");
  // The command prints the same text.
  const auto r = test::run_chutelab("init --reference");
  BOOST_TEST(r.exit_code == 0, r.err);
  BOOST_TEST(r.out == dataset_reference_markdown());
}

BOOST_AUTO_TEST_CASE(every_listed_field_is_read_and_nothing_else_is_quiet) {
  const std::string page = dataset_reference_markdown();
  // setup.toml: every key of the page, and only those, are the reader's.
  std::set<std::string> page_keys;
  for (const char* t : {"### [belt]", "### [plate]", "### [material]", "### At the top (before any table)"})
    for (const auto& k : names_under(page, t)) page_keys.insert(k);
  std::set<std::string> reader_keys;
  for (const auto& f : rig_fields()) reader_keys.insert(std::string(f.key));
  BOOST_TEST(page_keys == reader_keys, boost::test_tools::per_element());

  // conditions.csv with every column the page lists: each value is taken (a setup key's column set
  // to 1.01 times the setup's value lands in the station), no column is warned about.
  const fs::path d = skeleton("ref-all-columns");
  const Setup setup = read_setup(d / "setup.toml");
  std::vector<std::string> head, row;
  for (const auto& c : names_under(page, "## conditions.csv")) {
    head.push_back(c);
    std::string v;
    for (const auto& k : condition_columns())
      if (k.name == c) v = k.example.empty() ? "20.0" : std::string(k.example);
    for (const auto& u : operating_uncertainty_columns())
      if (u.column == c) v = "0.01";
    BOOST_TEST_CONTEXT(c) { BOOST_TEST(!v.empty()); }
  }
  std::vector<std::string> override_columns;
  for (const auto& f : rig_fields())
    if (!f.column.empty()) {
      BOOST_TEST(page.find(fmt::format("`{}`", f.column)) != std::string::npos, f.column);
      override_columns.emplace_back(f.column);
    }
  for (const auto& f : rig_fields())
    if (!f.column.empty()) {
      Setup s = setup;
      head.emplace_back(f.column);
      row.push_back(fmt::format("{:.9g}", f.ref(s) / f.to_si * (f.key == "loaded_width_mm" ? 0.99 : 1.01)));
    }
  std::vector<std::string> first;
  for (const auto& c : names_under(page, "## conditions.csv")) {
    std::string v;
    for (const auto& k : condition_columns())
      if (k.name == c) v = k.example.empty() ? "20.0" : std::string(k.example);
    for (const auto& u : operating_uncertainty_columns())
      if (u.column == c) v = "0.01";
    first.push_back(v);
  }
  first.insert(first.end(), row.begin(), row.end());
  test::write_file(d / "conditions.csv", fmt::format("{}\n{}\n", fmt::join(head, ","), fmt::join(first, ",")));
  test::write_file(d / "measurements.csv", csv_of(measurement_columns()));
  test::write_file(d / "trajectory.csv", csv_of(trajectory_columns()));
  test::write_file(d / "plate_map.csv", csv_of(plate_map_columns()));
  {
    Stderr err;
    const Dataset ds = read_dataset(d);
    BOOST_TEST(err.str() == "");
    BOOST_REQUIRE(ds.stations.size() == 1u);
    const Station& st = ds.stations[0];
    BOOST_TEST(st.stream_thickness.has_value());
    BOOST_TEST(ds.input_uncertainty[0].belt_speed.has_value());
    BOOST_TEST(ds.input_uncertainty[0].stream_thickness.has_value());
    BOOST_TEST(st.material.friction_plate == setup.material.friction_plate * 1.01, boost::test_tools::tolerance(1e-9));
    BOOST_TEST(st.belt.pulley_diameter == setup.belt.pulley_diameter * 1.01, boost::test_tools::tolerance(1e-9));
    BOOST_TEST(ds.measurements.at(0).uncertainty.has_value());
    BOOST_TEST(ds.trajectory.at(0).uncertainty.has_value());
    BOOST_TEST(ds.plate_map.at(0).uncertainty.has_value());
  }
  // A column the page does not list is warned about (so the page's list is all the reader takes).
  test::write_file(d / "conditions.csv", fmt::format("{},not_a_column\n{},1\n", fmt::join(head, ","), fmt::join(first, ",")));
  {
    Stderr err;
    read_dataset(d);
    BOOST_TEST(err.str().find("unknown column 'not_a_column'") != std::string::npos, err.str());
  }

  // Each file: a required column left out is refused naming it; an optional one is not missed.
  const struct {
    const char* file;
    std::span<const ColumnSpec> columns;
  } files[] = {{"measurements.csv", measurement_columns()},
               {"trajectory.csv", trajectory_columns()},
               {"plate_map.csv", plate_map_columns()},
               {"conditions.csv", condition_columns()}};
  for (const auto& f : files) {
    const fs::path e = skeleton(fmt::format("ref-drop-{}", f.file));
    for (const auto& c : f.columns) {
      BOOST_TEST_CONTEXT(f.file << " without " << c.name) {
        BOOST_TEST(page.find(fmt::format("| `{}` |", c.name)) != std::string::npos);
        test::write_file(e / "measurements.csv", csv_of(measurement_columns()));
        test::write_file(e / "conditions.csv", csv_of(condition_columns()));
        test::write_file(e / f.file, csv_of(f.columns, {c.name}));
        Stderr err;  // an unstated uncertainty warns: not this check's business
        if (c.required) {
          try {
            read_dataset(e);
            BOOST_ERROR("read without a required column");
          } catch (const InputError& x) {
            BOOST_TEST(std::string(x.what()).find(std::string(c.name)) != std::string::npos, x.what());
          }
        } else {
          BOOST_CHECK_NO_THROW(read_dataset(e));
        }
      }
    }
  }
}

BOOST_AUTO_TEST_CASE(init_writes_a_dataset_that_validates) {
  const fs::path root = test::fresh_dir("ref-init");
  const auto r = test::run_chutelab(fmt::format("init --out '{}'", (root / "mine").string()));
  BOOST_TEST(r.exit_code == 0, r.err);
  BOOST_TEST(r.err == "");
  const Dataset d = read_dataset(root / "mine");
  BOOST_TEST(d.stations.size() == 5u);
  BOOST_TEST(d.measurements.size() == 10u);
  const auto v = test::run_chutelab(
      fmt::format("validate --dataset '{}' --out '{}'", (root / "mine").string(), (root / "report").string()));
  BOOST_TEST(v.exit_code == 0, v.err);
  BOOST_TEST(v.err == "");
  // Every line of setup.toml says what its key is; every key the reader takes is there.
  const std::string setup = test::read_file(root / "mine/setup.toml");
  for (const auto& f : rig_fields()) BOOST_TEST(setup.find(fmt::format("\n{} = ", f.key)) != std::string::npos, f.key);
  std::istringstream in(setup);
  for (std::string line; std::getline(in, line);)
    if (line.find(" = ") != std::string::npos) BOOST_TEST(line.find('#') != std::string::npos, line);
  // It never writes over a dataset: a second init into the same folder is refused, nothing changed.
  const auto again = test::run_chutelab(fmt::format("init --out '{}'", (root / "mine").string()));
  BOOST_TEST(again.exit_code == 0, again.err);  // its own files, as it wrote them: replaced by the same
  test::write_file(root / "mine/setup.toml", setup + "\n# mine now\n");
  const auto changed = test::run_chutelab(fmt::format("init --out '{}'", (root / "mine").string()));
  BOOST_TEST(changed.exit_code == 2);
  BOOST_TEST(test::read_file(root / "mine/setup.toml") == setup + "\n# mine now\n");
}

BOOST_AUTO_TEST_CASE(a_wide_table_is_shown_the_long_layout) {
  const fs::path d = skeleton("ref-wide");
  test::write_file(d / "measurements.csv",
                   "Test,Belt speed (m/s),Mass flow (t/h),Rn (N),Rn +/-,Rs (N),Rs +/-\nV2-26,2.0,26.0,14.9,0.3,3.6,0.2\n");
  try {
    read_dataset(d);
    BOOST_ERROR("a wide table was read");
  } catch (const InputError& e) {
    const std::string m = e.what();
    BOOST_TEST(m.find("measurements.csv") != std::string::npos, m);
    BOOST_TEST(m.find("condition,quantity,value,uncertainty") != std::string::npos, m);
    BOOST_TEST(m.find("V2-26,normal_force_N,") != std::string::npos, m);
    BOOST_TEST(m.find('\n') == std::string::npos, m);
  }
}

BOOST_AUTO_TEST_CASE(a_value_without_uncertainty_is_warned_about) {
  const fs::path d = skeleton("ref-no-uncertainty");
  std::string m = test::read_file(d / "measurements.csv");
  // The first data row's uncertainty emptied, the second's set to 0 (also "unknown").
  std::istringstream in(m);
  std::string out;
  int data = 0;
  long line_no = 0, first_line = 0, second_line = 0;
  for (std::string line; std::getline(in, line);) {
    ++line_no;
    if (!line.empty() && line[0] != '#' && line.rfind("condition,", 0) != 0) {
      ++data;
      if (data <= 2) {
        line = line.substr(0, line.rfind(',') + 1) + (data == 2 ? "0" : "");
        (data == 1 ? first_line : second_line) = line_no;
      }
    }
    out += line + "\n";
  }
  test::write_file(d / "measurements.csv", out);
  Stderr err;
  const Dataset ds = read_dataset(d);
  const std::string w = err.str();
  BOOST_TEST(w.find(fmt::format("measurements.csv:{}: normal_force_N of 'V2-26' has no uncertainty", first_line)) !=
                 std::string::npos,
             w);
  BOOST_TEST(w.find(fmt::format("measurements.csv:{}: shear_force_N of 'V2-26' has no uncertainty", second_line)) !=
                 std::string::npos,
             w);
  BOOST_TEST(test::count_lines(w) == 2);
}

BOOST_AUTO_TEST_SUITE_END()
