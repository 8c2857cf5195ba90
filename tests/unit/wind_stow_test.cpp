// The wind-stow rule on its own (core/care/wind_stow.*, docs/care.md): the
// hold time, the calm time, the override, bad readings counted, and the
// anemometer's pulse meter.
#include "care/wind_stow.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "care/wind_pulses.hpp"

namespace rotord::care {
namespace {

WindConfig windy_config() {
  WindConfig c;
  c.source = WindSource::kMqtt;
  c.stow_mps = 20.0f;
  c.calm_mps = 15.0f;
  c.hold_ms = 10000;
  c.calm_ms = 600000;
  c.override_ms = 1800000;
  return c;
}

/// Feeds `mps` every `every_ms` from `from_ms` for `for_ms`, ticking every 10 ms.
Millis blow(WindStow& w, float mps, Millis from_ms, Millis for_ms, Millis every_ms = 1000) {
  Millis t = from_ms;
  for (; t < from_ms + for_ms; t += 10) {
    if ((t - from_ms) % every_ms == 0) w.speed(mps, t);
    w.tick(t);
  }
  return t;
}

TEST(WindStow, OffUntilASourceIsConfigured) {
  WindStow w;
  w.speed(50.0f, 0);
  blow(w, 50.0f, 0, 30000);
  EXPECT_EQ(w.state(), WindState::kOff);
  EXPECT_FALSE(w.refusing());
  EXPECT_EQ(w.stows(), 0u);
}

TEST(WindStow, StowsOnlyWhenTheThresholdIsHeldForTheHoldTime) {
  WindStow w;
  w.configure(windy_config());
  Millis t = blow(w, 25.0f, 0, 9000);  // 9 s: not yet
  EXPECT_EQ(w.state(), WindState::kRising);
  t = blow(w, 10.0f, t, 1000);  // a lull ends the spell
  EXPECT_EQ(w.state(), WindState::kCalm);
  t = blow(w, 25.0f, t, 9990);
  EXPECT_FALSE(w.refusing());
  t = blow(w, 25.0f, t, 20);
  EXPECT_TRUE(w.refusing());
  EXPECT_EQ(w.stows(), 1u);
  EXPECT_TRUE(w.take_stow_request());
  EXPECT_FALSE(w.take_stow_request());
  (void)t;
}

TEST(WindStow, CalmForTheCalmTimeEndsIt) {
  WindStow w;
  w.configure(windy_config());
  Millis t = blow(w, 25.0f, 0, 11000);
  ASSERT_TRUE(w.refusing());
  // Between calm and stow: not calm, stays stowed.
  t = blow(w, 17.0f, t, 900000, 5000);
  EXPECT_TRUE(w.refusing());
  t = blow(w, 5.0f, t, 599000, 5000);
  EXPECT_TRUE(w.refusing());
  EXPECT_GT(w.calm_left_ms(t), 0);
  t = blow(w, 5.0f, t, 2000, 1000);
  EXPECT_FALSE(w.refusing());
  EXPECT_EQ(w.state(), WindState::kCalm);
  EXPECT_EQ(w.stows(), 1u);
}

TEST(WindStow, AnOverrideLetsMovesThroughThenStowsAgainIfStillWindy) {
  WindStow w;
  w.configure(windy_config());
  Millis t = blow(w, 25.0f, 0, 11000);
  ASSERT_TRUE(w.take_stow_request());
  EXPECT_FALSE(WindStow().override_now(t));  // nothing stowed: refused
  ASSERT_TRUE(w.override_now(t, 60000));
  EXPECT_FALSE(w.refusing());
  EXPECT_EQ(w.state(), WindState::kOverride);
  EXPECT_EQ(w.override_left_ms(t), 60000);
  t = blow(w, 25.0f, t, 59000);
  EXPECT_FALSE(w.refusing());
  t = blow(w, 25.0f, t, 2000);
  EXPECT_TRUE(w.refusing());
  EXPECT_EQ(w.stows(), 2u);
  EXPECT_TRUE(w.take_stow_request());
  // Ended early: stowed at once.
  ASSERT_TRUE(w.override_now(t));
  w.end_override();
  EXPECT_TRUE(w.refusing());
  EXPECT_EQ(w.overrides(), 2u);
}

TEST(WindStow, BadReadingsAreCountedAndNeverTaken) {
  WindStow w;
  w.configure(windy_config());
  w.speed_text("banana", 1.0f, 0);
  w.speed_text("", 1.0f, 0);
  w.speed_text("12 m/s", 1.0f, 0);
  w.speed_text("nan", 1.0f, 0);
  w.speed(-3.0f, 0);
  w.speed_text("-0.5", 1.0f, 0);
  w.speed(500.0f, 0);
  w.speed(std::nanf(""), 0);
  w.direction_text("north", 0);
  w.direction(400.0f, 0);
  w.direction(-1.0f, 0);
  EXPECT_EQ(w.rejected(WindReject::kGarbage), 5u);
  EXPECT_EQ(w.rejected(WindReject::kNegative), 2u);
  EXPECT_EQ(w.rejected(WindReject::kTooHigh), 1u);
  EXPECT_EQ(w.rejected(WindReject::kBadDirection), 3u);
  EXPECT_EQ(w.readings(), 0u);
  EXPECT_FALSE(w.has_speed());
  EXPECT_FALSE(w.has_direction());
  // A unit: 90 km/h is 25 m/s.
  w.speed_text(" 90\n", 1.0f / 3.6f, 0);
  EXPECT_NEAR(w.speed_mps(), 25.0f, 1e-3f);
  w.direction_text("360", 0);
  EXPECT_EQ(w.direction_deg(), 0.0f);
}

TEST(WindStow, ASilentSourceIsCountedOnceAndNeverStowsOnAnOldGust) {
  WindStow w;
  w.configure(windy_config());
  w.speed(25.0f, 0);
  Millis t = 0;
  for (; t < 300000; t += 10) w.tick(t);
  // One reading of 25 m/s, then silence: after kStaleMs it no longer counts.
  EXPECT_EQ(w.rejected(WindReject::kStale), 1u);
  EXPECT_EQ(w.stows(), 1u);  // the hold passed while it was fresh
  // A stow stays through a silence: only calm readings end it.
  EXPECT_TRUE(w.refusing());
}

TEST(WindStow, BoomIntoTheWindIsAimedAgainWhenTheWindVeers) {
  WindStow w;
  WindConfig c = windy_config();
  c.into_wind = true;
  w.configure(c);
  w.direction(270.0f, 0);
  Millis t = blow(w, 25.0f, 0, 11000);
  ASSERT_TRUE(w.take_stow_request());
  w.direction(290.0f, t);
  t = blow(w, 25.0f, t, 1000);
  EXPECT_FALSE(w.take_stow_request());  // 20 deg: not worth a start
  w.direction(305.0f, t);
  t = blow(w, 25.0f, t, 1000);
  EXPECT_TRUE(w.take_stow_request());
  // Across north.
  w.direction(10.0f, t);
  t = blow(w, 25.0f, t, 1000);
  EXPECT_TRUE(w.take_stow_request());
  w.direction(355.0f, t);
  blow(w, 25.0f, t, 1000);
  EXPECT_FALSE(w.take_stow_request());
}

TEST(WindPulseMeter, TwoSecondsOfPulsesOverPulsesPerMps) {
  WindPulseMeter m;
  std::uint32_t count = 4294967000u;  // across the counter's wrap
  std::optional<float> last;
  // 30 Hz for 5 s at 1.5 pulses per m/s: 20 m/s.
  for (Millis t = 0; t <= 5000; t += 10) {
    if (t % 100 == 0 && t > 0) count += 3;
    if (const auto v = m.sample(count, t, 1.5f)) last = v;
  }
  ASSERT_TRUE(last.has_value());
  EXPECT_NEAR(*last, 20.0f, 0.2f);
  // The anemometer stops: within 2 s it reads 0.
  for (Millis t = 5010; t <= 8500; t += 10)
    if (const auto v = m.sample(count, t, 1.5f)) last = v;
  EXPECT_EQ(*last, 0.0f);
}

}  // namespace
}  // namespace rotord::care
