#include "pico_hal.hpp"

#include <algorithm>

#include "hardware/adc.h"
#include "hardware/clocks.h"
#include "hardware/gpio.h"
#include "hardware/i2c.h"
#include "hardware/pwm.h"
#include "hardware/sync.h"
#include "pico/time.h"

namespace rotord::pico_w {

namespace {

uint pin(int gpio) {
  return static_cast<uint>(gpio);
}

}  // namespace

// --- ADC ---------------------------------------------------------------------

void PicoAdc::begin() {
  adc_init();  // idempotent: resets the ADC block, which holds no state we keep
  adc_gpio_init(pin(gpio_));
}

std::uint16_t PicoAdc::read_counts() {
  adc_select_input(pin(gpio_ - 26));  // GPIO 26..29 are ADC inputs 0..3
  return adc_read();
}

// --- Switches ------------------------------------------------------------------

void PicoSwitch::begin() {
  gpio_init(pin(gpio_));
  gpio_set_dir(pin(gpio_), GPIO_IN);
  gpio_pull_up(pin(gpio_));
}

bool PicoSwitch::active() {
  return !gpio_get(pin(gpio_));
}

// --- MA3 PWM input ---------------------------------------------------------------

namespace {
// The GPIO bank has one interrupt; the raw handler finds its inputs here.
std::array<Ma3EdgeInput*, 2> g_ma3_inputs{};
}  // namespace

namespace {
PicoPulseCounter* g_pulse_counter = nullptr;
}  // namespace

void PicoPulseCounter::begin() {
  if (g_pulse_counter != nullptr) return;  // one anemometer
  g_pulse_counter = this;
  gpio_init(pin(gpio_));
  gpio_set_dir(pin(gpio_), GPIO_IN);
  gpio_pull_up(pin(gpio_));
  // A raw handler, as the MA3's: the cyw43 driver's GPIO interrupt is left alone.
  gpio_add_raw_irq_handler(pin(gpio_), &PicoPulseCounter::on_irq);
  gpio_set_irq_enabled(pin(gpio_), GPIO_IRQ_EDGE_FALL, true);
  irq_set_enabled(IO_IRQ_BANK0, true);
}

void PicoPulseCounter::on_irq() {
  PicoPulseCounter* c = g_pulse_counter;
  if (c == nullptr) return;
  const std::uint32_t events = gpio_get_irq_event_mask(pin(c->gpio_));
  if (events == 0) return;
  gpio_acknowledge_irq(pin(c->gpio_), events);
  const std::uint32_t now = time_us_32();
  if (now - c->last_us_ < kDebounceUs) return;
  c->last_us_ = now;
  // A 32-bit store is atomic on the M0+: the loop reads it without a lock.
  c->count_ = c->count_ + 1;
}

void Ma3EdgeInput::begin() {
  const auto free = std::find(g_ma3_inputs.begin(), g_ma3_inputs.end(), nullptr);
  if (free == g_ma3_inputs.end()) return;  // more than two encoders: not wired
  *free = this;
  gpio_init(pin(gpio_));
  gpio_set_dir(pin(gpio_), GPIO_IN);
  // Pull down: an unplugged encoder reads a steady low, i.e. "no signal",
  // rather than a floating pin that toggles on noise.
  gpio_pull_down(pin(gpio_));
  // A raw handler (not gpio_set_irq_callback) so the cyw43 driver's own GPIO
  // interrupt handling is left alone.
  gpio_add_raw_irq_handler(pin(gpio_), &Ma3EdgeInput::on_irq);
  gpio_set_irq_enabled(pin(gpio_), GPIO_IRQ_EDGE_RISE | GPIO_IRQ_EDGE_FALL, true);
  irq_set_enabled(IO_IRQ_BANK0, true);
}

void Ma3EdgeInput::on_irq() {
  const std::uint32_t now = time_us_32();
  for (Ma3EdgeInput* input : g_ma3_inputs) {
    if (input == nullptr) continue;
    const std::uint32_t events = gpio_get_irq_event_mask(pin(input->gpio_));
    if (events == 0) continue;
    gpio_acknowledge_irq(pin(input->gpio_), events);
    input->on_edge(events, now);
  }
}

void Ma3EdgeInput::on_edge(std::uint32_t events, std::uint32_t now_us) {
  // Both edges in one interrupt means we were late: the timing is unknown,
  // so start a fresh period rather than report a wrong duty.
  if ((events & GPIO_IRQ_EDGE_RISE) != 0 && (events & GPIO_IRQ_EDGE_FALL) != 0) {
    seen_rise_ = false;
    seen_fall_ = false;
    last_edge_us_ = now_us;
    return;
  }
  if ((events & GPIO_IRQ_EDGE_FALL) != 0) {
    fall_us_ = now_us;
    seen_fall_ = seen_rise_;
  } else {
    if (seen_rise_ && seen_fall_) {
      high_us_ = fall_us_ - rise_us_;
      low_us_ = now_us - fall_us_;
      have_period_ = true;
    }
    rise_us_ = now_us;
    seen_rise_ = true;
    seen_fall_ = false;
  }
  last_edge_us_ = now_us;
}

hal::PwmPeriod Ma3EdgeInput::read() {
  const std::uint32_t saved = save_and_disable_interrupts();
  hal::PwmPeriod period{high_us_, low_us_, have_period_};
  const std::uint32_t last_edge = last_edge_us_;
  restore_interrupts(saved);
  if (time_us_32() - last_edge > kTimeoutUs) period.valid = false;
  return period;
}

// --- I2C -----------------------------------------------------------------------------

namespace {
i2c_inst_t* i2c_block(int sda) {
  return (sda / 2) % 2 == 0 ? i2c0 : i2c1;  // RP2040 pin mux
}
}  // namespace

void PicoI2c::begin() {
  i2c_init(i2c_block(sda_), kBaudHz);
  for (const int gpio : {sda_, scl_}) {
    gpio_set_function(pin(gpio), GPIO_FUNC_I2C);
    gpio_pull_up(pin(gpio));
  }
}

bool PicoI2c::write(std::uint8_t address, const std::uint8_t* data, std::size_t length) {
  return i2c_write_timeout_us(i2c_block(sda_), address, data, length, false, kTimeoutUs) ==
         static_cast<int>(length);
}

bool PicoI2c::write_read(std::uint8_t address, const std::uint8_t* wdata, std::size_t wlength,
                         std::uint8_t* rdata, std::size_t rlength) {
  i2c_inst_t* bus = i2c_block(sda_);
  if (i2c_write_timeout_us(bus, address, wdata, wlength, true /* repeated start */, kTimeoutUs) !=
      static_cast<int>(wlength))
    return false;
  return i2c_read_timeout_us(bus, address, rdata, rlength, false, kTimeoutUs) ==
         static_cast<int>(rlength);
}

// --- Outputs -------------------------------------------------------------------------

void PicoDriveSink::begin() {
  for (std::size_t i = 0; i < kOutputChannelCount; ++i) {
    const int gpio = pins_.pin[i];
    if (gpio == kNoPin) continue;
    // Low before it becomes an output, so the pin never glitches high.
    gpio_init(pin(gpio));
    gpio_put(pin(gpio), false);
    gpio_set_dir(pin(gpio), GPIO_OUT);
    if (!is_pwm(static_cast<OutputChannel>(i))) continue;
    const uint slice = pwm_gpio_to_slice_num(pin(gpio));
    pwm_config config = pwm_get_default_config();
    const float divider =
        static_cast<float>(clock_get_hz(clk_sys)) / static_cast<float>(kPwmHz * (kPwmWrap + 1u));
    pwm_config_set_clkdiv(&config, std::max(divider, 1.0f));
    pwm_config_set_wrap(&config, kPwmWrap);
    pwm_set_gpio_level(pin(gpio), 0);
    pwm_init(slice, &config, true);
    gpio_set_function(pin(gpio), GPIO_FUNC_PWM);
  }
}

void PicoDriveSink::apply(const DriveOutputs& outputs) {
  for (std::size_t i = 0; i < kOutputChannelCount; ++i) {
    const int gpio = pins_.pin[i];
    if (gpio == kNoPin) continue;
    const float value = outputs.value[i];
    if (is_pwm(static_cast<OutputChannel>(i))) {
      const float duty = std::clamp(value, 0.0f, 1.0f);
      pwm_set_gpio_level(pin(gpio), static_cast<std::uint16_t>(duty * (kPwmWrap + 1) + 0.5f));
    } else {
      gpio_put(pin(gpio), value > 0.0f);
    }
  }
}

void PicoDriveSink::all_off() {
  DriveOutputs off;
  off.all_off();
  apply(off);
}

}  // namespace rotord::pico_w
