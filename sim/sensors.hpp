#pragma once
#include <cstdint>

#include "hal/analog_in.hpp"
#include "hal/digital_in.hpp"
#include "hal/i2c.hpp"
#include "hal/pwm_in.hpp"
#include "sim/fault_window.hpp"
#include "sim/plant.hpp"
#include "sim/rng.hpp"

namespace rotord::sim {

/// Hardware-boundary fakes: they implement the HAL interfaces the controller
/// reads, from the plant's true output angle. Each keeps the plant time it was
/// last updated to (update(now_s)) for its own fault windows.

/// Potentiometer on an ADC: V = v0 + k theta + N(0, sigma), then
/// code = clamp(round(V / vref * 4095)).
class SimPot final : public hal::AnalogIn {
 public:
  struct Config {
    double v0_v = 0.05;  ///< wiper voltage at theta = 0
    double k_v_per_deg = 0.0;
    double sigma_v = 0.0;  ///< white noise per conversion
  };

  SimPot(const AxisPlant& plant, const Config& config, std::uint64_t seed)
      : plant_(plant), config_(config), rng_(seed) {}

  std::uint16_t read_counts() override;
  std::uint16_t full_scale_counts() const override;
  float reference_v() const override;

  void update(double now_s) { now_s_ = now_s; }
  /// Noise-free wiper voltage for an angle.
  double volts_at(double theta_deg) const { return config_.v0_v + config_.k_v_per_deg * theta_deg; }
  const Config& config() const { return config_; }

  /// Open wiper: the input is pulled to ground and reads 0 counts.
  void inject_loss(double duration_s) { loss_.start(now_s_, duration_s); }
  void inject_noise_burst(double sigma_v, double duration_s);
  /// The reading freezes at the current code (corroded wiper, dead ADC mux).
  void inject_stuck(double duration_s);
  void clear_faults();

 private:
  std::uint16_t convert(double volts) const;

  const AxisPlant& plant_;
  Config config_;
  Rng rng_;
  double now_s_ = 0.0;
  FaultWindow loss_;
  FaultWindow noise_burst_;
  double burst_sigma_v_ = 0.0;
  FaultWindow stuck_;
  std::uint16_t stuck_counts_ = 0;
};

/// US Digital MA3 12-bit PWM absolute encoder on the output shaft:
/// code = floor((mod(theta, 360) + N(0, sigma)) / 360 * 4096), refreshed every
/// 4.1 ms; the pulse is high for code + 1 us of a 4098 us frame, so
/// t_on * 4098 / (t_on + t_off) - 1 gives the code back exactly.
class SimMa3 final : public hal::PwmIn {
 public:
  static constexpr int kCounts = 4096;
  static constexpr std::uint32_t kFrame_us = kCounts + 2;
  static constexpr double kRefresh_s = 0.0041;
  static constexpr double kNominalSigma_deg = 0.03;  // transition noise, datasheet

  SimMa3(const AxisPlant& plant, double sigma_deg, std::uint64_t seed)
      : plant_(plant), sigma_deg_(sigma_deg), rng_(seed) {
    sample();
  }

  hal::PwmPeriod read() override;

  /// Latches a new code when the refresh period has passed.
  void update(double now_s);
  /// Latches a new code now (after the test moved the plant).
  void sample();
  int code() const { return code_; }
  /// The encoder reads the shaft this many degrees ahead of the antenna's
  /// bearing (a coupling not set at north): what its zero corrects.
  void set_mount_deg(double deg) { mount_deg_ = deg; }

  /// No edges (cable off): read() reports valid = false.
  void inject_loss(double duration_s) { loss_.start(now_s_, duration_s); }
  void inject_noise_burst(double sigma_deg, double duration_s);
  /// The output keeps repeating the current code.
  void inject_stuck(double duration_s) { stuck_.start(now_s_, duration_s); }
  void clear_faults();

 private:
  const AxisPlant& plant_;
  double sigma_deg_;
  Rng rng_;
  double mount_deg_ = 0.0;
  double now_s_ = 0.0;
  double next_refresh_s_ = 0.0;
  int code_ = 0;
  FaultWindow loss_;
  FaultWindow noise_burst_;
  double burst_sigma_deg_ = 0.0;
  FaultWindow stuck_;
};

/// QMC5883L magnetometer on the azimuth mast (I2C 0x0D), registers only as
/// far as the driver uses them: chip id, control writes, X/Y/Z and status.
/// The field turns with the plant's angle and is read through a hard-iron
/// offset and unequal axis gains, as near a steel mast, so the default
/// calibration (+-1000) reads a distorted heading until the web page's spin
/// calibration has recorded the real extremes:
///   x = 300 + 1200 cos(theta), y = -150 + 900 sin(theta) (+ noise).
class SimMag final : public hal::I2c {
 public:
  static constexpr std::uint8_t kAddress = 0x0D;
  static constexpr double kOffsetX = 300.0, kOffsetY = -150.0;
  static constexpr double kGainX = 1200.0, kGainY = 900.0, kZ = 400.0;

  SimMag(const AxisPlant& plant, double sigma_counts, std::uint64_t seed)
      : plant_(plant), sigma_counts_(sigma_counts), rng_(seed) {}

  bool write(std::uint8_t address, const std::uint8_t* data, std::size_t length) override;
  bool write_read(std::uint8_t address, const std::uint8_t* wdata, std::size_t wlength,
                  std::uint8_t* rdata, std::size_t rlength) override;
  /// The chip's north lies this many degrees off the boom's (declination
  /// and mounting angle together): what its heading offset corrects.
  void set_mount_deg(double deg) { mount_deg_ = deg; }

 private:
  const AxisPlant& plant_;
  double sigma_counts_;
  Rng rng_;
  double mount_deg_ = 0.0;
};

/// A switch that closes on one side of a threshold angle (limit switch, T1/T2
/// overlap sensor).
class SimSwitch final : public hal::DigitalIn {
 public:
  enum class Sense : std::uint8_t { kAtOrAbove, kAtOrBelow };

  SimSwitch(const AxisPlant& plant, Sense sense, double threshold_deg)
      : plant_(plant), sense_(sense), threshold_deg_(threshold_deg) {}

  bool active() override;

  void update(double now_s) { now_s_ = now_s; }
  /// Welded contact or broken wire: reads `state` whatever the angle.
  void inject_stuck(bool state, double duration_s) {
    stuck_state_ = state;
    stuck_.start(now_s_, duration_s);
  }
  void clear_faults() { stuck_.clear(); }
  double threshold_deg() const { return threshold_deg_; }

 private:
  const AxisPlant& plant_;
  Sense sense_;
  double threshold_deg_;
  double now_s_ = 0.0;
  FaultWindow stuck_;
  bool stuck_state_ = false;
};

}  // namespace rotord::sim
