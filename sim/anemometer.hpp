#pragma once
// A cup anemometer at the hardware boundary (docs/care.md, "Wind stow"): a
// reed contact closing pulses_per_mps times a second per m/s of wind, as a
// hal::PulseCounter the controller reads, in virtual time. The wind itself
// is the caller's: set_wind_mps() whenever it changes (gusts, storms).
#include <cmath>
#include <cstdint>

#include "hal/pulse_counter.hpp"
#include "util/time.hpp"

namespace rotord::sim {

class Anemometer : public hal::PulseCounter {
 public:
  explicit Anemometer(double pulses_per_mps) : pulses_per_mps_(pulses_per_mps) {}

  void set_wind_mps(double mps) { wind_mps_ = mps < 0.0 ? 0.0 : mps; }
  double wind_mps() const { return wind_mps_; }
  /// Turns the cups from the last time to now_ms at the wind set.
  void advance_to(Millis now_ms) {
    if (now_ms <= now_ms_) return;
    turns_ += wind_mps_ * pulses_per_mps_ * static_cast<double>(now_ms - now_ms_) / 1000.0;
    now_ms_ = now_ms;
  }
  std::uint32_t count() override {
    // The counter wraps at 2^32, as the ports' do.
    return static_cast<std::uint32_t>(static_cast<std::uint64_t>(std::floor(turns_)));
  }

 private:
  double pulses_per_mps_;
  double wind_mps_ = 0.0;
  double turns_ = 0.0;
  Millis now_ms_ = 0;
};

}  // namespace rotord::sim
