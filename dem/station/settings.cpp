#include "dem/station/settings.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <stdexcept>
#include <thread>
#include <filesystem>
#include <fmt/format.h>
#include <toml++/toml.h>

#include "core/free_cores.h"
#include "core/input_error.h"
#include "core/option_check.h"
#include "core/toml_file.h"

namespace chutelab::dem::station {

std::string_view name(Quality q) {
  switch (q) {
    case Quality::quick: return "quick";
    case Quality::standard: return "standard";
    case Quality::paper: return "paper";
  }
  return "?";
}

std::optional<Quality> parse_quality(std::string_view s) {
  for (Quality q : {Quality::quick, Quality::standard, Quality::paper})
    if (name(q) == s) return q;
  return std::nullopt;
}

std::string_view name(ContactLaw c) { return c.key(); }

std::optional<ContactLaw> parse_contact(std::string_view s) { return NormalLaw::named(s); }

std::string_view name(ParticleShape p) { return p == ParticleShape::sphere ? "sphere" : "clump"; }

std::optional<ParticleShape> parse_shape(std::string_view s) {
  if (s == "sphere") return ParticleShape::sphere;
  if (s == "clump") return ParticleShape::clump;
  return std::nullopt;
}

RunSettings preset(Quality q) {
  RunSettings s;  // the defaults of settings.h are the standard preset
  s.quality = q;
  switch (q) {
    case Quality::standard:
      // The dataset's own particle size and modulus, the LIGGGHTS rig's feed (0.4 m face, 50 1/s
      // relaxation, 0.2 m of free belt) and up to 1.3 s from an empty belt, the longest
      // run of the LIGGGHTS rig; stops early once 0.5 s (five 0.1 s blocks) are steady.
      break;
    case Quality::paper:
      // The reference study's spheres (Grima & Wypych 2010 §4: 5.6 mm) at the dataset's modulus; 3.4x the
      // particles of the 9 mm rig and a shorter time step: hours, not minutes.
      s.particle_diameter = 5.6e-3;
      break;
    case Quality::quick:
      // 13.6 mm spheres (reference study Table 6's largest size: mean plate force unchanged, fluctuation
      // larger) at a third of the modulus: ~3.4x fewer particles and a ~2.4x longer time step. A
      // shorter feed face and free belt (the layer still reaches the pulley at belt speed, checked
      // by the tests), and a 0.3 s steady window (three 0.1 s blocks) within at most 1.0 s.
      s.particle_diameter = 13.6e-3;
      s.shear_modulus_scale = 1.0 / 3.0;
      s.feed_length = 0.25;
      s.free_belt = 0.12;
      s.min_time = 0.4;
      s.max_time = 1.0;
      s.min_window = 0.3;
      break;
  }
  return s;
}

const std::vector<WearField>& wear_fields() {
  using A = wear::ArchardParams;
  using F = wear::FinnieParams;
  static const std::vector<WearField> f = {
      {"archard_coefficient", "Archard wear coefficient k_A (dimensionless)", nullptr, &A::coefficient, nullptr, false},
      {"hardness_Pa", "plate hardness H for Archard, Pa", nullptr, &A::hardness, nullptr, false},
      {"finnie_flow_pressure_Pa", "plate plastic flow pressure p for Finnie, Pa", nullptr, nullptr, &F::flow_pressure, false},
      {"finnie_force_ratio", "Finnie's K, vertical/horizontal force on the cutting tip", nullptr, nullptr, &F::force_ratio, false},
      {"finnie_depth_ratio", "Finnie's psi, contact length / depth of cut", nullptr, nullptr, &F::depth_ratio, false},
      {"finnie_cutting_fraction", "Finnie's c, fraction of particles that cut", nullptr, nullptr, &F::cutting_fraction, false},
      {"finnie_velocity_exponent", "Finnie speed exponent n (theory 2)", nullptr, nullptr, &F::velocity_exponent, false},
      {"exposure_h", "hours of operation a measured wear depth covers (wear_depth_um)", &WearInputs::exposure_hours,
       nullptr, nullptr, true},
  };
  return f;
}

void set_wear(WearInputs& w, const std::string& key, double value, const std::string& file, long line,
              const std::string& field) {
  const std::string where = field.empty() ? key : field;
  for (const auto& f : wear_fields()) {
    if (key != f.key) continue;
    if (!std::isfinite(value) || value < 0.0 || (!f.allow_zero && value == 0.0))
      throw InputError(file, line, where, fmt::format("must be a {} number, got {}", f.allow_zero ? "non-negative" : "positive", value));
    if (key == "finnie_cutting_fraction" && value > 1.0)
      throw InputError(file, line, where, fmt::format("is a fraction in (0, 1], got {}", value));
    if (key == "finnie_velocity_exponent" && value > 5.0)
      throw InputError(file, line, where, fmt::format("must be in (0, 5], got {}", value));
    f.ref(w) = value;
    return;
  }
  std::string known;
  for (const auto& f : wear_fields()) known += (known.empty() ? "" : ", ") + std::string(f.key);
  throw InputError(file, line, where, "unknown key (known: " + known + ")");
}

int effective_threads(int threads) { return threads > 0 ? threads : free_cores(); }

namespace {

long line_of(const toml::node& n) { return static_cast<long>(n.source().begin.line); }

constexpr double kAny = std::numeric_limits<double>::max();

std::string path_string(const toml::node& n, const std::string& file, const std::string& key) {
  const auto v = n.value<std::string>();
  if (!v || v->empty()) throw InputError(file, line_of(n), key, "must be a file name (string)");
  namespace fs = std::filesystem;
  fs::path p(*v);
  if (p.is_relative()) p = fs::path(file).parent_path() / p;
  if (!fs::exists(p)) throw InputError(file, line_of(n), key, fmt::format("file '{}' not found", p.string()));
  return p.string();
}

template <class E>
std::function<std::vector<DemWord>()> words_of(std::initializer_list<E> values) {
  std::vector<DemWord> w;
  for (E v : values) w.push_back({std::string(name(v)), ""});
  return [w] { return w; };
}

std::function<std::vector<DemWord>()> two_words(const char* a, const char* a_means, const char* b, const char* b_means) {
  return [=] { return std::vector<DemWord>{{a, a_means}, {b, b_means}}; };
}

// A flag of RunSettings that is true for `yes`, false for the other word.
std::function<void(RunSettings&, const DemValue&)> flag(bool RunSettings::*m, const char* yes) {
  return [m, yes](RunSettings& s, const DemValue& v) { s.*m = v.word == yes; };
}

std::function<void(RunSettings&, const DemValue&)> number(double RunSettings::*m) {
  return [m](RunSettings& s, const DemValue& v) { s.*m = v.number; };
}

// The table. Its order is the order a [dem] table is applied in (feed_length_mm before [dem.feed]'s
// face_length_mm, face_low_mm before face_high_mm) and of the known-keys message.
std::vector<DemField> make_fields() {
  using S = RunSettings;
  auto field = [](std::string_view key, std::string_view option, DemKind kind, std::string_view unit, double to_si,
                  double lo, double hi, bool lo_open, bool hi_open, std::string_view help) {
    DemField f{key, option, kind, unit, to_si, lo, hi, lo_open, hi_open, {}, help, {}, {}, {}};
    return f;
  };
  auto num = [&](std::string_view key, std::string_view option, std::string_view unit, double to_si, double lo,
                 double hi, bool lo_open, bool hi_open, std::string_view help, double S::*m) {
    DemField f = field(key, option, DemKind::number, unit, to_si, lo, hi, lo_open, hi_open, help);
    f.set = number(m);
    f.member = m;
    return f;
  };
  auto word = [&](std::string_view key, std::string_view option, std::string_view help,
                  std::function<std::vector<DemWord>()> words, std::function<void(S&, const DemValue&)> set,
                  bool S::*flag_member = nullptr) {
    DemField f = field(key, option, DemKind::word, "", 1.0, 0.0, 0.0, false, false, help);
    f.words = std::move(words);
    f.set = std::move(set);
    if (flag_member) f.member = flag_member;
    return f;
  };
  std::vector<DemField> v;
  DemField quality = word("quality", "quality", "the preset the other settings go on top of (dem.md)",
                          words_of({Quality::quick, Quality::standard, Quality::paper}),
                          [](S& s, const DemValue& x) { s.quality = *parse_quality(x.word); });
  quality.member = &S::quality;
  quality.selects_preset = true;
  v.push_back(quality);
  DemField d = num("particle_diameter_mm", "diameter_mm", "mm", 1e-3, 0.0, 200.0, true, true,
                   "particle diameter of the run (scale-up; for a clump, its spheres')", &S::particle_diameter);
  d.zero_in_settings = true;  // the preset's "the dataset's own particles"
  v.push_back(d);
  v.push_back(num("shear_modulus_scale", "shear_modulus_scale", "", 1.0, 0.0, 1000.0, true, false,
                  "factor on E and G of particles and walls", &S::shear_modulus_scale));
  v.push_back(num("dt_fraction", "dt_fraction", "", 1.0, 0.0, 0.5, true, false,
                  "time step as a fraction of the Hertz collision time", &S::dt_fraction));
  DemField contact = word("contact", "contact", "contact law (dem.md)",
                          [] {
                            std::vector<DemWord> w;
                            for (int i = 0; const auto law = NormalLaw::at(i); ++i) w.push_back({std::string(law->key()), ""});
                            return w;
                          },
                          [](S& s, const DemValue& x) { s.contact = *parse_contact(x.word); });
  contact.member = &S::contact;
  v.push_back(contact);
  DemField shape = word("shape", "shape", "particle shape: spheres, or the reference study's two-sphere pellet (Fig. 4c)",
                        words_of({ParticleShape::sphere, ParticleShape::clump}),
                        [](S& s, const DemValue& x) { s.particle_shape = *parse_shape(x.word); });
  shape.member = &S::particle_shape;
  v.push_back(shape);
  DemField seed = field("seed", "seed", DemKind::whole, "", 1.0, 0.0, kAny, false, false, "seed of the particle feed");
  seed.set = [](S& s, const DemValue& x) { s.seed = x.whole; };
  seed.member = &S::seed;
  seed.kept = true;
  v.push_back(seed);
  DemField max_time = num("max_time_s", "max_time", "s", 1.0, 0.0, 100.0, true, false,
                          "simulated time limit (the run stops earlier when steady)", &S::max_time);
  // Given on its own, a shorter limit keeps a run possible: the earliest stop and the steady window
  // shrink with it.
  max_time.after_override = [](S& s) {
    s.min_time = std::min(s.min_time, s.max_time);
    s.min_window = std::min(s.min_window, 0.5 * s.max_time);
  };
  v.push_back(max_time);
  v.push_back(num("min_window_s", "", "s", 1.0, 0.0, kAny, true, false, "steady window needed for an early stop",
                  &S::min_window));
  DemField steady = word("steady_on", "steady_on", "the plate loads the steady window is judged on",
                         two_words("normal", "the steady window judged on R_n, as the LIGGGHTS rig did", "all",
                                   "on R_n, R_s and the moment"),
                         flag(&S::steady_all_loads, "all"), &S::steady_all_loads);
  steady.kept = true;
  v.push_back(steady);
  v.push_back(num("feed_length_mm", "", "mm", 1e-3, 0.0, 1e4, true, false, "length of the insertion face along the belt",
                  &S::feed_length));
  v.push_back(num("skin_fraction", "", "", 1.0, 0.0, kAny, true, false, "Verlet skin as a fraction of the particle radius",
                  &S::skin_fraction));
  v.push_back(word("rolling_lever", "", "lever arm of the particle-particle rolling torque",
                   two_words("particle", "reference study Eq 10", "effective", "LIGGGHTS cdt"),
                   flag(&S::rolling_lever_effective, "effective"), &S::rolling_lever_effective));
  // [dem.feed]: the dataset's own feeder (RunSettings' feed fields; README "DEM").
  v.push_back(num("feed.face_length_mm", "", "mm", 1e-3, 0.0, 1e4, true, false,
                  "length of the insertion face along the belt", &S::feed_length));
  DemField width = num("feed.face_width_mm", "", "mm", 1e-3, 0.0, 1e4, true, false,
                       "width of the insertion face across the belt (default: the loaded width)", &S::face_width);
  width.nan_unset = true;
  v.push_back(width);
  v.push_back(num("feed.face_low_mm", "", "mm", 1e-3, 0.0, kAny, true, false,
                  "bottom of the insertion box above the belt", &S::insert_low));
  DemField high = field("feed.face_high_mm", "", DemKind::number, "mm", 1e-3, 0.0, kAny, true, false,
                        "top of the insertion box above the belt");
  high.set = [](S& s, const DemValue& x) { s.insert_depth = x.number - s.insert_low; };
  high.above = "feed.face_low_mm";
  v.push_back(high);
  DemField end = num("feed.face_end_mm", "", "mm", 1e-3, 0.0, kAny, false, false,
                     "where the insertion face ends upstream of the pulley's tangent point (with face_end_time_s)",
                     &S::face_end);
  end.nan_unset = true;
  v.push_back(end);
  DemField end_time = num("feed.face_end_time_s", "", "s", 1.0, -kAny, kAny, false, false,
                          "the face ends this time times the belt speed further upstream", &S::face_end_time);
  end_time.needs = "feed.face_end_mm";
  v.push_back(end_time);
  v.push_back(num("feed.insert_speed_down_mps", "", "m/s", 1.0, -kAny, kAny, false, false,
                  "downward velocity of inserted particles", &S::insert_speed_down));
  v.push_back(word("feed.insertion", "", "where particles enter",
                   two_words("face", "through the box's lower face, as LIGGGHTS' fix insert/stream", "box",
                             "free from where they are placed in the box"),
                   flag(&S::insert_at_face, "face"), &S::insert_at_face));
  v.push_back(num("feed.relax_rate_per_s", "", "1/s", 1.0, 0.0, 1e4, false, false,
                  "feeder relaxation of the velocity towards the belt's (0: none)", &S::relax_rate));
  v.push_back(word("feed.relax_components", "", "what the feeder relaxes",
                   two_words("all", "the whole velocity, the fall included", "along",
                             "the along-belt components and rebounds"),
                   flag(&S::relax_all, "all"), &S::relax_all));
  v.push_back(word("feed.relax_end", "", "where the relaxation ends (relax_past_mm further)",
                   two_words("face", "past the insertion face", "landing", "past the landing of the last inserted particles"),
                   flag(&S::relax_from_face, "face"), &S::relax_from_face));
  v.push_back(num("feed.relax_past_mm", "", "mm", 1e-3, -kAny, kAny, false, false,
                  "how far past its start point the relaxation ends", &S::relax_past));
  DemField belt = num("feed.belt_start_mm", "", "mm", 1e-3, -kAny, kAny, false, false, "x of the belt's upstream end",
                      &S::belt_start_x);
  belt.nan_unset = true;
  v.push_back(belt);
  DemField cells = field("plate_cells", "plate_cells", DemKind::whole, "", 1.0, 1.0, 400.0, false, false,
                         "rows of cells down the generated plate for the pressure and wear maps");
  cells.zero_means = "the plate as two triangles";
  cells.set = [](S& s, const DemValue& x) { s.plate_cells = static_cast<int>(x.whole); };
  cells.member = &S::plate_cells;
  v.push_back(cells);
  DemField map = num("map_cell_mm", "map_cell_mm", "mm", 1e-3, 1.0, 1000.0, false, false,
                     "cell size of the plate's pressure and wear maps (the contacts are binned on the face; the plate "
                     "itself stays two triangles)",
                     &S::map_cell);
  map.zero_means = "the plate's own triangles";
  v.push_back(map);
  return v;
}

std::string quoted_words(const std::vector<DemWord>& w) {
  std::string o;
  for (std::size_t i = 0; i < w.size(); ++i) {
    if (i) o += i + 1 == w.size() ? " or " : ", ";
    o += "\"" + w[i].word + "\"";
    if (!w[i].meaning.empty()) o += " (" + w[i].meaning + ")";
  }
  return o;
}

}  // namespace

std::string DemField::range_text() const {
  if (kind == DemKind::word) return quoted_words(words());
  const options::NumberRule r{"", lo, hi, lo_open, hi_open, kind == DemKind::whole, unit};
  return zero_means.empty() ? r.describe() : fmt::format("0 ({}) or {}", zero_means, r.describe());
}

options::NumberRule DemField::rule(std::string_view option_key) const {
  return {option_key, zero_means.empty() ? lo : 0.0, hi, zero_means.empty() && lo_open, hi_open, kind == DemKind::whole, unit};
}

std::optional<std::string> DemField::problem(const DemValue& v) const {
  if (kind == DemKind::word) {
    for (const auto& w : words())
      if (w.word == v.word) return std::nullopt;
    return "must be " + range_text();
  }
  const double x = kind == DemKind::whole ? static_cast<double>(v.whole) : v.number;
  if (!zero_means.empty() && x == 0.0) return std::nullopt;
  const bool ok = std::isfinite(x) && (lo_open ? x > lo : x >= lo) && (hi_open ? x < hi : x <= hi);
  if (ok) return std::nullopt;
  return kind == DemKind::whole ? fmt::format("must be {}, got {}", range_text(), v.whole)
                                : fmt::format("must be {}, got {}", range_text(), v.number);
}

const std::vector<DemField>& dem_fields() {
  static const std::vector<DemField> f = make_fields();
  return f;
}

const DemField& dem_field(std::string_view key) {
  for (const auto& f : dem_fields())
    if (f.key == key) return f;
  throw std::logic_error("no [dem] key " + std::string(key));
}

// How check() and the overrides name a field: by its option, else by its [dem] key.
std::string field_name(const DemField& f) {
  return f.option.empty() ? "dem." + std::string(f.key) : std::string(f.option);
}

const DemField* dem_option(std::string_view option) {
  for (const auto& f : dem_fields())
    if (!f.option.empty() && f.option == option) return &f;
  return nullptr;
}

namespace {

// One value of a [dem] key from its TOML node, checked; InputError names the file, line and key.
DemValue read_value(const DemField& f, const toml::node& n, const std::string& file, const std::string& key) {
  DemValue v;
  bool typed = false;
  if (f.kind == DemKind::word) {
    const auto w = n.value<std::string>();
    typed = w.has_value();
    if (w) v.word = *w;
  } else if (f.kind == DemKind::whole) {
    const auto w = n.value<std::int64_t>();
    typed = w && n.is_integer() && *w >= 0;
    if (typed) v.whole = static_cast<std::uint64_t>(*w);
  } else {
    const auto x = n.value<double>();
    typed = x && n.is_number();
    if (typed) v.number = *x;
  }
  if (!typed) throw InputError(file, line_of(n), key, "must be " + f.range_text());
  if (const auto p = f.problem(v)) throw InputError(file, line_of(n), key, *p);
  return v;
}

// The keys of [dem] (prefix "") or of one of its tables ("feed."), for the unknown-key message.
std::string known_keys(std::string_view prefix, std::string_view tables) {
  std::string o;
  for (const auto& f : dem_fields()) {
    if (f.key.substr(0, prefix.size()) != prefix) continue;
    const std::string_view rest = f.key.substr(prefix.size());
    if (rest.find('.') != std::string_view::npos) continue;
    o += (o.empty() ? "" : ", ") + std::string(rest);
  }
  return "unknown key (known: " + o + std::string(tables) + ")";
}

// The tables of [dem] whose keys are dem_fields() ("feed" for [dem.feed]).
bool is_field_table(std::string_view name) {
  for (const auto& f : dem_fields())
    if (f.key.size() > name.size() && f.key.substr(0, name.size()) == name && f.key[name.size()] == '.') return true;
  return false;
}

void read_fields(const toml::table& t, const std::string& file, const std::string& prefix, DemTable& out);

void read_stl(const toml::node& node, const std::string& file, const std::string& key, DemTable& t) {
  const toml::table* stl = node.as_table();
  if (!stl) throw InputError(file, line_of(node), key, "must be a table ([dem.stl])");
  for (const auto& [sk, sn] : *stl) {
    const std::string skey = key + "." + std::string(sk.str());
    if (sk.str() == "plate") t.stl_plate = path_string(sn, file, skey);
    else if (sk.str() == "belt") t.stl_belt = path_string(sn, file, skey);
    else if (sk.str() == "pulley") t.stl_pulley = path_string(sn, file, skey);
    else if (sk.str() == "walls") {
      const toml::array* a = sn.as_array();
      if (!a) throw InputError(file, line_of(sn), skey, "must be an array of file names");
      for (const auto& e : *a) t.stl_walls.push_back(path_string(e, file, skey));
    } else {
      throw InputError(file, line_of(sn), skey, "unknown key (known: plate, belt, pulley, walls)");
    }
  }
}

void read_wear(const toml::node& node, const std::string& file, const std::string& key, DemTable& t) {
  const toml::table* wt = node.as_table();
  if (!wt) throw InputError(file, line_of(node), key, "must be a table ([dem.wear])");
  for (const auto& [wk, wn] : *wt) {
    const std::string wkey = key + "." + std::string(wk.str());
    const auto v = wn.value<double>();
    if (!v || !wn.is_number()) throw InputError(file, line_of(wn), wkey, "must be a number");
    WearInputs probe;
    set_wear(probe, std::string(wk.str()), *v, file, line_of(wn), wkey);
    t.wear.emplace_back(std::string(wk.str()), *v);
  }
}

// The keys of [dem] ("dem.") or of a table of fields ("dem.feed."), then the pairs its fields declare.
void read_fields(const toml::table& t, const std::string& file, const std::string& prefix, DemTable& out) {
  const std::string in_table = prefix.substr(4);  // "" or "feed."
  for (const auto& [k, node] : t) {
    const std::string key = prefix + std::string(k.str());
    const std::string name = in_table + std::string(k.str());
    if (in_table.empty() && k.str() == "stl") {
      read_stl(node, file, key, out);
    } else if (in_table.empty() && k.str() == "wear") {
      read_wear(node, file, key, out);
    } else if (in_table.empty() && is_field_table(name)) {
      const toml::table* sub = node.as_table();
      if (!sub) throw InputError(file, line_of(node), key, fmt::format("must be a table ([{}])", key));
      read_fields(*sub, file, key + ".", out);
    } else {
      const DemField* f = nullptr;
      for (const auto& c : dem_fields())
        if (c.key == name) f = &c;
      if (!f) {
        std::string tables;
        if (in_table.empty()) {
          for (const auto& c : dem_fields())
            if (const auto dot = c.key.find('.'); dot != std::string_view::npos) {
              const std::string t_name = fmt::format(", [dem.{}]", c.key.substr(0, dot));
              if (tables.find(t_name) == std::string::npos) tables += t_name;
            }
          tables += ", [dem.stl], [dem.wear]";
        }
        throw InputError(file, line_of(node), key, known_keys(in_table, tables));
      }
      out.settings.push_back({f, read_value(*f, node, file, key), line_of(node)});
    }
  }
}

const DemSetting* given(const std::vector<DemSetting>& settings, const DemField& f) {
  const DemSetting* last = nullptr;
  for (const auto& s : settings)
    if (s.field == &f) last = &s;
  return last;
}

}  // namespace

DemTable read_dem_table(const std::string& file, const std::string* text) {
  DemTable t;
  toml::table doc = text ? parse_toml_text(*text, file) : read_toml_file(file);
  const toml::node* dem_node = doc.get("dem");
  if (!dem_node) return t;
  t.file = file;
  const toml::table* dem = dem_node->as_table();
  if (!dem) throw InputError(file, line_of(*dem_node), "dem", "must be a table ([dem])");
  read_fields(*dem, file, "dem.", t);
  // What the fields declare of each other.
  for (const auto& s : t.settings) {
    const DemField& f = *s.field;
    const std::string key = "dem." + std::string(f.key);
    if (!f.above.empty())
      if (const DemSetting* below = given(t.settings, dem_field(f.above)); below && !(s.value.number > below->value.number))
        throw InputError(file, s.line, key, fmt::format("must be above {}", f.above.substr(f.above.rfind('.') + 1)));
    if (!f.needs.empty() && !given(t.settings, dem_field(f.needs)))
      throw InputError(file, s.line, key, fmt::format("needs {}", f.needs.substr(f.needs.rfind('.') + 1)));
  }
  return t;
}

namespace {
// A field's value into the settings: numbers in SI.
void set_field(RunSettings& s, const DemField& f, const DemValue& v) {
  DemValue si = v;
  if (f.kind == DemKind::number) si.number = v.number * f.to_si;
  f.set(s, si);
}
}  // namespace

void apply(const DemTable& t, RunSettings& s) {
  for (const auto& f : dem_fields())
    if (const DemSetting* g = given(t.settings, f); g && !f.selects_preset) set_field(s, f, g->value);
  for (const auto& [k, v] : t.wear) set_wear(s.wear, k, v, t.file, 0, "dem.wear." + k);
}

SettingsOverrides& SettingsOverrides::set(std::string_view option, double number) {
  DemValue v;
  v.number = number;
  v.whole = number >= 0.0 && number < 18446744073709551616.0 ? static_cast<std::uint64_t>(number) : 0;
  const DemField* f = dem_option(option);
  if (!f) throw InputError("", 0, std::string(option), "is no DEM setting");
  if (f->kind == DemKind::whole && (v.number != std::floor(v.number) || !(number >= 0.0)))
    throw InputError("", 0, std::string(option), "must be " + f->range_text());
  if (f->kind == DemKind::word) throw InputError("", 0, std::string(option), "must be " + f->range_text());
  std::erase_if(settings, [&](const DemSetting& s) { return s.field == f; });
  settings.push_back({f, v, 0});
  return *this;
}

SettingsOverrides& SettingsOverrides::set_whole(std::string_view option, std::uint64_t whole) {
  const DemField* f = dem_option(option);
  if (!f) throw InputError("", 0, std::string(option), "is no DEM setting");
  if (f->kind != DemKind::whole) return set(option, static_cast<double>(whole));
  DemValue v;
  v.whole = whole;
  v.number = static_cast<double>(whole);
  std::erase_if(settings, [&](const DemSetting& s) { return s.field == f; });
  settings.push_back({f, v, 0});
  return *this;
}

SettingsOverrides& SettingsOverrides::set(std::string_view option, std::string word) {
  const DemField* f = dem_option(option);
  if (!f) throw InputError("", 0, std::string(option), "is no DEM setting");
  if (f->kind != DemKind::word) throw InputError("", 0, std::string(option), "must be " + f->range_text());
  DemValue v;
  v.word = std::move(word);
  std::erase_if(settings, [&](const DemSetting& s) { return s.field == f; });
  settings.push_back({f, v, 0});
  return *this;
}

SettingsOverrides& SettingsOverrides::set_quality(Quality q) {
  for (const auto& f : dem_fields())
    if (f.selects_preset) return set(f.option, std::string(name(q)));
  return *this;
}

const DemValue* SettingsOverrides::find(std::string_view option) const {
  for (const auto& s : settings)
    if (s.field->option == option) return &s.value;
  return nullptr;
}

void SettingsOverrides::check() const {
  for (const auto& s : settings)
    if (const auto p = s.field->problem(s.value)) throw InputError("", 0, std::string(s.field->option), *p);
}

SettingsOverrides SettingsOverrides::at_quality(Quality q) const {
  SettingsOverrides o;
  o.threads = threads;
  for (const auto& s : settings)
    if (s.field->kept) o.settings.push_back(s);
  return o.set_quality(q);
}

RunSettings resolve(const DemTable& table, const SettingsOverrides& o, Quality fallback) {
  o.check();
  Quality q = fallback;
  for (const auto& f : dem_fields())
    if (f.selects_preset) {
      if (const DemSetting* g = given(o.settings, f)) q = *parse_quality(g->value.word);
      else if (const DemSetting* t = given(table.settings, f)) q = *parse_quality(t->value.word);
    }
  RunSettings s = preset(q);
  apply(table, s);
  for (const auto& f : dem_fields())
    if (const DemSetting* g = given(o.settings, f); g && !f.selects_preset) set_field(s, f, g->value);
  if (o.threads) s.threads = *o.threads;
  for (const auto& [k, v] : o.wear) set_wear(s.wear, k, v, "", 0, "wear." + k);
  // After every value is in: what an override adjusts depends on the value it ends with.
  for (const auto& f : dem_fields())
    if (f.after_override && given(o.settings, f)) f.after_override(s);
  check(s);
  return s;
}

void check(const RunSettings& s) {
  auto need = [](bool ok, const std::string& field, std::string problem) {
    if (!ok) throw InputError("", 0, field, problem);
  };
  // Every plain number of the table, in case code (a study's variant, a ladder) set it.
  for (const auto& f : dem_fields()) {
    DemValue v;
    if (const auto m = f.member_of<double>()) {
      if ((f.nan_unset && std::isnan(s.*m)) || (f.zero_in_settings && s.*m == 0.0)) continue;
      v.number = s.*m / f.to_si;
    } else if (const auto w = f.member_of<int>()) {
      if (s.*w < 0) need(false, field_name(f), "must be " + f.range_text());
      v.whole = static_cast<std::uint64_t>(s.*w);
    } else {
      continue;
    }
    if (const auto p = f.problem(v)) need(false, field_name(f), *p);
  }
  need(s.threads >= 0 && s.threads <= 256, "threads", "must be between 0 (all) and 256");
  need(s.min_window < s.max_time, field_name(&RunSettings::min_window),
       fmt::format("steady window {} s must be shorter than the simulated time {} s", s.min_window, s.max_time));
  need(s.insert_depth > 0.0, field_name(&RunSettings::insert_low), "the insertion face must lie above the belt");
  need(s.sample_interval > 0.0 && s.snapshot_interval >= s.sample_interval, "sample_interval",
       "snapshots must not be more frequent than force samples");
}

std::string canonical(const RunSettings& s) {
  std::string o;
  auto put = [&](const char* k, double v) { o += fmt::format("{} = {:.17g}\n", k, v); };
  o += fmt::format("quality = {}\ncontact = {}\nseed = {}\n", name(s.quality), name(s.contact), s.seed);
  // Spheres keep the key they had before shapes existed, so cached sphere runs stay valid.
  if (s.particle_shape != ParticleShape::sphere) o += fmt::format("shape = {}\n", name(s.particle_shape));
  put("particle_diameter", s.particle_diameter);
  put("shear_modulus_scale", s.shear_modulus_scale);
  put("dt_fraction", s.dt_fraction);
  put("rayleigh_fraction", s.rayleigh_fraction);
  put("feed_length", s.feed_length);
  put("free_belt", s.free_belt);
  put("belt_upstream", s.belt_upstream);
  put("insert_low", s.insert_low);
  put("insert_depth", s.insert_depth);
  put("insert_speed_down", s.insert_speed_down);
  put("insert_interval", s.insert_interval);
  put("relax_rate", s.relax_rate);
  put("relax_past", s.relax_past);
  put("min_time", s.min_time);
  put("max_time", s.max_time);
  put("min_window", s.min_window);
  put("sample_interval", s.sample_interval);
  put("snapshot_interval", s.snapshot_interval);
  put("detect_block", s.detect_block);
  put("mean_block", s.mean_block);
  put("detect_tail", s.detect_tail);
  put("skin_fraction", s.skin_fraction);
  put("momentum_plane_fraction", s.momentum_plane_fraction);
  // The dataset's feeder: only what differs from the recipe, so older cached runs keep their key.
  if (s.rolling_lever_effective) o += "rolling_lever = effective\n";
  // The window's rule changes where a run stops and what it averages; the rig's rule keeps old keys.
  if (s.steady_all_loads) o += "steady_on = all\n";
  if (s.relax_all) o += "relax_all = true\n";
  if (s.relax_from_face) o += "relax_from_face = true\n";
  if (s.insert_at_face) o += "insert_at_face = true\n";
  if (std::isfinite(s.face_end)) {
    put("face_end", s.face_end);
    put("face_end_time", s.face_end_time);
  }
  if (std::isfinite(s.face_width)) put("face_width", s.face_width);
  if (std::isfinite(s.belt_start_x)) put("belt_start_x", s.belt_start_x);
  // Keys of runs without a finer plate or a Finnie model of their own stay as they were. Finnie's
  // K and n enter the per-impact sums; every other wear input only scales the stored sums.
  if (s.plate_cells > 0) o += fmt::format("plate_cells = {}\n", s.plate_cells);
  // The map grid bins contacts and changes no force: only a size other than the default keys apart.
  if (s.map_cell != RunSettings{}.map_cell) put("map_cell", s.map_cell);
  const wear::FinnieParams finnie_default;
  if (s.wear.finnie.force_ratio != finnie_default.force_ratio) put("finnie_force_ratio", s.wear.finnie.force_ratio);
  if (s.wear.finnie.velocity_exponent != finnie_default.velocity_exponent)
    put("finnie_velocity_exponent", s.wear.finnie.velocity_exponent);
  // threads are left out on purpose: 1 and N threads give bit-identical results (dem/world.h).
  return o;
}

}  // namespace chutelab::dem::station
