// The DEM result cache trusts an entry only whole (dem/station/cache.h): a damaged number, a line
// gone, a file cut short, a file of another format or a FIFO in an entry's place is refused with
// the line and field that failed, never read as numbers; a run that cannot be cached says so; and
// the DEM model runs a refused entry again, or, told never to run, stops naming the file.
#define BOOST_TEST_MODULE dem_station_cache
#include <boost/test/unit_test.hpp>

#include <fcntl.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <future>
#include <sstream>
#include <string>

#include <fmt/format.h>

#include "core/input_error.h"
#include "dem/station/cache.h"
#include "tiny_station.h"
#include "validation/models/dem_model.h"

using namespace chutelab;
using namespace chutelab::dem::station;
namespace fs = std::filesystem;

namespace {

const fs::path kPeer = fs::path(CHUTELAB_SOURCE_DIR) / "tests" / "peer" / "dem-cache";
// The smallest recorded run (format 5, V2-26 of the LIGGGHTS rig at standard quality).
const fs::path kRecorded = kPeer / "5f4ab5a87a660dca.txt";

std::string slurp(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

void put(const fs::path& p, const std::string& text) { std::ofstream(p, std::ios::binary) << text; }

fs::path fresh(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / fmt::format("chutelab-cache-{}-{}", name, ::getpid());
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

// The key a file repeats on its second line and after it.
std::string key_of(const std::string& text) {
  const std::size_t nl1 = text.find('\n'), nl2 = text.find('\n', nl1 + 1);
  const std::size_t bytes = std::stoull(text.substr(nl1 + 5, nl2 - nl1 - 5));
  return text.substr(nl2 + 1, bytes);
}

// The text with its first line starting `prefix` replaced by `line` (or removed when empty).
std::string with_line(std::string text, const std::string& prefix, const std::string& line) {
  const std::size_t at = text.find("\n" + prefix) + 1;
  BOOST_REQUIRE(at != 0);
  const std::size_t end = text.find('\n', at);
  text.replace(at, end + 1 - at, line.empty() ? "" : line + "\n");
  return text;
}

// A recorded run copied into a fresh cache under its own name, and its key.
struct Recorded {
  fs::path dir;
  std::string text, key;
  ResultCache cache;
  explicit Recorded(const std::string& name)
      : dir(fresh(name)), text(slurp(kRecorded)), key(key_of(text)), cache(dir.string()) {
    BOOST_REQUIRE(cache.path_for(key) == (dir / kRecorded.filename()).string());
    put(cache.path_for(key), text);
  }
  CacheEntry with(const std::string& damaged) const {
    put(cache.path_for(key), damaged);
    return cache.lookup(key);
  }
  ~Recorded() { fs::remove_all(dir); }
};

bool says(const CacheEntry& e, const std::string& what) { return e.said().find(what) != std::string::npos; }

// Where the 20th force sample's line starts ("\nforce ..."), in the middle of the series.
std::size_t a_force_line(const std::string& text) {
  std::size_t at = text.find("\nforce ");
  for (int k = 0; k < 20 && at != std::string::npos; ++k) at = text.find("\nforce ", at + 1);
  BOOST_REQUIRE(at != std::string::npos);
  return at;
}

}  // namespace

// The recorded runs (format 5) load, number for number.
BOOST_AUTO_TEST_CASE(recorded_runs_still_load) {
  const Recorded rec("recorded");
  const CacheEntry e = rec.cache.lookup(rec.key);
  BOOST_TEST(!e.refused.has_value(), e.said());
  BOOST_REQUIRE(e.result.has_value());
  BOOST_TEST(e.result->condition == "V2-26");
  BOOST_TEST(e.result->normal_force.value == 9.5234918076475044);
  BOOST_TEST(e.result->normal_force.n == 99);
  BOOST_TEST(e.result->forces.size() > 100u);
  // Another key's entry in the file (stale, or a hash collision) is a plain miss, not a refusal.
  const CacheEntry other = rec.cache.lookup(rec.key + "x");
  BOOST_TEST(!other.result.has_value());
  BOOST_TEST(!other.refused.has_value());
}

// Every recorded run the peer tests read (format 5) passes the strict reading.
BOOST_AUTO_TEST_CASE(every_recorded_run_loads) {
  int n = 0;
  for (const auto& f : fs::directory_iterator(kPeer)) {
    if (f.path().extension() != ".txt") continue;
    const ResultCache cache(kPeer.string());
    const CacheEntry e = cache.lookup(key_of(slurp(f.path())));
    BOOST_TEST((e.result && e.file == f.path().string()), f.path() << ": " << e.said());
    ++n;
  }
  BOOST_TEST(n > 100);
}

// What the probe found: each of these used to load as a result.
BOOST_AUTO_TEST_CASE(damaged_entries_are_refused_with_line_and_field) {
  const Recorded rec("damaged");
  const long rn_line = 75;  // the scalar normal_force line of the recorded file
  BOOST_REQUIRE(rec.text.find("\nscalar normal_force 9.5234918076475044 ") != std::string::npos);
  // An unparsable number (read as R_n = 0 before).
  CacheEntry e = rec.with(with_line(rec.text, "scalar normal_force", "scalar normal_force abc 0.26423501579995051 99"));
  BOOST_TEST(!e.result.has_value());
  BOOST_REQUIRE(e.refused.has_value());
  BOOST_TEST(e.refused->line == rn_line);
  BOOST_TEST(e.refused->field == "scalar");
  BOOST_TEST(says(e, fmt::format("{}:{}: scalar: normal_force: 'abc' is not a number", rec.cache.path_for(rec.key), rn_line)),
             e.said());
  // A number with trailing junk (read as its leading part before).
  e = rec.with(with_line(rec.text, "scalar normal_force", "scalar normal_force 9.52x 0.26423501579995051 99"));
  BOOST_TEST((!e.result && says(e, "'9.52x' is not a number")), e.said());
  // nan for a quantity that has values (the quantity silently dropped before).
  e = rec.with(with_line(rec.text, "scalar normal_force", "scalar normal_force nan 0.26423501579995051 99"));
  BOOST_TEST((!e.result && says(e, "no mean of 99 values")), e.said());
  // inf, a negative count, a field too many, a field missing.
  e = rec.with(with_line(rec.text, "scalar normal_force", "scalar normal_force inf 0.26423501579995051 99"));
  BOOST_TEST((!e.result && says(e, "not a finite number")), e.said());
  e = rec.with(with_line(rec.text, "scalar normal_force", "scalar normal_force 9.5 0.26 -99"));
  BOOST_TEST((!e.result && says(e, "not a whole number") == false && says(e, "outside")), e.said());
  e = rec.with(with_line(rec.text, "scalar normal_force", "scalar normal_force 9.5 0.26 99 1"));
  BOOST_TEST((!e.result && says(e, "has 5 fields, expected 4")), e.said());
  e = rec.with(with_line(rec.text, "scalar normal_force", "scalar normal_force 9.5 0.26"));
  BOOST_TEST((!e.result && says(e, "has 3 fields, expected 4")), e.said());
  // A deleted line: the quantity is missing, not "not measured".
  e = rec.with(with_line(rec.text, "scalar normal_force", ""));
  BOOST_TEST((!e.result && says(e, "scalar: normal_force is missing")), e.said());
  e = rec.with(with_line(rec.text, "window ", ""));
  BOOST_TEST((!e.result && says(e, "window: the line is missing")), e.said());
  // A line twice, a force sample out of order, an unknown line.
  const std::size_t rn = rec.text.find("\nscalar normal_force");
  std::string twice = rec.text;
  twice.insert(rn + 1, twice.substr(rn + 1, twice.find('\n', rn + 1) - rn));
  e = rec.with(twice);
  BOOST_TEST((!e.result && says(e, "appears twice")), e.said());
  e = rec.with(with_line(rec.text, "force 0.0060653262656305724", "force 0.001 0 0 0 0 0 0 0"));
  BOOST_TEST((!e.result && says(e, "does not follow")), e.said());
  e = rec.with(with_line(rec.text, "window ", "windoe 1 0.3 0.8 5"));
  BOOST_TEST((!e.result && says(e, "windoe: unknown line")), e.said());
  // Cut short: no end line.
  e = rec.with(rec.text.substr(0, a_force_line(rec.text) + 1));
  BOOST_TEST((!e.result && says(e, "end: the end line is missing")), e.said());
  // Format 2 had no end line, so one cut at a line end looked whole: no format but 5 and 6 is read.
  std::string v2 = rec.text.substr(0, a_force_line(rec.text) + 1);
  v2.replace(0, v2.find('\n'), "chutelab-dem-result 2");
  e = rec.with(v2);
  BOOST_TEST((!e.result && says(e, ":1: format 2 is not read")), e.said());
  e = rec.with("garbage");
  BOOST_TEST((!e.result && says(e, ":1: not a DEM cache entry")), e.said());
  e = rec.with("");
  BOOST_TEST((!e.result && e.refused.has_value()), e.said());
}

// Format 6 carries a check sum of everything before its end line: an edited number that still
// parses, a line cut off at a line end, or a second copy of a line is refused as well.
BOOST_AUTO_TEST_CASE(written_entries_carry_a_check_sum) {
  const Recorded rec("checksum");
  const StationResult r = *rec.cache.lookup(rec.key).result;
  const fs::path dir = fresh("checksum-6");
  const ResultCache cache(dir.string());
  const CacheWrite w = cache.store(rec.key, r);
  BOOST_TEST(w.written, w.problem);
  const std::string text = slurp(cache.path_for(rec.key));
  BOOST_TEST(text.starts_with("chutelab-dem-result 6\n"));
  const CacheEntry back = cache.lookup(rec.key);
  BOOST_REQUIRE(back.result.has_value());
  BOOST_TEST(to_text(*back.result) == to_text(r));
  // One digit of R_n changed: still a number, in range, but not what was written.
  std::string edited = text;
  const std::size_t at = edited.find("scalar normal_force 9.52") + 22;
  edited[at] = '6';
  put(cache.path_for(rec.key), edited);
  CacheEntry e = cache.lookup(rec.key);
  BOOST_TEST((!e.result && says(e, "end: the check sum does not match")), e.said());
  // Cut at a line end, the end line kept: the sum tells.
  std::string cut = text;
  const std::size_t f = a_force_line(cut);
  cut.erase(f + 1, cut.find('\n', f + 1) - f);
  put(cache.path_for(rec.key), cut);
  e = cache.lookup(rec.key);
  BOOST_TEST((!e.result && says(e, "check sum does not match")), e.said());
  put(cache.path_for(rec.key), text.substr(0, text.rfind("end ")));
  e = cache.lookup(rec.key);
  BOOST_TEST((!e.result && says(e, "the end line is missing")), e.said());
  fs::remove_all(dir);
}

// Only a regular file is opened: a FIFO where an entry belongs (no writer ever comes) is refused at
// once, as are a folder and a device.
BOOST_AUTO_TEST_CASE(only_regular_files_are_read) {
  const fs::path dir = fresh("fifo");
  const ResultCache cache(dir.string());
  const std::string path = cache.path_for("key\n");
  BOOST_REQUIRE(::mkfifo(path.c_str(), 0600) == 0);
  auto looked = std::async(std::launch::async, [&] { return cache.lookup("key\n"); });
  if (looked.wait_for(std::chrono::seconds(10)) != std::future_status::ready) {
    BOOST_ERROR("the look-up blocks on a FIFO");
    // Let it go: a writer that opens and closes the FIFO ends the blocked read.
    const int fd = ::open(path.c_str(), O_WRONLY | O_NONBLOCK);
    if (fd >= 0) ::close(fd);
  }
  const CacheEntry e = looked.get();
  BOOST_TEST((!e.result && says(e, "is a FIFO")), e.said());
  fs::remove(path);
  fs::create_directories(fs::path(path) / "sub");
  BOOST_TEST(says(cache.lookup("key\n"), "is a folder"));
  fs::remove_all(path);
  fs::create_symlink("/dev/zero", path);
  BOOST_TEST(says(cache.lookup("key\n"), "not a regular file"));
  fs::remove_all(dir);
}

// A cache that cannot be written says so and why, and leaves nothing behind.
BOOST_AUTO_TEST_CASE(a_failed_write_is_reported) {
  const Recorded rec("unwritable");
  const StationResult r = *rec.cache.lookup(rec.key).result;
  // The folder cannot be made: a file stands where it would go.
  put(rec.dir / "file", "x");
  const CacheWrite no_dir = ResultCache((rec.dir / "file" / "cache").string()).store(rec.key, r);
  BOOST_TEST(!no_dir.written);
  BOOST_TEST(no_dir.problem.find("cannot make the cache folder") != std::string::npos, no_dir.problem);
  // The entry's name is taken by a folder that is not empty: the rename fails.
  fs::remove(rec.cache.path_for(rec.key));
  fs::create_directories(fs::path(rec.cache.path_for(rec.key)) / "sub");
  const CacheWrite no_rename = rec.cache.store(rec.key, r);
  BOOST_TEST(!no_rename.written);
  BOOST_TEST(no_rename.problem.find("cannot write " + rec.cache.path_for(rec.key)) != std::string::npos,
             no_rename.problem);
  for (const auto& f : fs::directory_iterator(rec.dir)) BOOST_TEST(f.path().extension() != ".tmp", f.path());
  // A write that fails half-way (a full disk; here a file size limit, which fails write() the same
  // way): no entry, and the reason.
  std::signal(SIGXFSZ, SIG_IGN);
  rlimit was{};
  ::getrlimit(RLIMIT_FSIZE, &was);
  rlimit small = was;
  small.rlim_cur = 4096;
  BOOST_REQUIRE(::setrlimit(RLIMIT_FSIZE, &small) == 0);
  fs::remove_all(rec.cache.path_for(rec.key));
  const CacheWrite cut = rec.cache.store(rec.key, r);
  ::setrlimit(RLIMIT_FSIZE, &was);
  BOOST_TEST(!cut.written);
  BOOST_TEST(cut.problem.find("File too large") != std::string::npos, cut.problem);
  BOOST_TEST(!fs::exists(rec.cache.path_for(rec.key)));
  for (const auto& f : fs::directory_iterator(rec.dir)) BOOST_TEST(f.path().extension() != ".tmp", f.path());
}

// The DEM model: a damaged entry under --dem-cache-only is bad input naming the file and line; the
// model never reads it as numbers.
BOOST_AUTO_TEST_CASE(cache_only_names_the_damaged_file) {
  const fs::path dir = fresh("model");
  const Station st = test::tiny_station();
  validation::DemModelConfig c;
  c.overrides.set_quality(Quality::quick);
  c.overrides.threads = 1;
  c.cache_dir = dir.string();
  c.cache_only = true;
  c.ladder = false;
  const RunSettings settings = resolve(DemTable{}, c.overrides);
  const std::string key = validation::dem_cache_key(validation::dem_effect_inputs(st, {}), settings, {});
  const ResultCache cache(dir.string());
  // A whole entry of this key: loaded, never run.
  const Recorded rec("model-source");
  StationResult r = *rec.cache.lookup(rec.key).result;
  r.condition = st.condition;
  BOOST_REQUIRE(cache.store(key, r).written);
  const validation::ModelPtr m = validation::make_dem_model(c);
  validation::PredictRequest request;
  request.curves = false;
  const validation::ModelPrediction p = m->predict(st, {}, request);
  BOOST_TEST(*p.values[Quantity::normal_force] == r.normal_force.value);
  // The same entry with R_n unreadable.
  std::string text = slurp(cache.path_for(key));
  const std::size_t at = text.find("scalar normal_force ") + 20;
  text.replace(at, text.find(' ', at) - at, "R_n");
  put(cache.path_for(key), text);
  try {
    m->predict(st, {}, request);
    BOOST_ERROR("a damaged entry was used");
  } catch (const InputError& e) {
    BOOST_TEST(e.file() == cache.path_for(key));
    BOOST_TEST(e.line() > 2);
    BOOST_TEST(e.field() == "scalar");
    BOOST_TEST(e.problem().find("'R_n' is not a number") != std::string::npos, e.what());
    BOOST_TEST(e.problem().find("does not run it again") != std::string::npos, e.what());
  }
  fs::remove_all(dir);
}
