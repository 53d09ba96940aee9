#include "logs/sensor_model.h"

#include <cmath>
#include <fmt/format.h>
#include <utility>
#include <vector>

#include "core/input_error.h"
#include "core/message.h"
#include "core/toml_file.h"

namespace chutelab::logs {

SensorModel read_sensor_model(const std::filesystem::path& path) {
  const std::string file = path.string();
  const toml::table doc = read_toml_file(file);
  SensorModel m;
  struct Key {
    const char* name;
    double* v;
    double lo, hi;
  };
  const std::vector<Key> keys = {
      {"rate_hz", &m.rate_hz, 1.0, 1e5},          {"lowpass_hz", &m.lowpass_hz, 0.0, 1e5},
      {"white_N", &m.white_N, 0.0, 1e6},          {"corr_fraction", &m.corr_fraction, 0.0, 1.0},
      {"corr_s", &m.corr_s, 1e-4, 1e3},           {"resolution_N", &m.resolution_N, 0.0, 1e3},
      {"gain_u", &m.gain_u, 0.0, 0.5},            {"zero_offset_N", &m.zero_offset_N, 0.0, 1e6},
      {"drift_N", &m.drift_N, -1e6, 1e6},         {"creep_per_s", &m.creep_per_s, -0.1, 0.1},
      {"tare_s", &m.tare_s, 0.0, 3600.0},         {"loaded_s", &m.loaded_s, 1.0, 36000.0},
      {"rise_s", &m.rise_s, 0.0, 100.0},          {"surge", &m.surge, 0.0, 10.0},
      {"surge_s", &m.surge_s, 1e-3, 100.0},       {"fall_s", &m.fall_s, 0.0, 100.0},
      {"belt_speed_error", &m.belt_speed_error, -0.5, 0.5},
      {"tacho_noise", &m.tacho_noise, 0.0, 1.0},  {"scale_noise", &m.scale_noise, 0.0, 1.0},
  };
  for (const auto& [k, n] : doc) {
    const long line = static_cast<long>(n.source().begin.line);
    const Key* key = nullptr;
    for (const auto& c : keys)
      if (k.str() == c.name) key = &c;
    if (!key) throw InputError(file, line, std::string(k.str()), "unknown key of the sensor model");
    const auto v = n.value<double>();
    if (!v || !std::isfinite(*v)) throw InputError(file, line, key->name, "must be a finite number");
    if (*v < key->lo || *v > key->hi)
      throw InputError(file, line, key->name, fmt::format("must be within [{:g}, {:g}]", key->lo, key->hi));
    *key->v = *v;
  }
  if (m.rate_hz * (m.tare_s * 2.0 + m.loaded_s + 5.0) > 5e6)
    throw InputError(file, 0, "rate_hz", "the log would hold more than 5 million samples");
  return m;
}

}  // namespace chutelab::logs
