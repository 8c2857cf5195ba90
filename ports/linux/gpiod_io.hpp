#pragma once
// `rotord --hw gpiod`: the rotator's relays and switches on a Linux GPIO chip
// (a Raspberry Pi's header), MA3 encoders timed from edge events, pots on IIO
// ADCs. Built from the gpiod.* and iio.* settings the way SimRotator is built
// from a profile, and handed to the Controller as one AxisIo per axis.
#include <array>
#include <asio.hpp>
#include <memory>
#include <string>

#include "axis/axis_io.hpp"
#include "gpio_line.hpp"
#include "gpiod_pulse_counter.hpp"
#include "hal/pwm_out.hpp"
#include "i2c_dev.hpp"
#include "iio_adc.hpp"
#include "ma3_edge_timer.hpp"
#include "settings/settings.hpp"
#include "util/axis_id.hpp"

namespace rotord::linux_port {

/// One axis's outputs: relays on GPIO lines, H-bridge halves on kernel PWM
/// channels. A line or duty is written only when it changes (one ioctl per
/// relay change, not per tick).
class GpiodDriveSink final : public DriveSink {
 public:
  void map(OutputChannel channel, std::unique_ptr<GpioLine> line);
  void map(OutputChannel channel, std::unique_ptr<hal::PwmOut> pwm);
  void apply(const DriveOutputs& outputs) override;
  /// Every mapped line inactive, written whatever the last value was.
  void all_off();
  /// What was last written successfully (relays 0/1, PWM duty): what the
  /// hardware holds as far as the driver knows, for the exit report.
  DriveOutputs written() const {
    DriveOutputs o;
    o.value = written_;
    return o;
  }

 private:
  void write(std::size_t channel, float value);

  std::array<std::unique_ptr<GpioLine>, kOutputChannelCount> lines_{};
  std::array<std::unique_ptr<hal::PwmOut>, kOutputChannelCount> pwms_{};
  std::array<float, kOutputChannelCount> written_{};  ///< relays 0/1, PWM duty
  bool error_reported_ = false;
};

/// A switch or button input. An I/O error reads "not active" (the core's
/// safety rules do not rely on a switch alone) and is reported once.
class GpiodSwitch final : public hal::DigitalIn {
 public:
  GpiodSwitch(std::unique_ptr<GpioLine> line, const char* key)
      : line_(std::move(line)), key_(key) {}
  bool active() override;

 private:
  std::unique_ptr<GpioLine> line_;
  const char* key_;
  bool error_reported_ = false;
};

/// Where the host's hardware interfaces are: the real ones in the daemon, a
/// temporary tree and a chip model in tests.
struct GpiodHost {
  std::string iio_root;      ///< /sys/bus/iio/devices
  std::string pwm_root;      ///< /sys/class/pwm
  std::string i2c_dev_root;  ///< /dev (i2c-N)
  I2cKernel* i2c_kernel = nullptr;
  GpiodMa3Input::Clock clock;
};

class GpiodRotator {
 public:
  /// Requests every line the settings call for (outputs inactive), opens
  /// every ADC channel and the magnetometer's I2C adapter (and checks that
  /// the chip answers), or returns nullptr with `error` naming the setting,
  /// the line or file and what is wrong. H-bridge drives need kernel PWM
  /// channels (pwm.*; never software PWM for a motor).
  static std::unique_ptr<GpiodRotator> open(const settings::Settings& s,
                                            std::unique_ptr<GpioChip> chip, const GpiodHost& host,
                                            std::string& error);
  /// Outputs off, then the lines are released.
  ~GpiodRotator();
  GpiodRotator(const GpiodRotator&) = delete;
  GpiodRotator& operator=(const GpiodRotator&) = delete;

  /// Wiring for the controller; all null for an axis that is not enabled.
  AxisIo io(AxisId axis);
  /// The emergency-stop switch (gpiod.estop), or nullptr when not wired.
  hal::DigitalIn* estop() { return estop_.get(); }
  /// The anemometer's pulses (gpiod.wind, with wind.source = pulses), or
  /// nullptr when not wired.
  hal::PulseCounter* wind_pulses() { return wind_.get(); }
  /// Drains MA3 edges as they arrive, on the daemon's loop.
  void watch(asio::io_context& io);
  /// Once per control tick, before it: one conversion per pot.
  void sample();
  void all_off();
  /// The outputs of `axis` as last written to the lines and PWM channels.
  DriveOutputs written(AxisId id) const {
    return id == AxisId::kEl ? el_.drive.written() : az_.drive.written();
  }
  /// What was opened, one line per axis, for the start-up log.
  const std::string& summary() const { return summary_; }

 private:
  struct AxisHw {
    bool fitted = false;
    GpiodDriveSink drive;
    std::unique_ptr<GpiodSwitch> limit_cw, limit_ccw, t1, t2, button_fwd, button_rev;
    std::unique_ptr<GpiodMa3Input> ma3;
    std::unique_ptr<IioAdc> pot;
    bool pot_error_reported = false;
  };
  /// The azimuth magnetometer's adapter (az.sensor = mag).
  bool open_magnetometer(const settings::Settings& s, const GpiodHost& host, std::string& where,
                         std::string& error);
  explicit GpiodRotator(std::unique_ptr<GpioChip> chip) : chip_(std::move(chip)) {}
  AxisHw& axis(AxisId id) { return id == AxisId::kEl ? el_ : az_; }

  std::unique_ptr<GpioChip> chip_;  // first: released after every line
  AxisHw az_;
  AxisHw el_;
  std::unique_ptr<GpiodSwitch> estop_;
  std::unique_ptr<GpiodPulseCounter> wind_;
  std::unique_ptr<I2cDev> i2c_;
  std::string summary_;
};

}  // namespace rotord::linux_port
