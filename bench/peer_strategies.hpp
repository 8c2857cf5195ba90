#pragma once
#include "axis/drive_outputs.hpp"
#include "sim/plant_params.hpp"

namespace rotord::bench {

/// Stop/approach logic of a controller other than rotord, re-implemented from
/// its published description so it
/// can drive the same simulated plant. Each one reads the true output angle
/// (no sensor noise, no quantisation: an advantage over rotord, which reads
/// the simulated pot or encoder) and writes the plant's output channels.
class PeerStrategy {
 public:
  virtual ~PeerStrategy() = default;
  virtual const char* name() const = 0;
  /// How often the firmware's loop runs.
  virtual int loop_ms() const = 0;
  /// Outputs for the next loop period, from the error target - theta.
  virtual DriveOutputs step(double error_deg) = 0;
};

/// WRC firmware: two speeds by distance, fast beyond 30 deg, slow within
/// 10 deg (linear in between), stop when within 0.3 deg. Once stopped it
/// starts again only when the error exceeds `restart_deg` (else a relay plant,
/// which coasts ~0.9 deg, would hunt forever around a 0.3 deg window).
class WrcTwoSpeed final : public PeerStrategy {
 public:
  WrcTwoSpeed(sim::DriveKind drive, bool has_brake, double restart_deg)
      : drive_(drive), has_brake_(has_brake), restart_deg_(restart_deg) {}
  const char* name() const override { return "wrc"; }
  int loop_ms() const override { return 10; }
  DriveOutputs step(double error_deg) override;

  static constexpr double kFastBeyondDeg = 30.0;
  static constexpr double kSlowWithinDeg = 10.0;
  static constexpr double kStopWithinDeg = 0.3;
  static constexpr double kSlowDuty = 0.5;  // PWM plants; relay plants have one speed

 private:
  sim::DriveKind drive_;
  bool has_brake_;
  double restart_deg_;
  bool driving_ = false;
  int dir_ = 0;
};

/// Pico Rotor (MicroPython) firmware: 50 ms loop; stop when within 1.0 deg;
/// inside 5 deg duty = 30 % + 20 % * err / 5; else 100 %; no ramp, no coast
/// model. On a relay plant the duty is just on/off.
class PicoRotorSlowZone final : public PeerStrategy {
 public:
  PicoRotorSlowZone(sim::DriveKind drive, bool has_brake) : drive_(drive), has_brake_(has_brake) {}
  const char* name() const override { return "picorotor"; }
  int loop_ms() const override { return 50; }
  DriveOutputs step(double error_deg) override;

 private:
  sim::DriveKind drive_;
  bool has_brake_;
};

/// Outputs that drive `dir` (+1 CW, -1 CCW, 0 stop) at `duty` on this drive
/// kind (relay plants ignore the duty; a brake is released while driving).
DriveOutputs drive_outputs(sim::DriveKind drive, bool has_brake, int dir, double duty);

}  // namespace rotord::bench
