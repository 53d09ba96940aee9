#pragma once
// Every number that shapes a DEM run of the transfer station besides the Station (rig + condition)
// itself, in one place: the quality presets, the scaling options of the reference study's Table 6 and the
// numerics. Precedence: preset(quality) < the dataset's optional [dem] table < command-line flags.
#include <atomic>
#include <cstdint>
#include <functional>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "core/option_check.h"
#include "dem/contact/normal_laws.h"
#include "dem/wear/archard.h"
#include "dem/wear/finnie.h"

namespace chutelab::dem::station {

// Inputs of the wear models of the plate maps (dem/station/plate_map.h): [dem.wear] and simulate's
// flags. Defaults in dem/wear/archard.h and dem/wear/finnie.h.
struct WearInputs {
  wear::ArchardParams archard;
  wear::FinnieParams finnie;
  double exposure_hours = 0.0;  // h of operation a measured wear depth covers; 0 = no wear_depth_um
};

// One settable wear input: its [dem.wear] key (= the command line's flag without its dashes and with '-' for '_'),
// what it means, and where it lives.
struct WearField {
  const char* key;
  const char* help;
  double WearInputs::*top;
  double wear::ArchardParams::*archard;
  double wear::FinnieParams::*finnie;
  bool allow_zero;
  double& ref(WearInputs& w) const {
    return top ? w.*top : archard ? w.archard.*archard : w.finnie.*finnie;
  }
};
const std::vector<WearField>& wear_fields();

enum class Quality { quick, standard, paper };
std::string_view name(Quality q);
std::optional<Quality> parse_quality(std::string_view s);

// The contact law of a run: one of the registered normal laws ([dem] contact, --contact), by its key.
using ContactLaw = NormalLaw;
std::string_view name(ContactLaw c);
std::optional<ContactLaw> parse_contact(std::string_view s);

// Particle representation (reference study Fig. 4): single spheres (4b) or the two-overlapping-sphere clump of
// the reference study's shaped pellet (4c).
enum class ParticleShape { sphere, clump };
std::string_view name(ParticleShape p);
std::optional<ParticleShape> parse_shape(std::string_view s);

struct RunSettings {
  Quality quality = Quality::quick;

  // --- scaling (reference study Table 6) ---
  // Particle diameter, m; 0 = the dataset's material (particle_diameter_mm). Scaling the diameter
  // up keeps the mass flow (fewer, heavier particles); the reference study found the mean plate force similar
  // at 9 and 13.6 mm, with larger fluctuations.
  double particle_diameter = 0.0;
  // Multiplies Young's modulus (and so the shear modulus G = E / 2(1 + nu)) of particles and walls.
  // The reference study varied G by x10 and /10 with small changes in the mean plate force; a softer material
  // allows a longer time step (dt ~ E^-2/5).
  double shear_modulus_scale = 1.0;
  // dt = dt_fraction * Hertz collision time (reference study Eq 11) at the characteristic impact speed; the
  // reference study used 1/10 and tested 1/20. Also capped at rayleigh_fraction of the Rayleigh time.
  double dt_fraction = 0.1;
  double rayleigh_fraction = 0.2;
  ContactLaw contact;  // Hertz-Mindlin
  // clump: the feed inserts the reference study's pellet (dem::ClumpShape::reference_pellet, the shape `chutelab
  // calibrate` uses) with spheres of diameter `particle_diameter`, in random orientations, at the
  // condition's mass flow (fewer bodies than spheres of that size: each weighs ~1.1 spheres).
  ParticleShape particle_shape = ParticleShape::sphere;

