#pragma once
#include <cstdint>
#include <optional>

#include "hal/pwm_in.hpp"
#include "sensors/position_sensor.hpp"

namespace rotord {

/// The PWM frame of an MA3 part (US Digital MA3 datasheet): a 12-bit part
/// runs at 244 Hz typical (period 4097 us, one count per us), a 10-bit part at
/// 975 Hz (1025 us). The on-chip RC clock drifts +-10 % over temperature
/// (220..268 Hz and 877..1072 Hz), so only the duty ratio carries the angle.
struct Ma3Timing {
  int counts;                   ///< positions per turn: 4096 or 1024
  std::uint32_t min_period_us;  ///< shortest plausible period, with 5 % margin
  std::uint32_t max_period_us;  ///< longest plausible period, with 5 % margin
};

/// The frame of a 10- or 12-bit part (any other `bits` is treated as 12).
Ma3Timing ma3_timing(int bits);

/// Decodes an MA3 PWM period into its position code. The datasheet's frame
/// is t_on = code + 1 clocks of counts + 1, so the code is
/// round(t_on * (counts + 1) / (t_on + t_off)) - 1, clamped to 0..counts-1
/// (its x = counts case is position counts - 1). Uses only the duty ratio,
/// never the period. Integer arithmetic: the Pico and the host agree exactly.
/// nullopt: no signal (invalid period or zero length).
std::optional<int> ma3_decode_code(const hal::PwmPeriod& period, int bits);

/// Why one period was not turned into a position.
enum class Ma3Reject : std::uint8_t {
  kNone,
  kNoSignal,    ///< no edges within the input's timeout
  kBadPeriod,   ///< period outside the part's frame: a glitch, or the wrong ma3_bits
  kUnconfirmed  ///< a jump that the next period has not confirmed yet
};

/// MA3 absolute encoder (single turn), with zero offset and direction.
///
/// Glitch rejection, before the axis's own plausibility checks: a period
/// whose length does not fit the part is dropped (a noise edge splits or
/// merges periods, which changes their length); a code more than
/// kConfirmCounts (1/64 turn) away from the last accepted one is taken only
/// when the next period agrees with it, so one corrupted period never moves
/// the reported angle, while a real fast change costs one reading. The 359/0
/// wrap counts as a small step, not a jump.
class Ma3Sensor final : public PositionSensor {
 public:
  explicit Ma3Sensor(hal::PwmIn& input) : input_(input) {}
  void configure(int bits, float zero_deg, bool reverse);
  PositionReading read(Millis now) override;
  bool single_turn() const override { return true; }
  void restart() override { have_code_ = have_candidate_ = false; }
  Ma3Reject last_reject() const { return last_reject_; }

 private:
  int confirm_counts() const { return timing_.counts / 64; }
  int circular_distance(int a, int b) const;

  hal::PwmIn& input_;
  int bits_ = 12;
  Ma3Timing timing_ = ma3_timing(12);
  float zero_deg_ = 0.0f;
  bool reverse_ = false;
  bool have_code_ = false;
  int code_ = 0;
  bool have_candidate_ = false;
  int candidate_ = 0;
  Ma3Reject last_reject_ = Ma3Reject::kNone;
};

}  // namespace rotord
