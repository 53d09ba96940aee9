#pragma once
// What an added physical effect may change, stage by stage, in the analytical chain
// (discharge -> flight -> plate -> measurement). Each effect overrides only the stages it touches;
// the chain calls every stage of every enabled effect in the order the effects were given.
// The effects themselves live in effects/, one file each.
#include <Eigen/Core>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/quantity.h"
#include "core/rig.h"

namespace chutelab::analytical {

// Operating inputs of the condition as the physics sees them (before the load shape is derived).
struct OperatingPoint {
  double belt_speed = 0.0;  // m/s
  double mass_flow = 0.0;   // kg/s actually delivered
};

// How one streamline leaves the pulley (Booth).
struct DischargeInput {
  double radius = 0.0;          // m, R_b + e
  double speed = 0.0;           // m/s, speed of the material on the belt (V_b without slip)
  double incline = 0.0;         // rad
  double gravity = 0.0;         // m/s^2
  double holding_accel = 0.0;   // m/s^2 pulling the material towards the pulley axis (adhesion)
  double layer_mass_per_area = 0.0;  // kg/m^2 of belt: rho_bl * load area / contact width
};

// The stream striking the plate: everything Korzen's control volume needs, adjustable by effects.
struct PlateInteraction {
  double friction = 0.0;         // mu_pw
  double rebound = 0.0;          // fraction of the normal momentum returned by rebounding particles
};

struct FlightContext {
  double particle_diameter = 0.0;
  double solid_density = 0.0;
};

class Effect;
using EffectList = std::vector<std::shared_ptr<const Effect>>;

class Effect {
 public:
  virtual ~Effect() = default;
  virtual std::string name() const = 0;
  // Whether it acts at this station at all: an error in one condition's record acts there alone.
  // Whoever applies a list of effects to a condition applies those that act there (acting_at).
  virtual bool acts_at(const Station&) const { return true; }

  // The rig as it really was, from the rig as recorded (a plate further than the drawing says, a
  // belt faster than its nameplate): a wrong number in the record, not physics. Called first, by
  // every model that reads the station.
  virtual void adjust_station(Station&) const {}
  virtual void adjust_operating_point(OperatingPoint&) const {}
  virtual void adjust_discharge(DischargeInput&, const Station&) const {}
  // Extra acceleration in flight (beyond gravity); has_flight_force() lets the chain keep the
  // closed-form trajectory when no effect adds a force. The DEM calls it from several threads at
  // once (a body force per range of particles), so it must be a pure function of its arguments.
  virtual bool has_flight_force() const { return false; }
  virtual Eigen::Vector2d flight_acceleration(const Eigen::Vector2d& velocity,
                                              const FlightContext&) const {
    (void)velocity;
    return Eigen::Vector2d::Zero();
  }
  // Turn the release velocity of an outer streamline (spread of the stream); centre untouched.
  virtual void adjust_release(Boundary, Eigen::Vector2d& velocity) const { (void)velocity; }
  virtual void adjust_plate(PlateInteraction&) const {}
  // The measurement itself (instrument bias): applied to any model's predictions, DEM included.
  virtual void adjust_measurement(QuantityValues&) const {}
  // ... and to the stream heights read off the trajectory (m), where the rig measured them.
  virtual void adjust_trajectory(std::vector<std::optional<double>>& y) const { (void)y; }
};

// Whether every effect of a list acts at this station, so that the list applies there as it is.
inline bool all_act_at(const EffectList& effects, const Station& s) {
  for (const auto& e : effects)
    if (!e->acts_at(s)) return false;
  return true;
}

// The effects of a list that act at this station.
inline EffectList acting_at(const EffectList& effects, const Station& s) {
  EffectList here;
  for (const auto& e : effects)
    if (e->acts_at(s)) here.push_back(e);
  return here;
}

// The station as every effect's adjust_station leaves it, in the order the effects were given.
inline Station as_really_was(const Station& recorded, const EffectList& effects) {
  Station s = recorded;
  for (const auto& e : effects) e->adjust_station(s);
  return s;
}

}  // namespace chutelab::analytical