  // --- feed (after the LIGGGHTS rig's recipe, datasets/liggghts-rig/README.md; see feeder_relaxation.h) ---
  // Along the belt, from upstream: belt_upstream, the insertion face (feed_length), the landing of
  // the last inserted particles (V_b times their free-fall time) plus relax_past, where the feeder
  // relaxation ends, then free_belt of belt before the pulley's tangent point.
  double feed_length = 0.40;         // m, length of the insertion face along the belt
  double free_belt = 0.20;           // m of belt without relaxation before the pulley (the rig: 0.2-0.43 m)
  double belt_upstream = 0.025;      // m of belt behind the insertion face
  double insert_low = 0.030;         // m above the belt: bottom of the insertion box (at least 2.5 d)
  double insert_depth = 0.032;       // m: height of the insertion box (at least 3.5 d)
  double insert_speed_down = 1.0;    // m/s, downward velocity of inserted particles
  double insert_interval = 0.003;    // s between insertion events (each forces a neighbour rebuild)
  double relax_rate = 50.0;          // 1/s, feeder relaxation of the velocity towards the belt's
  double relax_past = 0.05;          // m past the landing of the last inserted particles
  // How a dataset's own feeder differs from the recipe above ([dem.feed], README "DEM"): the
  // experiment as it was run, so that the DEM reproduces the rig it is compared with. Unset (NaN,
  // false) keeps the recipe, and the cache keys of runs made before these keys existed.
  // relax_all: relax the whole velocity towards the belt's, the fall included (the LIGGGHTS rig),
  // instead of the along-belt components and rebounds only.
  bool relax_all = false;
  // relax_from_face: the relaxation ends relax_past after the insertion face's downstream end, not
  // after the landing of the last inserted particles.
  bool relax_from_face = false;
  // insert_at_face: particles enter through the insertion box's lower face, the way a stream
  // inserter through a face does (LIGGGHTS' fix insert/stream): placed in the box, they move
  // rigidly straight down at insert_speed_down, pushing what they touch but pushed by nothing, and
  // are released with the full insertion velocity where their centre crosses the face. Unset: they
  // are free from where they are placed in the box.
  bool insert_at_face = false;
  // Where the insertion face ends, upstream of the pulley's tangent point: face_end + V_b *
  // face_end_time (m; the LIGGGHTS rig: 0.15 m + 0.075 s V_b). Set: free_belt is not used.
  double face_end = std::numeric_limits<double>::quiet_NaN();
  double face_end_time = 0.0;        // s
  double face_width = std::numeric_limits<double>::quiet_NaN();  // m across the belt (default: loaded width)
  double belt_start_x = std::numeric_limits<double>::quiet_NaN(); // m, x of the belt's upstream end
  // Lever arm of the particle-particle rolling torque: false = the particle's radius R_i (reference study
  // Eq 10); true = the effective radius R_i R_j / (R_i + R_j), as LIGGGHTS' `rolling_friction cdt`
  // defines it (half of R_i for the station's equal spheres). Against walls both use R_i.
  bool rolling_lever_effective = false;

  // --- time ---
  double min_time = 0.5;             // s, never stop before
  double max_time = 1.3;             // s, always stop here
  double min_window = 0.5;           // s, steady window needed for an early stop
  double sample_interval = 0.003;    // s, plate forces averaged over this (LIGGGHTS: 100 steps)
  double snapshot_interval = 0.010;  // s, particle sensors (LIGGGHTS: 333 steps)
  double detect_block = 0.05;        // s, blocks compared for the steady-state detection
  double mean_block = 0.1;           // s, blocks for the standard error of the steady means
  double detect_tail = 0.4;          // s, reference: mean of the last detect_tail
  // Which of the plate load cell's channels the steady window is judged on: false = R_n alone, the
  // LIGGGHTS rig's rule; true = R_n, R_s and the moment (so the impact point), the window starting
  // where the last of them became steady. The build-up on the plate forms more slowly than the load,
  // so R_s settles later (bench/WINDOW.md): a station that has run for long is compared with true.
  bool steady_all_loads = false;

  // --- numerics ---
  // Verlet skin as a fraction of the particle radius. Measured (bench/log/STATION.md): 1.0 halves the
  // rebuilds of 0.5 at the same cost per step; 1.5 gains nothing more.
  double skin_fraction = 1.0;
  // OpenMP threads; results do not depend on it (dem/world.h). 0 = automatic: one per core that
  // other processes leave free now (core/free_cores.h; at least 1). On a shared 2-core machine two
  // threads that wait for each other in every step's parallel loops ran 2-10x slower than one
  // (bench/log/STATION.md).
  int threads = 0;
  // Threads the run may add as they free up (campaign::JobContext::idle); read once per force
  // sample. Not part of the result (nor of the cache key), like `threads`.
  const std::atomic<int>* extra_threads = nullptr;
  std::uint64_t seed = 1;            // insertion random numbers

