// The pin map in the image's binary info, for `picotool info`. Every pin is a
// setting (pins.*, applied at boot), so what is declared here is the default
// of each, read from the settings table itself so that the two cannot
// disagree; a board whose settings move a pin does not match this list.
// Pins that are unwired by default (buttons, emergency stop) are left out.
#include <cstdint>

#include "pico/binary_info.h"

namespace {

// The default of every setting, by its Id's name (kPinAzCw...).
namespace defaults {
#define SETTING(id, key, type, unit, min, max, def, group, flags, choices, label, condition, help) \
  constexpr int id = static_cast<int>(def);
#include "settings/settings_table.def"
#undef SETTING
}  // namespace defaults

// One bit per GPIO; an unwired default (-1) declares nothing.
constexpr std::uint32_t gpio_mask(int gpio) {
  return gpio < 0 ? 0u : 1u << gpio;
}

}  // namespace

bi_decl(bi_program_feature("Pin map: the defaults of the pins.* settings"));
bi_decl(bi_pin_mask_with_name(gpio_mask(defaults::kPinAzCw), "az CW relay (default, pins.az_cw)"));
bi_decl(bi_pin_mask_with_name(gpio_mask(defaults::kPinAzCcw),
                              "az CCW relay (default, pins.az_ccw)"));
bi_decl(bi_pin_mask_with_name(gpio_mask(defaults::kPinAzSpeed),
                              "az speed relay (default, pins.az_speed)"));
bi_decl(bi_pin_mask_with_name(gpio_mask(defaults::kPinAzBrake),
                              "az brake relay (default, pins.az_brake)"));
bi_decl(bi_pin_mask_with_name(gpio_mask(defaults::kPinAzT1), "az T1 switch (default, pins.az_t1)"));
bi_decl(bi_pin_mask_with_name(gpio_mask(defaults::kPinAzT2), "az T2 switch (default, pins.az_t2)"));
bi_decl(bi_pin_mask_with_name(gpio_mask(defaults::kPinAzL1),
                              "az CCW end switch L1 (default, pins.az_l1)"));
bi_decl(bi_pin_mask_with_name(gpio_mask(defaults::kPinAzL2),
                              "az CW end switch L2 (default, pins.az_l2)"));
bi_decl(bi_pin_mask_with_name(gpio_mask(defaults::kPinAzPwmCw),
                              "az H-bridge PWM CW (default, pins.az_pwm_cw)"));
bi_decl(bi_pin_mask_with_name(gpio_mask(defaults::kPinAzPwmCcw),
                              "az H-bridge PWM CCW (default, pins.az_pwm_ccw)"));
bi_decl(bi_pin_mask_with_name(gpio_mask(defaults::kPinAzMa3),
                              "az MA3 PWM in (default, pins.az_ma3)"));
bi_decl(bi_pin_mask_with_name(gpio_mask(defaults::kPinAzPot), "az pot ADC (default, pins.az_pot)"));
bi_decl(bi_pin_mask_with_name(gpio_mask(defaults::kPinElUp), "el UP relay (default, pins.el_up)"));
bi_decl(bi_pin_mask_with_name(gpio_mask(defaults::kPinElDown),
                              "el DOWN relay (default, pins.el_down)"));
bi_decl(bi_pin_mask_with_name(gpio_mask(defaults::kPinElSpeed),
                              "el speed relay (default, pins.el_speed)"));
bi_decl(bi_pin_mask_with_name(gpio_mask(defaults::kPinElLimitUp),
                              "el UP end switch (default, pins.el_limit_up)"));
bi_decl(bi_pin_mask_with_name(gpio_mask(defaults::kPinElLimitDown),
                              "el DOWN end switch (default, pins.el_limit_down)"));
bi_decl(bi_pin_mask_with_name(gpio_mask(defaults::kPinElPwmUp),
                              "el H-bridge PWM UP (default, pins.el_pwm_up)"));
bi_decl(bi_pin_mask_with_name(gpio_mask(defaults::kPinElPwmDown),
                              "el H-bridge PWM DOWN (default, pins.el_pwm_down)"));
bi_decl(bi_pin_mask_with_name(gpio_mask(defaults::kPinElMa3),
                              "el MA3 PWM in (default, pins.el_ma3)"));
bi_decl(bi_pin_mask_with_name(gpio_mask(defaults::kPinElPot), "el pot ADC (default, pins.el_pot)"));
bi_decl(bi_pin_mask_with_name(gpio_mask(defaults::kPinI2cSda),
                              "magnetometer I2C SDA (default, pins.i2c_sda)"));
bi_decl(bi_pin_mask_with_name(gpio_mask(defaults::kPinI2cScl),
                              "magnetometer I2C SCL (default, pins.i2c_scl)"));
