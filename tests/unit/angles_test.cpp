#include "motion/angles.hpp"

#include <gtest/gtest.h>

namespace rotord {
namespace {

TEST(Angles, WrapsInto0To360) {
  EXPECT_FLOAT_EQ(wrap_360(370.0f), 10.0f);
  EXPECT_FLOAT_EQ(wrap_360(-10.0f), 350.0f);
  EXPECT_FLOAT_EQ(wrap_360(360.0f), 0.0f);
  EXPECT_FLOAT_EQ(wrap_180(190.0f), -170.0f);
}

TEST(Angles, CompassTargetOn450RotatorTurnsLeast) {
  // At 400 deg, 60 deg is reached at 420 (20 deg away), not at 60 (340 deg away).
  EXPECT_FLOAT_EQ(*choose_unwrapped_az(60.0f, 400.0f, 0.0f, 450.0f, false), 420.0f);
  // At 100 deg, 60 deg is reached directly.
  EXPECT_FLOAT_EQ(*choose_unwrapped_az(60.0f, 100.0f, 0.0f, 450.0f, false), 60.0f);
  // 100 deg has no second turn inside 0..450 (460 is outside).
  EXPECT_FLOAT_EQ(*choose_unwrapped_az(100.0f, 440.0f, 0.0f, 450.0f, false), 100.0f);
}

TEST(Angles, CompassTargetOnMinus180To540Rotator) {
  // Three candidates for 350: -10, 350 and 710 (outside); from 20 the nearest is -10.
  EXPECT_FLOAT_EQ(*choose_unwrapped_az(350.0f, 20.0f, -180.0f, 540.0f, false), -10.0f);
  // From 300 it is 350.
  EXPECT_FLOAT_EQ(*choose_unwrapped_az(350.0f, 300.0f, -180.0f, 540.0f, false), 350.0f);
  // 170 from 500: 530 is 30 away, 170 is 330 away.
  EXPECT_FLOAT_EQ(*choose_unwrapped_az(170.0f, 500.0f, -180.0f, 540.0f, false), 530.0f);
}

TEST(Angles, UnreachableCompassTargetIsRefused) {
  // A rotator limited to 20..300 cannot reach 330.
  EXPECT_FALSE(choose_unwrapped_az(330.0f, 100.0f, 20.0f, 300.0f, false).has_value());
}

TEST(Angles, ContinuousRotatorTakesTheShortWay) {
  EXPECT_FLOAT_EQ(*choose_unwrapped_az(10.0f, 350.0f, 0.0f, 360.0f, true), 370.0f);
  EXPECT_FLOAT_EQ(*choose_unwrapped_az(350.0f, 10.0f, 0.0f, 360.0f, true), -10.0f);
}

}  // namespace
}  // namespace rotord
