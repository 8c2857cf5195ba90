#include "settings/pin_rules.hpp"

#include <cstdio>
#include <cstring>

namespace rotord::settings {
namespace {

constexpr const char kPinPrefix[] = "pins.";

bool is_adc_pin(int gpio) {
  return gpio >= 26 && gpio <= 28;
}

// RP2040 pin mux: GPIO n carries I2C block (n / 2) % 2, SDA on even pins and
// SCL on odd ones.
int i2c_block(int gpio) {
  return (gpio / 2) % 2;
}

Error fail(char* detail, std::size_t capacity, const char* format, const char* key,
           const char* other, int gpio) {
  std::snprintf(detail, capacity, format, key, other, gpio);
  return Error::kOutOfRange;
}

}  // namespace

bool is_pin(Id id) {
  return std::strncmp(def(id).key, kPinPrefix, sizeof kPinPrefix - 1) == 0;
}

std::optional<Error> check_pins(const Settings& s, char* detail, std::size_t capacity) {
  for (std::size_t n = 0; n < kCount; ++n) {
    const auto id = static_cast<Id>(n);
    if (!is_pin(id)) continue;
    const int gpio = s.i(id);
    if (gpio == kNoPin) continue;
    const char* key = def(id).key;
    if (gpio >= 23 && gpio <= 25)
      return fail(detail, capacity, "%s%s: GPIO %d belongs to the Pico W's Wi-Fi chip", key, "",
                  gpio);
    for (std::size_t m = 0; m < n; ++m) {
      const auto other = static_cast<Id>(m);
      if (is_pin(other) && s.i(other) == gpio)
        return fail(detail, capacity, "%s and %s both use GPIO %d", def(other).key, key, gpio);
    }
  }
  for (const Id pot : {Id::kPinAzPot, Id::kPinElPot}) {
    const int gpio = s.i(pot);
    if (gpio != kNoPin && !is_adc_pin(gpio))
      return fail(detail, capacity, "%s%s: GPIO %d has no ADC; use 26, 27 or 28", def(pot).key, "",
                  gpio);
  }
  const int sda = s.i(Id::kPinI2cSda);
  const int scl = s.i(Id::kPinI2cScl);
  if ((sda == kNoPin) != (scl == kNoPin))
    return fail(detail, capacity, "%s and %s: wire both or neither (GPIO %d)",
                def(Id::kPinI2cSda).key, def(Id::kPinI2cScl).key, sda == kNoPin ? scl : sda);
  if (sda != kNoPin && (sda % 2 != 0 || scl % 2 != 1 || i2c_block(sda) != i2c_block(scl)))
    return fail(detail, capacity,
                "%s and %s must be the SDA (even) and SCL (odd) pins of one I2C block, e.g. 0 "
                "and 1 (GPIO %d)",
                def(Id::kPinI2cSda).key, def(Id::kPinI2cScl).key, sda);
  return std::nullopt;
}

}  // namespace rotord::settings
