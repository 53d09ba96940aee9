#pragma once
// SI inside, suffixed units at the boundary (files, CLI). These factors convert boundary units to SI.
#include <numbers>

namespace chutelab::units {
inline constexpr double mm = 1e-3;                  // m per mm
inline constexpr double deg = std::numbers::pi / 180.0;  // rad per degree
// The way out, SI to degrees, as a factor of its own: x * (180/pi) and x / (pi/180) can differ in the
// last bit, and the outputs are written with the former.
inline constexpr double deg_per_rad = 180.0 / std::numbers::pi;  // degrees per rad
inline constexpr double tph = 1000.0 / 3600.0;      // kg/s per t/h
inline constexpr double standard_gravity = 9.80665; // m/s^2 (CGPM 1901)
inline constexpr double air_density = 1.204;        // kg/m^3, dry air at 20 degC, 101.325 kPa
}  // namespace chutelab::units
