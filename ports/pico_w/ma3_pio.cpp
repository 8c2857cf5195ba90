#include "ma3_pio.hpp"

#include "hardware/clocks.h"
#include "hardware/gpio.h"
#include "hardware/pio.h"
#include "ma3_pwm.pio.h"
#include "pico/time.h"

namespace rotord::pico_w {

hal::PwmPeriod ma3_pio_word_to_period(std::uint32_t word, std::uint32_t cycles_per_us) {
  const std::uint32_t high_loops = 0xFFFFu - (word >> 16);
  const std::uint32_t low_loops = 0xFFFFu - (word & 0xFFFFu);
  // Cycles spent outside the counting loops (see ma3_pwm.pio).
  const std::uint32_t high_cycles = 2 * high_loops + 4;
  const std::uint32_t low_cycles = 2 * low_loops + 2;
  return {(high_cycles + cycles_per_us / 2) / cycles_per_us,
          (low_cycles + cycles_per_us / 2) / cycles_per_us, true};
}

bool Ma3PioInput::begin() {
  PIO pio = nullptr;
  uint sm = 0;
  uint offset = 0;
  const uint pin = static_cast<uint>(gpio_);
  if (!pio_claim_free_sm_and_add_program_for_gpio_range(&ma3_pwm_program, &pio, &sm, &offset, pin,
                                                        1, true))
    return false;
  // Pull down: an unplugged encoder reads a steady low (no periods, so the
  // input times out) rather than a floating pin that toggles on noise.
  gpio_init(pin);
  gpio_set_dir(pin, GPIO_IN);
  gpio_pull_down(pin);
  pio_sm_config c = ma3_pwm_program_get_default_config(offset);
  sm_config_set_in_pins(&c, pin);
  sm_config_set_jmp_pin(&c, pin);
  sm_config_set_in_shift(&c, false /* shift left */, false /* no autopush */, 32);
  sm_config_set_fifo_join(&c, PIO_FIFO_JOIN_RX);
  const float divider =
      static_cast<float>(clock_get_hz(clk_sys)) / (static_cast<float>(kCyclesPerUs) * 1'000'000.0f);
  sm_config_set_clkdiv(&c, divider < 1.0f ? 1.0f : divider);
  pio_sm_init(pio, sm, offset, &c);
  pio_sm_set_enabled(pio, sm, true);
  pio_ = pio;
  sm_ = sm;
  last_period_us_ = time_us_32();
  return true;
}

hal::PwmPeriod Ma3PioInput::read() {
  PIO pio = static_cast<PIO>(pio_);
  if (pio == nullptr) return {};
  // Drain the FIFO; the newest whole period wins.
  bool fresh = false;
  std::uint32_t word = 0;
  while (!pio_sm_is_rx_fifo_empty(pio, sm_)) {
    word = pio_sm_get(pio, sm_);
    fresh = true;
  }
  const std::uint32_t now = time_us_32();
  if (fresh) {
    last_ = ma3_pio_word_to_period(word, kCyclesPerUs);
    last_period_us_ = now;
    have_period_ = true;
  }
  hal::PwmPeriod period = last_;
  period.valid = have_period_ && now - last_period_us_ <= kTimeoutUs;
  return period;
}

}  // namespace rotord::pico_w
