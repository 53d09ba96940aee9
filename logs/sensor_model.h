#pragma once
// What stands between a plate's true load and the numbers in a rig's log: the virtual rig's sensor
// model (virtual_rig.h). Every default is a plausible strain-gauge rig of the reference study's
// size; the bench and the tests set what they study.
//
// A channel reads  gain_true * (raw - zero_true) = low-pass(load(t) (1 + creep (t - t_on)) + noise)
// + drift t, sampled at rate_hz and rounded to the logger's step, where
//  - load(t) rises from zero after the start (first order, rise_s, with an overshoot decaying over
//    surge_s) and falls back after the stop (fall_s);
//  - noise = white (white_N, always: the amplifier) + an Ornstein-Uhlenbeck process of correlation
//    time corr_s and standard deviation corr_fraction of the cell's load (the stream and the plate's
//    vibration, loaded only), or the DEM's own fluctuation when a series is given;
//  - gain_true differs from the layout's gain by a normal deviate of gain_u (the calibration's
//    error), zero_true from the layout's zero by zero_offset_N;
//  - drift_N is the zero's change over the whole log, creep the relative change of the reading per
//    second under load.
#include <filesystem>
#include <string>

namespace chutelab::logs {

struct SensorModel {
  double rate_hz = 50.0;
  double lowpass_hz = 10.0;       // first-order anti-alias filter (0: none)
  double white_N = 0.05;
  double corr_fraction = 0.02;
  double corr_s = 0.5;
  double resolution_N = 0.01;     // the logger's step, in N at the cell's gain
  double gain_u = 0.003;          // relative, one standard deviation (stated in the layout)
  double zero_offset_N = 0.5;     // sd of the true zero about the layout's
  double drift_N = 0.0;           // per channel, over the whole log
  double creep_per_s = 0.0;       // relative
  double tare_s = 5.0;            // unloaded before and after
  double loaded_s = 30.0;         // from the start to the stop
  double rise_s = 0.6, surge = 0.15, surge_s = 1.5, fall_s = 0.4;
  double belt_speed_error = 0.0;  // the real belt's speed relative to the record (tachometer reads it)
  double tacho_noise = 0.003;     // relative, white
  double scale_noise = 0.02;      // relative, correlated over 2 s (the belt scale's)
};

// The model as TOML keys (the same names); unknown keys and bad values are InputErrors.
SensorModel read_sensor_model(const std::filesystem::path& file);

}  // namespace chutelab::logs
