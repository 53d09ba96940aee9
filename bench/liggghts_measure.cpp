// Measures a finished LIGGGHTS station run with chutelab's sensors (dem/liggghts/run.h
// measure_run), for decks run by hand or edited for an experiment (bench/LIGGGHTS_ENGINE.md).
// Usage: liggghts_measure DATASET CONDITION QUALITY SIM_TIME_S RUN_DIR OUT_DIR
#include <filesystem>
#include <iostream>

#include <fmt/format.h>

#include "core/input_error.h"
#include "dem/liggghts/run.h"
#include "validation/dataset.h"

using namespace chutelab;

int main(int argc, char** argv) {
  if (argc != 7) {
    std::cerr << "usage: liggghts_measure DATASET CONDITION QUALITY SIM_TIME_S RUN_DIR OUT_DIR\n";
    return 2;
  }
  try {
    namespace fs = std::filesystem;
    namespace st = dem::station;
    const fs::path dir(argv[1]);
    const Setup setup = validation::read_setup(dir / "setup.toml");
    const auto stations = validation::read_conditions(dir / "conditions.csv", setup, nullptr);
    const Station* station = nullptr;
    for (const auto& s : stations)
      if (s.condition == argv[2]) station = &s;
    if (!station) throw InputError((dir / "conditions.csv").string(), 0, "CONDITION", "no such condition");
    st::SettingsOverrides ov;
    const auto quality = st::parse_quality(argv[3]);
    if (!quality) throw InputError("", 0, "QUALITY", "must be quick, standard or paper");
    ov.set_quality(*quality);
    dem::liggghts::Options o;
    o.settings = st::resolve(st::read_dem_table((dir / "setup.toml").string()), ov);
    o.sim_time = std::stod(argv[4]);
    const auto r = dem::liggghts::measure_run(*station, o, argv[5]);
    st::write_result_files(argv[6], r);
    std::cout << fmt::format("R_n {:.3f} +- {:.3f} N, y_R {:.1f} mm, layer speed {:.3f} m/s, mass flux {:.3f} kg/s, "
                             "window {:.2f}-{:.2f} s\n",
                             r.normal_force.value, r.normal_force.se, r.impact_point_y.value * 1e3, r.layer_speed.value,
                             r.mass_flux.value, r.window.start, r.window.end);
    return 0;
  } catch (const InputError& e) {
    std::cerr << "liggghts_measure: " << e.what() << "\n";
    return 2;
  }
}
