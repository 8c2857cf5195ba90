#include "net/setup_ap.hpp"

#include <gtest/gtest.h>

#include "settings/settings.hpp"

namespace rotord::net {
namespace {

constexpr Millis kMinute = 60'000;

TEST(SetupAp, AnOpenAccessPointIsOfferedOnlyWithinItsWindowAfterPowerOn) {
  const SetupApPolicy open{false, 30};
  EXPECT_TRUE(open.may_offer(0, 0));
  EXPECT_TRUE(open.may_offer(30 * kMinute - 1, 0));
  EXPECT_FALSE(open.may_offer(30 * kMinute, 0));
  EXPECT_FALSE(open.may_offer(24 * 60 * kMinute, 0));  // the router was down all day
}

TEST(SetupAp, APhoneStillJoinedIsNotCutOffMidSetup) {
  const SetupApPolicy open{false, 30};
  EXPECT_TRUE(open.may_offer(45 * kMinute, 1));
  EXPECT_FALSE(open.may_offer(45 * kMinute, 0));  // gone once it leaves
}

TEST(SetupAp, AWpa2AccessPointAndAZeroWindowHaveNoLimit) {
  EXPECT_TRUE((SetupApPolicy{true, 30}).may_offer(48 * 60 * kMinute, 0));
  EXPECT_TRUE((SetupApPolicy{false, 0}).may_offer(48 * 60 * kMinute, 0));
}

TEST(SetupAp, TheSettingsDefaultIsThirtyMinutes) {
  settings::Settings s;
  EXPECT_EQ(s.i(settings::Id::kWifiApOpenMinutes), 30);
  EXPECT_EQ(s.set(settings::Id::kWifiApOpenMinutes, 1441.0).error, Error::kOutOfRange);
}

}  // namespace
}  // namespace rotord::net
