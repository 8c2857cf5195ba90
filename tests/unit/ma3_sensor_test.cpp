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

TEST(Ma3Sensor, ReadsDegreesWithZeroAndDirection) {
  FakePwm pwm;
  Ma3Sensor ma3(pwm);
  ma3.configure(12, 0.0f, false);
  pwm.period = frame(1024, 12);
  PositionReading r = ma3.read(0);
  ASSERT_TRUE(r.ok);
  EXPECT_NEAR(r.deg, 90.0f, 0.01f);
  EXPECT_EQ(r.raw, 1024.0f);

  ma3.configure(12, 30.0f, true);
  r = ma3.read(10);
  ASSERT_TRUE(r.ok);
  EXPECT_NEAR(r.deg, 240.0f, 0.01f);  // -90 - 30 wrapped
}

TEST(Ma3Sensor, APeriodThatDoesNotFitThePartIsAGlitch) {
  FakePwm pwm;
  Ma3Sensor ma3(pwm);
  ma3.configure(12, 0.0f, false);
  pwm.period = frame(2000, 12);
  ASSERT_TRUE(ma3.read(0).ok);
  // A noise edge split the frame: a short "period" with a plausible-looking duty.
  pwm.period = {500, 500, true};
  PositionReading r = ma3.read(10);
  EXPECT_FALSE(r.ok);
  EXPECT_EQ(r.fault, SensorFault::kImplausible);
  EXPECT_EQ(ma3.last_reject(), Ma3Reject::kBadPeriod);
  // Two frames merged.
  pwm.period = {2001, 6193, true};
  EXPECT_FALSE(ma3.read(20).ok);
  pwm.period = frame(2001, 12);
  EXPECT_TRUE(ma3.read(30).ok);
}

TEST(Ma3Sensor, AWrongBitsSettingIsRefusedNotMisread) {
  // A 10-bit part (1025 us) configured as 12-bit would read a wrong angle
  // forever; its period gives it away.
  FakePwm pwm;
  Ma3Sensor ma3(pwm);
  ma3.configure(12, 0.0f, false);
  pwm.period = frame(512, 10);
  EXPECT_FALSE(ma3.read(0).ok);
  EXPECT_EQ(ma3.last_reject(), Ma3Reject::kBadPeriod);
  ma3.configure(10, 0.0f, false);
  const PositionReading r = ma3.read(10);
  ASSERT_TRUE(r.ok);
  EXPECT_NEAR(r.deg, 180.0f, 0.01f);
}

TEST(Ma3Sensor, ASingleCorruptedPeriodNeverMovesTheAngle) {
  FakePwm pwm;
  Ma3Sensor ma3(pwm);
  ma3.configure(12, 0.0f, false);
  pwm.period = frame(1000, 12);
  ASSERT_TRUE(ma3.read(0).ok);
  pwm.period = frame(3000, 12);  // one bad frame, right length
  EXPECT_FALSE(ma3.read(10).ok);
  EXPECT_EQ(ma3.last_reject(), Ma3Reject::kUnconfirmed);
  pwm.period = frame(1001, 12);  // back where it was: accepted at once
  const PositionReading r = ma3.read(20);
  ASSERT_TRUE(r.ok);
  EXPECT_EQ(r.raw, 1001.0f);
}

TEST(Ma3Sensor, ARealJumpIsTakenWhenTheNextPeriodConfirmsIt) {
  FakePwm pwm;
  Ma3Sensor ma3(pwm);
  ma3.configure(12, 0.0f, false);
  pwm.period = frame(1000, 12);
  ASSERT_TRUE(ma3.read(0).ok);
  pwm.period = frame(3000, 12);
  EXPECT_FALSE(ma3.read(10).ok);
  pwm.period = frame(3003, 12);
  const PositionReading r = ma3.read(20);
  ASSERT_TRUE(r.ok);
  EXPECT_EQ(r.raw, 3003.0f);
}

TEST(Ma3Sensor, NorthIsASmallStepNotAJump) {
  FakePwm pwm;
  Ma3Sensor ma3(pwm);
  ma3.configure(12, 0.0f, false);
  int code = 4080;
  for (Millis t = 0; t < 400; t += 10) {  // 4080 .. 4095, 0 .. 23
    pwm.period = frame(code, 12);
    const PositionReading r = ma3.read(t);
    ASSERT_TRUE(r.ok) << code;
    code = (code + 1) % 4096;
  }
}

TEST(Ma3Sensor, LossThenReturnStartsAfresh) {
  FakePwm pwm;
  Ma3Sensor ma3(pwm);
  ma3.configure(12, 0.0f, false);
  pwm.period = frame(1000, 12);
  ASSERT_TRUE(ma3.read(0).ok);
  pwm.period.valid = false;
  const PositionReading lost = ma3.read(10);
  EXPECT_FALSE(lost.ok);
  EXPECT_EQ(lost.fault, SensorFault::kNoSignal);
  pwm.period = frame(3000, 12);  // re-plugged elsewhere: no confirmation needed
  EXPECT_TRUE(ma3.read(20).ok);
}

}  // namespace
}  // namespace rotord
