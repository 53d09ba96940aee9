#include "dem/station/settings.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <thread>
#include <filesystem>
#include <fmt/format.h>
#include <toml++/toml.h>

#include "core/free_cores.h"
#include "core/input_error.h"
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

double positive_number(const toml::node& n, const std::string& file, const std::string& key) {
  const auto v = n.value<double>();
  if (!v || !n.is_number() || !std::isfinite(*v) || !(*v > 0.0))
    throw InputError(file, line_of(n), key, "must be a positive number");
  return *v;
}

std::string path_string(const toml::node& n, const std::string& file, const std::string& key) {
  const auto v = n.value<std::string>();
  if (!v || v->empty()) throw InputError(file, line_of(n), key, "must be a file name (string)");
  namespace fs = std::filesystem;
  fs::path p(*v);
  if (p.is_relative()) p = fs::path(file).parent_path() / p;
  if (!fs::exists(p)) throw InputError(file, line_of(n), key, fmt::format("file '{}' not found", p.string()));
  return p.string();
}

double finite_number(const toml::node& n, const std::string& file, const std::string& key) {
  const auto v = n.value<double>();
  if (!v || !n.is_number() || !std::isfinite(*v)) throw InputError(file, line_of(n), key, "must be a number");
  return *v;
}

// [dem.feed]: lengths in mm, the rest in the units its names say.
void read_feed_table(const toml::node& node, const std::string& file, const std::string& key, DemTable::Feed& f) {
  const toml::table* t = node.as_table();
  if (!t) throw InputError(file, line_of(node), key, "must be a table ([dem.feed])");
  for (const auto& [k, n] : *t) {
    const std::string fk = key + "." + std::string(k.str());
    const std::string_view kv = k.str();
    const toml::node& value = n;  // a structured binding cannot be captured by clang 14
    auto choice = [&](const char* a, const char* b) {
      const auto v = value.value<std::string>();
      if (!v || (*v != a && *v != b))
        throw InputError(file, line_of(value), fk, fmt::format("must be \"{}\" or \"{}\"", a, b));
      return *v == a;
    };
    if (kv == "face_length_mm") f.face_length = positive_number(n, file, fk) * 1e-3;
    else if (kv == "face_width_mm") f.face_width = positive_number(n, file, fk) * 1e-3;
    else if (kv == "face_low_mm") f.face_low = positive_number(n, file, fk) * 1e-3;
    else if (kv == "face_high_mm") f.face_high = positive_number(n, file, fk) * 1e-3;
    else if (kv == "face_end_mm") f.face_end = finite_number(n, file, fk) * 1e-3;
    else if (kv == "face_end_time_s") f.face_end_time = finite_number(n, file, fk);
    else if (kv == "insert_speed_down_mps") f.insert_speed_down = finite_number(n, file, fk);
    else if (kv == "relax_rate_per_s") {
      const double v = finite_number(n, file, fk);
      if (v < 0.0) throw InputError(file, line_of(n), fk, "must be zero (no relaxation) or positive");
      f.relax_rate = v;
    } else if (kv == "relax_past_mm") f.relax_past = finite_number(n, file, fk) * 1e-3;
    else if (kv == "relax_components") f.relax_all = choice("all", "along");
    else if (kv == "relax_end") f.relax_from_face = choice("face", "landing");
    else if (kv == "insertion") f.insert_at_face = choice("face", "box");
    else if (kv == "belt_start_mm") f.belt_start_x = finite_number(n, file, fk) * 1e-3;
    else
      throw InputError(file, line_of(n), fk,
                       "unknown key (known: face_length_mm, face_width_mm, face_low_mm, face_high_mm, face_end_mm, "
                       "face_end_time_s, insert_speed_down_mps, insertion, relax_rate_per_s, relax_components, "
                       "relax_end, relax_past_mm, belt_start_mm)");
  }
  if (f.face_low && f.face_high && !(*f.face_high > *f.face_low))
    throw InputError(file, line_of(node), key + ".face_high_mm", "must be above face_low_mm");
  if (f.face_end_time && !f.face_end)
    throw InputError(file, line_of(node), key + ".face_end_time_s", "needs face_end_mm");
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
  for (const auto& [k, node] : *dem) {
    const std::string key = "dem." + std::string(k.str());
    const std::string_view kv = k.str();
    if (kv == "quality") {
      const auto v = node.value<std::string>();
      const auto q = v ? parse_quality(*v) : std::nullopt;
      if (!q) throw InputError(file, line_of(node), key, "must be \"quick\", \"standard\" or \"paper\"");
      t.quality = q;
    } else if (kv == "contact") {
      const auto v = node.value<std::string>();
      const auto c = v ? parse_contact(*v) : std::nullopt;
      if (!c) throw InputError(file, line_of(node), key, "must be one of " + NormalLaw::keys());
      t.contact = c;
    } else if (kv == "shape") {
      const auto v = node.value<std::string>();
      const auto p = v ? parse_shape(*v) : std::nullopt;
      if (!p) throw InputError(file, line_of(node), key, "must be \"sphere\" or \"clump\"");
      t.shape = p;
    } else if (kv == "particle_diameter_mm") {
      t.particle_diameter = positive_number(node, file, key) * 1e-3;
    } else if (kv == "shear_modulus_scale") {
      t.shear_modulus_scale = positive_number(node, file, key);
    } else if (kv == "dt_fraction") {
      t.dt_fraction = positive_number(node, file, key);
    } else if (kv == "max_time_s") {
      t.max_time = positive_number(node, file, key);
    } else if (kv == "min_window_s") {
      t.min_window = positive_number(node, file, key);
    } else if (kv == "feed_length_mm") {
      t.feed_length = positive_number(node, file, key) * 1e-3;
    } else if (kv == "skin_fraction") {
      t.skin_fraction = positive_number(node, file, key);
    } else if (kv == "seed") {
      const auto v = node.value<std::int64_t>();
      if (!v || !node.is_integer() || *v < 0) throw InputError(file, line_of(node), key, "must be a non-negative integer");
      t.seed = static_cast<std::uint64_t>(*v);
    } else if (kv == "rolling_lever") {
      const auto v = node.value<std::string>();
      if (!v || (*v != "particle" && *v != "effective"))
        throw InputError(file, line_of(node), key, "must be \"particle\" (reference study Eq 10) or \"effective\" (LIGGGHTS cdt)");
      t.rolling_lever_effective = *v == "effective";
    } else if (kv == "steady_on") {
      const auto v = node.value<std::string>();
      if (!v || (*v != "normal" && *v != "all"))
        throw InputError(file, line_of(node), key,
                         "must be \"normal\" (the steady window judged on R_n, as the LIGGGHTS rig did) or \"all\" "
                         "(on R_n, R_s and the moment)");
      t.steady_all_loads = *v == "all";
    } else if (kv == "feed") {
      read_feed_table(node, file, key, t.feed);
    } else if (kv == "plate_cells") {
      const auto v = node.value<std::int64_t>();
      if (!v || !node.is_integer() || *v < 0 || *v > 400)
        throw InputError(file, line_of(node), key, "must be an integer from 0 (the plate as two triangles) to 400");
      t.plate_cells = static_cast<int>(*v);
    } else if (kv == "map_cell_mm") {
      const auto v = node.value<double>();
      if (!v || !(*v == 0.0 || (*v >= 1.0 && *v <= 1000.0)))
        throw InputError(file, line_of(node), key, "must be 0 (the plate's own triangles) or from 1 to 1000 mm");
      t.map_cell = *v * 1e-3;
    } else if (kv == "wear") {
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
    } else if (kv == "stl") {
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
    } else {
      throw InputError(file, line_of(node), key,
                       "unknown key (known: quality, particle_diameter_mm, shear_modulus_scale, dt_fraction, "
                       "contact, shape, seed, max_time_s, min_window_s, steady_on, feed_length_mm, skin_fraction, rolling_lever, plate_cells, "
                       "map_cell_mm, "
                       "[dem.feed], [dem.stl], [dem.wear])");
    }
  }
  return t;
}

