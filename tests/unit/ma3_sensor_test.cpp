#include <gtest/gtest.h>

#include <cmath>

#include "sensors/ma3_sensor.hpp"

namespace rotord {
namespace {

class FakePwm final : public hal::PwmIn {
 public:
  hal::PwmPeriod period{1, 4096, true};
  hal::PwmPeriod read() override { return period; }
};

// The MA3's PWM for `code`, with its RC clock running `clock_scale` times the
// nominal speed (0.9..1.1 over temperature): t_on = code + 1 clocks of a
// (counts + 1)-clock frame, as the datasheet draws it.
hal::PwmPeriod frame(int code, int bits, double clock_scale = 1.0) {
  const int counts = bits == 10 ? 1024 : 4096;
  const double us_per_clock = 1.0 / clock_scale;
  const auto high = static_cast<std::uint32_t>(std::lround((code + 1) * us_per_clock));
  const auto total = static_cast<std::uint32_t>(std::lround((counts + 1) * us_per_clock));
  return {high, total - high, true};
}

TEST(Ma3Decode, TwelveBitCodesAtTheNominalClock) {
  for (int code : {0, 1, 100, 2048, 4000, 4094}) {
    SCOPED_TRACE(code);
    EXPECT_EQ(ma3_decode_code(frame(code, 12), 12), code);
  }
  // The datasheet's end case: x = 4096 means position 4095.
  EXPECT_EQ(ma3_decode_code({4097, 0, true}, 12), 4095);
  EXPECT_EQ(ma3_decode_code({4096, 1, true}, 12), 4095);
}

TEST(Ma3Decode, TenBitCodes) {
  for (int code : {0, 1, 512, 1000, 1022}) {
    SCOPED_TRACE(code);
    EXPECT_EQ(ma3_decode_code(frame(code, 10), 10), code);
  }
  EXPECT_EQ(ma3_decode_code({1025, 0, true}, 10), 1023);
}

TEST(Ma3Decode, TheDutyRatioIgnoresClockDrift) {
  // +-10 % clock: the period changes by hundreds of us, the code by at most one.
  for (double scale : {0.9, 0.95, 1.05, 1.1}) {
    for (int code : {10, 1024, 3000}) {
      SCOPED_TRACE(scale);
      const auto decoded = ma3_decode_code(frame(code, 12, scale), 12);
      ASSERT_TRUE(decoded);
      EXPECT_NEAR(*decoded, code, 1);
    }
    const auto ten = ma3_decode_code(frame(700, 10, scale), 10);
    ASSERT_TRUE(ten);
    EXPECT_NEAR(*ten, 700, 1);
  }
}

TEST(Ma3Decode, NoSignal) {
  EXPECT_FALSE(ma3_decode_code({0, 0, true}, 12));
  EXPECT_FALSE(ma3_decode_code({100, 3997, false}, 12));
}

/// A 12-bit MA3 (zero at 0, not reversed) on a fake input, as most tests
/// start.
struct TwelveBitMa3 {
  FakePwm pwm;
  Ma3Sensor ma3{pwm};
  TwelveBitMa3() { ma3.configure(12, 0.0f, false); }
  /// What the sensor reads at `t_ms` of a frame for `code`.
  PositionReading at(int code, Millis t_ms) {
    pwm.period = frame(code, 12);
    return ma3.read(t_ms);
  }
};

TEST(Ma3Sensor, ReadsDegreesWithZeroAndDirection) {
  TwelveBitMa3 s;
  PositionReading r = s.at(1024, 0);
  ASSERT_TRUE(r.ok);
  EXPECT_NEAR(r.deg, 90.0f, 0.01f);
  EXPECT_EQ(r.raw, 1024.0f);

  s.ma3.configure(12, 30.0f, true);
  r = s.ma3.read(10);
  ASSERT_TRUE(r.ok);
  EXPECT_NEAR(r.deg, 240.0f, 0.01f);  // -90 - 30 wrapped
}

TEST(Ma3Sensor, APeriodThatDoesNotFitThePartIsAGlitch) {
  TwelveBitMa3 s;
  ASSERT_TRUE(s.at(2000, 0).ok);
  // A noise edge split the frame: a short "period" with a plausible-looking duty.
  s.pwm.period = {500, 500, true};
  PositionReading r = s.ma3.read(10);
  EXPECT_FALSE(r.ok);
  EXPECT_EQ(r.fault, SensorFault::kImplausible);
  EXPECT_EQ(s.ma3.last_reject(), Ma3Reject::kBadPeriod);
  // Two frames merged.
  s.pwm.period = {2001, 6193, true};
  EXPECT_FALSE(s.ma3.read(20).ok);
  EXPECT_TRUE(s.at(2001, 30).ok);
}

TEST(Ma3Sensor, AWrongBitsSettingIsRefusedNotMisread) {
  // A 10-bit part (1025 us) configured as 12-bit would read a wrong angle
  // forever; its period gives it away.
  TwelveBitMa3 s;
  s.pwm.period = frame(512, 10);
  EXPECT_FALSE(s.ma3.read(0).ok);
  EXPECT_EQ(s.ma3.last_reject(), Ma3Reject::kBadPeriod);
  s.ma3.configure(10, 0.0f, false);
  const PositionReading r = s.ma3.read(10);
  ASSERT_TRUE(r.ok);
  EXPECT_NEAR(r.deg, 180.0f, 0.01f);
}

TEST(Ma3Sensor, ASingleCorruptedPeriodNeverMovesTheAngle) {
  TwelveBitMa3 s;
  ASSERT_TRUE(s.at(1000, 0).ok);
  EXPECT_FALSE(s.at(3000, 10).ok);  // one bad frame, right length
  EXPECT_EQ(s.ma3.last_reject(), Ma3Reject::kUnconfirmed);
  const PositionReading r = s.at(1001, 20);  // back where it was: accepted at once
  ASSERT_TRUE(r.ok);
  EXPECT_EQ(r.raw, 1001.0f);
}

TEST(Ma3Sensor, ARealJumpIsTakenWhenTheNextPeriodConfirmsIt) {
  TwelveBitMa3 s;
  ASSERT_TRUE(s.at(1000, 0).ok);
  EXPECT_FALSE(s.at(3000, 10).ok);
  const PositionReading r = s.at(3003, 20);
  ASSERT_TRUE(r.ok);
  EXPECT_EQ(r.raw, 3003.0f);
}

TEST(Ma3Sensor, NorthIsASmallStepNotAJump) {
  TwelveBitMa3 s;
  int code = 4080;
  for (Millis t = 0; t < 400; t += 10) {  // 4080 .. 4095, 0 .. 23
    const PositionReading r = s.at(code, t);
    ASSERT_TRUE(r.ok) << code;
    code = (code + 1) % 4096;
  }
}

TEST(Ma3Sensor, LossThenReturnStartsAfresh) {
  TwelveBitMa3 s;
  ASSERT_TRUE(s.at(1000, 0).ok);
  s.pwm.period.valid = false;
  const PositionReading lost = s.ma3.read(10);
  EXPECT_FALSE(lost.ok);
  EXPECT_EQ(lost.fault, SensorFault::kNoSignal);
  EXPECT_TRUE(s.at(3000, 20).ok);  // re-plugged elsewhere: no confirmation needed
}

}  // namespace
}  // namespace rotord