  // --- sensors ---
  // Face of the control volume of the momentum balance, as a fraction of the way from the pulley to
  // the plate: mid-flight, upstream of the cushion of slowed particles in front of the plate (both
  // DEMs show the stream slowing within ~0.1 m of the plate, README "DEM").
  double momentum_plane_fraction = 0.5;

  // --- plate maps ---
  // Rows of cells down the generated plate (two triangles a cell, columns chosen for square cells);
  // 0 = the plate as two triangles (the maps then have two cells). The mesh changes round-off
  // only, not the physics, but it is part of the cache key.
  int plate_cells = 0;
  // Cell size of the generated plate's maps when the plate is not meshed (plate_cells = 0): the
  // contacts are binned on a grid of such cells (plate_map.h MapGrid) while the World keeps the
  // plate as two triangles, so the physics is that of the coarse plate, bit for bit. 0 = the map of
  // the plate's own triangles (two cells). Binning only: a different size keys another cache entry,
  // the default none (entries recorded before the grid keep their key and their coarse map).
  double map_cell = 0.010;
  WearInputs wear;
};

// The presets. quick: for tests and first looks (13.6 mm spheres, soft, short belt, short time);
// standard: the dataset's own particles and modulus with the LIGGGHTS rig's feed; paper: the
// reference study's 5.6 mm spheres. Documented value by value in settings.cpp.
RunSettings preset(Quality q);

// The thread count a run uses: `threads` if > 0, else the automatic choice above.
int effective_threads(int threads);

// A value of one [dem] setting as given, in the setting's unit at the boundary: a number, a whole
// number (exact: a seed has more digits than a double holds) or a word.
struct DemValue {
  double number = 0.0;
  std::uint64_t whole = 0;
  std::string word;
};

enum class DemKind { number, whole, word };

// A word a [dem] setting accepts, and what it means (shown in its error message; "" = nothing to add).
struct DemWord {
  std::string word;
  std::string meaning;
};

// One [dem] setting of setup.toml, declared once (dem_fields()): the reader of [dem], its
// known-keys message, the overrides of the command line (simulate's flags) and of the library,
// the range checks and the dataset reference page all come from this table.
struct DemField {
  std::string_view key;          // in [dem]; "feed.KEY" in [dem.feed]
  std::string_view option;       // the override's neutral key (core/input_error.h; simulate's flag); "" = setup.toml only
  DemKind kind;
  std::string_view unit;         // at the boundary ("" = none)
  double to_si;                  // boundary value * to_si = the RunSettings value (numbers)
  double lo, hi;                 // range at the boundary (numbers, whole numbers)
  bool lo_open, hi_open;
  std::string_view zero_means;   // non-empty: 0 is accepted besides the range, and means this
  std::string_view help;
  std::function<std::vector<DemWord>()> words;           // DemKind::word: the accepted words
  std::function<void(RunSettings&, const DemValue&)> set;  // numbers already in SI
  // The member of RunSettings the setting sets (none: it sets a derived value). A plain number
  // (double, in SI) or a whole number (int) is checked again by check(); a flag is set by two words.
  using Member = std::variant<std::monostate, double RunSettings::*, int RunSettings::*, bool RunSettings::*,
                              std::uint64_t RunSettings::*, Quality RunSettings::*, ContactLaw RunSettings::*,
                              ParticleShape RunSettings::*>;
  Member member;
  // The member if it is of type T, else nullptr.
  template <class T>
  T RunSettings::*member_of() const {
    const auto* m = std::get_if<T RunSettings::*>(&member);
    return m ? *m : nullptr;
  }
  bool nan_unset = false;        // NaN in `member` means not given (nothing to check)
  bool zero_in_settings = false; // 0 in `member` means the dataset's value (a preset's; no input)
  std::string_view above = {};   // must lie above this key's value when both are given
  std::string_view needs = {};   // is read only together with this key
  bool selects_preset = false;   // the quality: picks the preset the rest goes on top of
  bool kept = false;             // the user's choice at any quality (a cheaper signature run keeps it)
  std::function<void(RunSettings&)> after_override = {};  // what an override also adjusts
  // The range as an option's rule (core/option_check.h), naming the option `key`; with zero_means
  // its lower end is 0 (problem() then refuses what lies between).
  options::NumberRule rule(std::string_view key) const;
  // Why `v` is refused, in words (no value: accepted).
  std::optional<std::string> problem(const DemValue& v) const;
  // The accepted values in words: "a finite number in (0, 0.5]", "\"quick\", \"standard\" or \"paper\"".
  std::string range_text() const;
};
const std::vector<DemField>& dem_fields();
// The field of [dem] key `key` (throws std::logic_error when there is none: a caller's mistake).
const DemField& dem_field(std::string_view key);
// The (first) field that sets `member`: code names a setting by its member, never by its key
// (throws std::logic_error when no field sets it: a caller's mistake).
template <class T>
const DemField& dem_field(T RunSettings::*member) {
  for (const auto& f : dem_fields())
    if (f.member_of<T>() == member) return f;
  throw std::logic_error("no [dem] field sets this member of RunSettings");
}
// How messages name a setting: its option, else "dem." + its key.
std::string field_name(const DemField& f);
template <class T>
std::string field_name(T RunSettings::*member) {
  return field_name(dem_field(member));
}
// The field an override names by `option`; nullptr when none does.
const DemField* dem_option(std::string_view option);

// A [dem] setting as given: its field, its value and where it was given (0: not in a file).
struct DemSetting {
  const DemField* field = nullptr;
  DemValue value;
  long line = 0;
};

// Optional [dem] table of setup.toml (README "DEM"). Every key is optional.
struct DemTable {
  std::string file;                          // setup.toml it came from ("" = none)
  std::vector<DemSetting> settings;          // dem_fields() given, in the file's order
  std::vector<std::pair<std::string, double>> wear;  // [dem.wear] key -> value (checked)
  // STL meshes (mm, DESIGN.md frame) replacing generated parts; absolute paths after reading.
  std::optional<std::string> stl_plate, stl_belt, stl_pulley;
  std::vector<std::string> stl_walls;        // extra static walls (side panels, skirts, chute)
};

// Reads [dem] from a setup.toml (absent table = all empty). Unknown keys and bad values throw
// InputError naming the file, line and key. With `text`, the file as already read (a dataset's own);
// relative STL paths are still taken from the file's folder.
DemTable read_dem_table(const std::string& setup_file, const std::string* text = nullptr);

// Overrides a preset with what a [dem] table sets (quality is handled by the caller).
void apply(const DemTable& t, RunSettings& s);

// What a command line (or a harness configuration) sets explicitly; wins over the [dem] table.
struct SettingsOverrides {
  std::vector<DemSetting> settings;  // dem_fields() with an option, by it
  std::optional<int> threads;
  std::vector<std::pair<std::string, double>> wear;  // wear_fields() key -> value
  // Sets the setting whose option is `option` (a number in its unit at the boundary, a whole
  // number, a word); a later value of the same option replaces an earlier one. An option no field
  // has throws InputError naming it; the value is checked by check() (resolve calls it).
  SettingsOverrides& set(std::string_view option, double number);
  SettingsOverrides& set_whole(std::string_view option, std::uint64_t whole);
  SettingsOverrides& set(std::string_view option, std::string word);
  SettingsOverrides& set_quality(Quality q);
  // The value set for `option`, if any.
  const DemValue* find(std::string_view option) const;
  // Throws InputError naming the option of the first value out of its field's range.
  void check() const;
  // The overrides of a run at quality `q` instead: the threads and the settings that are the
  // user's at any quality (DemField::kept).
  SettingsOverrides at_quality(Quality q) const;
};

// preset(quality) < [dem] table < overrides; the quality itself: overrides, then the table, then
// `fallback`. Checks the result.
RunSettings resolve(const DemTable& table, const SettingsOverrides& o, Quality fallback = Quality::quick);

// Checks ranges; throws InputError naming the field.
void check(const RunSettings& s);

// One line per field, "key = value" with full precision: the settings' share of a cache key.
std::string canonical(const RunSettings& s);

// Sets a wear input by its key; throws InputError (file, line, field) for an unknown key or a value
// out of range.
void set_wear(WearInputs& w, const std::string& key, double value, const std::string& file = "", long line = 0,
              const std::string& field = "");

}  // namespace chutelab::dem::station