void apply(const DemTable& t, RunSettings& s) {
  if (t.particle_diameter) s.particle_diameter = *t.particle_diameter;
  if (t.shear_modulus_scale) s.shear_modulus_scale = *t.shear_modulus_scale;
  if (t.dt_fraction) s.dt_fraction = *t.dt_fraction;
  if (t.contact) s.contact = *t.contact;
  if (t.shape) s.particle_shape = *t.shape;
  if (t.seed) s.seed = *t.seed;
  if (t.max_time) s.max_time = *t.max_time;
  if (t.min_window) s.min_window = *t.min_window;
  if (t.feed_length) s.feed_length = *t.feed_length;
  if (t.skin_fraction) s.skin_fraction = *t.skin_fraction;
  if (t.rolling_lever_effective) s.rolling_lever_effective = *t.rolling_lever_effective;
  if (t.steady_all_loads) s.steady_all_loads = *t.steady_all_loads;
  const DemTable::Feed& f = t.feed;
  if (f.face_length) s.feed_length = *f.face_length;
  if (f.face_width) s.face_width = *f.face_width;
  if (f.face_low) s.insert_low = *f.face_low;
  if (f.face_high) s.insert_depth = *f.face_high - s.insert_low;
  if (f.face_end) s.face_end = *f.face_end;
  if (f.face_end_time) s.face_end_time = *f.face_end_time;
  if (f.insert_speed_down) s.insert_speed_down = *f.insert_speed_down;
  if (f.relax_rate) s.relax_rate = *f.relax_rate;
  if (f.relax_past) s.relax_past = *f.relax_past;
  if (f.relax_all) s.relax_all = *f.relax_all;
  if (f.relax_from_face) s.relax_from_face = *f.relax_from_face;
  if (f.insert_at_face) s.insert_at_face = *f.insert_at_face;
  if (f.belt_start_x) s.belt_start_x = *f.belt_start_x;
  if (t.plate_cells) s.plate_cells = *t.plate_cells;
  if (t.map_cell) s.map_cell = *t.map_cell;
  for (const auto& [k, v] : t.wear) set_wear(s.wear, k, v, t.file, 0, "dem.wear." + k);
}

