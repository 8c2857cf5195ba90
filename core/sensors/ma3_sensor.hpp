#pragma once
#include <optional>

#include "hal/pwm_in.hpp"
#include "sensors/position_sensor.hpp"

namespace rotord {

/// Decodes an MA3 PWM period into its position code, per the US Digital
/// formula: code = t_on * (counts + 2) / (t_on + t_off) - 1, clamped. Uses the
/// duty ratio because the encoder's RC clock drifts by +-10 %.
std::optional<int> ma3_decode_code(const hal::PwmPeriod& period, int bits);

/// MA3 absolute encoder (single turn), with zero offset and direction.
class Ma3Sensor final : public PositionSensor {
 public:
  explicit Ma3Sensor(hal::PwmIn& input) : input_(input) {}
  void configure(int bits, float zero_deg, bool reverse) {
    bits_ = bits;
    zero_deg_ = zero_deg;
    reverse_ = reverse;
  }
  PositionReading read(Millis now) override;
  bool single_turn() const override { return true; }

 private:
  hal::PwmIn& input_;
  int bits_ = 12;
  float zero_deg_ = 0.0f;
  bool reverse_ = false;
};

}  // namespace rotord
