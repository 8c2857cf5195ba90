#pragma once
// The MA3 encoder's PWM timed by a PIO state machine (ma3_pwm.pio): no
// interrupts, 0.05 us timing, one FIFO word per period. Falls back to the
// GPIO edge interrupt input (Ma3EdgeInput) when no state machine is free.
#include <cstdint>

#include "hal/pwm_in.hpp"

namespace rotord::pico_w {

/// Decodes one FIFO word of ma3_pwm.pio into a period in whole microseconds
/// (the MA3's own resolution: one count per us), given the state machine's
/// cycles per microsecond. Pure: unit-testable without the SDK.
hal::PwmPeriod ma3_pio_word_to_period(std::uint32_t word, std::uint32_t cycles_per_us);

class Ma3PioInput final : public hal::PwmIn {
 public:
  /// No period for this long means the encoder is unplugged.
  static constexpr std::uint32_t kTimeoutUs = 100'000;
  /// State machine clock: 20 cycles per microsecond.
  static constexpr std::uint32_t kCyclesPerUs = 20;

  explicit Ma3PioInput(int gpio) : gpio_(gpio) {}
  /// Claims a free state machine and starts it; false when none is free.
  bool begin();
  hal::PwmPeriod read() override;

 private:
  int gpio_;
  void* pio_ = nullptr;  // PIO (pio_hw_t*), kept opaque so the header needs no SDK
  unsigned sm_ = 0;
  hal::PwmPeriod last_{};
  std::uint32_t last_period_us_ = 0;  // time_us_32() of the last period
  bool have_period_ = false;
};

}  // namespace rotord::pico_w