RunSettings resolve(const DemTable& table, const SettingsOverrides& o, Quality fallback) {
  const Quality q = o.quality ? *o.quality : table.quality ? *table.quality : fallback;
  RunSettings s = preset(q);
  apply(table, s);
  if (o.particle_diameter) s.particle_diameter = *o.particle_diameter;
  if (o.shear_modulus_scale) s.shear_modulus_scale = *o.shear_modulus_scale;
  if (o.dt_fraction) s.dt_fraction = *o.dt_fraction;
  if (o.contact) s.contact = *o.contact;
  if (o.shape) s.particle_shape = *o.shape;
  if (o.seed) s.seed = *o.seed;
  if (o.threads) s.threads = *o.threads;
  if (o.plate_cells) s.plate_cells = *o.plate_cells;
  if (o.map_cell) s.map_cell = *o.map_cell;
  for (const auto& [k, v] : o.wear) set_wear(s.wear, k, v, "", 0, "wear." + k);
  if (o.steady_all_loads) s.steady_all_loads = *o.steady_all_loads;
  if (o.max_time) {
    s.max_time = *o.max_time;
    s.min_time = std::min(s.min_time, s.max_time);
    s.min_window = std::min(s.min_window, 0.5 * s.max_time);
  }
  check(s);
  return s;
}

void check(const RunSettings& s) {
  auto need = [](bool ok, const char* field, std::string problem) {
    if (!ok) throw InputError("", 0, field, problem);
  };
  need(s.particle_diameter >= 0.0 && s.particle_diameter < 0.2, "diameter_mm",
       fmt::format("particle diameter must be in (0, 200) mm, got {} mm", s.particle_diameter * 1e3));
  need(s.shear_modulus_scale > 0.0 && s.shear_modulus_scale <= 1e3, "shear_modulus_scale",
       fmt::format("must be in (0, 1000], got {}", s.shear_modulus_scale));
  need(s.dt_fraction > 0.0 && s.dt_fraction <= 0.5, "dt_fraction",
       fmt::format("must be in (0, 0.5] of the collision time, got {}", s.dt_fraction));
  need(s.particle_shape == ParticleShape::sphere || s.particle_shape == ParticleShape::clump, "shape",
       "must be sphere or clump");
  need(s.threads >= 0 && s.threads <= 256, "threads", "must be between 0 (all) and 256");
  need(s.plate_cells >= 0 && s.plate_cells <= 400, "plate_cells", fmt::format("must be from 0 to 400, got {}", s.plate_cells));
  need(s.map_cell == 0.0 || (s.map_cell >= 1e-3 && s.map_cell <= 1.0), "map_cell_mm",
       fmt::format("must be 0 (the plate's own triangles) or from 1 to 1000 mm, got {} mm", s.map_cell * 1e3));
  need(s.max_time > 0.0 && s.max_time <= 100.0, "max_time_s", fmt::format("must be in (0, 100] s, got {}", s.max_time));
  need(s.min_window > 0.0 && s.min_window < s.max_time, "min_window_s",
       fmt::format("steady window {} s must be shorter than the simulated time {} s", s.min_window, s.max_time));
  need(s.feed_length > 0.0 && s.feed_length <= 10.0, "feed_length_mm", "must be in (0, 10000] mm");
  need(s.insert_low > 0.0 && s.insert_depth > 0.0, "dem.feed.face_low_mm", "the insertion face must lie above the belt");
  need(s.relax_rate >= 0.0 && s.relax_rate <= 1e4, "dem.feed.relax_rate_per_s", "must be in [0, 10000] 1/s");
  need(!std::isfinite(s.face_end) || s.face_end >= 0.0, "dem.feed.face_end_mm",
       "the insertion face must end upstream of the pulley (face_end_mm >= 0)");
  need(!std::isfinite(s.face_width) || (s.face_width > 0.0 && s.face_width <= 10.0), "dem.feed.face_width_mm",
       "must be in (0, 10000] mm");
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
