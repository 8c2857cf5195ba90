#pragma once
#include <cstdint>

#include "axis/axis_io.hpp"
#include "sim/plant.hpp"
#include "sim/profiles.hpp"
#include "sim/recording_sink.hpp"
#include "sim/sensors.hpp"
#include "util/axis_id.hpp"
#include "util/time.hpp"

namespace rotord::sim {

enum class SensorNoise : bool { kOff = false, kOn = true };

/// A whole simulated rotator built from a profile: one or two axis plants,
/// their sensors and switches, and the drive sinks the controller writes to.
/// Runs in virtual time: advance_to() integrates the plants in 1 ms steps on
/// the outputs the controller applied last.
class SimRotator {
 public:
  /// Starts with az at rest mid-range and el parked at its minimum, all
  /// outputs off. `profile` must outlive the rotator (the built-in ones do).
  SimRotator(const Profile& profile, std::uint64_t seed, SensorNoise noise = SensorNoise::kOn,
             Millis start_ms = 0);
  // Sensors point into the plants: not copyable or movable.
  SimRotator(const SimRotator&) = delete;
  SimRotator& operator=(const SimRotator&) = delete;

  /// Integrates from the last time to now_ms (no-op if now_ms is not later).
  void advance_to(Millis now_ms);
  Millis now_ms() const { return now_ms_; }

  /// Wiring for the controller; null where the profile has no such part, and
  /// all null for a missing elevation axis. Every azimuth also has a
  /// magnetometer on its I2C bus, so az.sensor = mag works on any profile.
  AxisIo io(AxisId axis);

  bool has_el() const { return profile_.has_el; }
  const Profile& profile() const { return profile_; }
  const AxisProfile& axis_profile(AxisId axis) const;
  AxisPlant& plant(AxisId axis) { return sim(axis).plant; }
  const AxisPlant& plant(AxisId axis) const { return sim(axis).plant; }
  /// Outputs the controller applied last on this axis.
  const DriveOutputs& outputs(AxisId axis) const { return sim(axis).sink.last(); }

  /// Test set-up: axis at rest at this angle (sensors resample at once).
  void set_theta_deg(AxisId axis, double theta_deg);
  /// The absolute sensors (MA3, magnetometer) read the antenna's bearing
  /// plus this angle: mounted off north, as self-commissioning's known
  /// bearing finds them (docs/commissioning.md).
  void set_sensor_mount_deg(AxisId axis, double deg);

  // Fault injection, from now for a duration (kForever_s for permanent).
  void jam(AxisId axis, double duration_s) { plant(axis).jam(duration_s); }
  void slip(AxisId axis, double load_factor, double duration_s) {
    plant(axis).slip(load_factor, duration_s);
  }
  /// Wind turning the unpowered antenna against its brake (AxisPlant::wind_slip).
  void wind_slip(AxisId axis, double speed_deg_s, double duration_s) {
    plant(axis).wind_slip(speed_deg_s, duration_s);
  }
  /// Position sensor lost: pot reads 0 counts, MA3 stops pulsing.
  void sensor_loss(AxisId axis, double duration_s);
  /// Position sensor noise raised to sigma_deg (converted to volts for a pot).
  void sensor_noise_burst(AxisId axis, double sigma_deg, double duration_s);
  /// Position sensor reading frozen.
  void sensor_stuck(AxisId axis, double duration_s);
  /// Limit switch welded / open regardless of the angle.
  void limit_switch_stuck(AxisId axis, bool cw, bool state, double duration_s);
  void clear_faults(AxisId axis);

 private:
  struct AxisSim {
    AxisSim(const AxisProfile& profile, std::uint64_t seed, SensorNoise noise);
    void step_1ms();

    const AxisProfile& profile;
    AxisPlant plant;
    SimPot pot;
    SimMa3 ma3;
    SimMag mag;  // read only when az.sensor = mag
    SimSwitch limit_cw;
    SimSwitch limit_ccw;
    SimSwitch t1;
    SimSwitch t2;
    RecordingSink sink;
  };

  AxisSim& sim(AxisId axis) { return axis == AxisId::kEl ? el_ : az_; }
  const AxisSim& sim(AxisId axis) const { return axis == AxisId::kEl ? el_ : az_; }
  bool fitted(AxisId axis) const { return axis == AxisId::kAz || profile_.has_el; }

  const Profile& profile_;
  AxisSim az_;
  AxisSim el_;
  Millis now_ms_;
};

}  // namespace rotord::sim
