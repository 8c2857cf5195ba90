#pragma once
// The core's HAL interfaces over the pico-sdk: ADC pots, switch inputs, relay
// and H-bridge PWM outputs, and the MA3 encoder's PWM input. Constructors
// touch no hardware (these objects are statics); begin() does.
#include <array>
#include <cstdint>

#include "axis/drive_outputs.hpp"
#include "hal/analog_in.hpp"
#include "hal/digital_in.hpp"
#include "hal/i2c.hpp"
#include "hal/pulse_counter.hpp"
#include "hal/pwm_in.hpp"

namespace rotord::pico_w {

/// No pin wired to this function.
inline constexpr int kNoPin = -1;

/// A potentiometer wiper on one of the RP2040's ADC inputs (GPIO 26..28).
class PicoAdc final : public hal::AnalogIn {
 public:
  explicit PicoAdc(int gpio) : gpio_(gpio) {}
  void begin();
  std::uint16_t read_counts() override;
  std::uint16_t full_scale_counts() const override { return 4095; }
  float reference_v() const override { return 3.3f; }

 private:
  int gpio_;
};

/// A switch to ground with the internal pull-up: closed = active. Limit and
/// threshold switches are wired this way so a broken wire reads "not
/// active"; the core's safety rules do not rely on the switch alone.
class PicoSwitch final : public hal::DigitalIn {
 public:
  explicit PicoSwitch(int gpio) : gpio_(gpio) {}
  void begin();
  bool active() override;

 private:
  int gpio_;
};

/// An anemometer's reed contact (or open collector) to ground on pins.wind
/// (docs/care.md, "Wind stow"): falling edges counted in a GPIO interrupt,
/// the pull-up on. An edge within kDebounceUs of the last one counted is the
/// contact bouncing (a cup anemometer at 75 m/s closes it 110 times a
/// second: 9 ms apart). One input at most.
class PicoPulseCounter final : public hal::PulseCounter {
 public:
  static constexpr std::uint32_t kDebounceUs = 2000;

  explicit PicoPulseCounter(int gpio) : gpio_(gpio) {}
  void begin();
  std::uint32_t count() override { return count_; }

 private:
  static void on_irq();
  int gpio_;
  volatile std::uint32_t count_ = 0;
  std::uint32_t last_us_ = 0;
};

/// The MA3's PWM output timed from GPIO edge interrupts: each rising edge
/// closes a period (high time = fall - previous rise, low time = rise - fall).
/// The core decodes the duty ratio, so the encoder's +-10 % clock drift does
/// not matter. The fallback when no PIO state machine is free (ma3_pio.hpp).
class Ma3EdgeInput final : public hal::PwmIn {
 public:
  /// No edge for this long means the encoder is unplugged (a 10-bit MA3's
  /// period is ~1 ms, a 12-bit one's ~4 ms).
  static constexpr std::uint32_t kTimeoutUs = 100'000;

  explicit Ma3EdgeInput(int gpio) : gpio_(gpio) {}
  /// Enables the edge interrupt; at most two inputs (az and el).
  void begin();
  hal::PwmPeriod read() override;

 private:
  static void on_irq();
  void on_edge(std::uint32_t events, std::uint32_t now_us);

  int gpio_;
  // Written by the interrupt, read with interrupts off.
  volatile std::uint32_t rise_us_ = 0;
  volatile std::uint32_t fall_us_ = 0;
  volatile std::uint32_t high_us_ = 0;
  volatile std::uint32_t low_us_ = 0;
  volatile std::uint32_t last_edge_us_ = 0;
  volatile bool have_period_ = false;
  volatile bool seen_rise_ = false;
  volatile bool seen_fall_ = false;
};

/// An I2C bus on an SDA/SCL pin pair (the settings check that they belong to
/// one RP2040 I2C block). 100 kHz, internal pull-ups as a fallback for
/// breakout boards without their own; every transfer has a timeout, so a
/// stuck bus costs one tick, never a hang.
class PicoI2c final : public hal::I2c {
 public:
  static constexpr unsigned kBaudHz = 100'000;
  static constexpr unsigned kTimeoutUs = 2'000;

  PicoI2c(int sda, int scl) : sda_(sda), scl_(scl) {}
  void begin();
  bool write(std::uint8_t address, const std::uint8_t* data, std::size_t length) override;
  bool write_read(std::uint8_t address, const std::uint8_t* wdata, std::size_t wlength,
                  std::uint8_t* rdata, std::size_t rlength) override;

 private:
  int sda_, scl_;
};

/// Which pin each logical output of one axis drives; kNoPin = not wired.
struct DrivePins {
  std::array<int, kOutputChannelCount> pin;
  DrivePins() { pin.fill(kNoPin); }
  DrivePins& set(OutputChannel ch, int gpio) {
    pin[static_cast<std::size_t>(ch)] = gpio;
    return *this;
  }
};

/// Writes one axis's outputs: relays as push-pull GPIO (high = energised),
/// H-bridge channels as 20 kHz PWM (above hearing, within the range of
/// common H-bridge drivers).
class PicoDriveSink final : public DriveSink {
 public:
  static constexpr std::uint32_t kPwmHz = 20'000;
  static constexpr std::uint16_t kPwmWrap = 999;  // 1000 duty steps

  explicit PicoDriveSink(const DrivePins& pins) : pins_(pins) {}
  /// Drives every wired pin low: the first thing the firmware does, before
  /// the network or anything that can fail.
  void begin();
  /// Re-maps the pins once the settings are known (drive type) and applies
  /// the new map, outputs off.
  void configure(const DrivePins& pins) {
    pins_ = pins;
    begin();
  }
  void apply(const DriveOutputs& outputs) override;
  /// All outputs off without going through the axis (watchdog path, faults).
  void all_off();

 private:
  static bool is_pwm(OutputChannel ch) {
    return ch == OutputChannel::kPwmCw || ch == OutputChannel::kPwmCcw;
  }
  DrivePins pins_;
};

}  // namespace rotord::pico_w
