// Wind stow (docs/care.md), on the physics simulator in virtual time: an
// anemometer's pulses (sim/anemometer.hpp) or MQTT readings above
// wind.stow_mps for wind.hold_s turn the antenna to its stow heading,
// against the wind's torque on the motor; other moves are refused until
// calm; STOP works; an operator may override.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "care_rig.hpp"
#include "sim/anemometer.hpp"
#include "sim/rng.hpp"

namespace rotord {
namespace {

using care::WindState;
using settings::Id;

/// A rig with an anemometer on its pulse input (1.5 pulses per m/s).
struct WindRig {
  explicit WindRig(const char* profile, double az0_deg) : rig(profile, az0_deg) {
    settings::Settings& s = rig.settings();
    EXPECT_EQ(s.set(Id::kWindSource, 2).error, Error::kOk);
    EXPECT_EQ(s.set(Id::kWindStowAzDeg, 90).error, Error::kOk);
    rig.controller().attach_wind_pulses(&anemometer);
  }
  void tick() {
    anemometer.advance_to(rig.now() + 10);
    rig.tick();
  }
  void run_ms(Millis ms) {
    for (Millis t = 0; t < ms; t += 10) tick();
  }
  RotatorStatus status() { return rig.controller().status(); }
  float az_deg() { return status().az.position_deg; }
  bool az_driven() {
    const AxisState st = status().az.state;
    return st == AxisState::kStarting || st == AxisState::kMoving;
  }

  Rig rig;
  sim::Anemometer anemometer{1.5};
};

TEST(Wind, AStormOnTheAnemometerStowsWithinTwoSecondsOfTheHold) {
  WindRig w("ham4", 200.0);
  w.anemometer.set_wind_mps(8.0);
  w.run_ms(60000);
  ASSERT_EQ(w.status().wind_state, WindState::kCalm);
  ASSERT_NEAR(w.status().wind_speed_mps, 8.0f, 0.7f);
  // The storm: 25 m/s from now on; the wind holds wind.stow_mps (20) for
  // wind.hold_s (10 s) at storm + 10 s.
  w.anemometer.set_wind_mps(25.0);
  // Its torque costs the motor 30 % of its speed while it turns.
  w.rig.sim().slip(AxisId::kAz, 0.7, 120.0);
  const Millis storm_ms = w.rig.now();
  Millis began_ms = -1;
  for (Millis t = 0; t < 20000 && began_ms < 0; t += 10) {
    w.tick();
    if (w.az_driven()) began_ms = w.rig.now();
  }
  ASSERT_GT(began_ms, 0);
  const Millis after_hold_ms = began_ms - storm_ms - 10000;
  std::printf("stow began %lld ms after the wind held 20 m/s for wind.hold_s\n",
              static_cast<long long>(after_hold_ms));
  EXPECT_GE(after_hold_ms, 0);  // never before the hold
  EXPECT_LE(after_hold_ms, 2000);
  EXPECT_EQ(w.status().wind_state, WindState::kStowed);
  EXPECT_EQ(w.status().mode, Mode::kStow);
  // There within the turn's time at 70 % speed (110 deg at ~4 deg/s).
  w.run_ms(45000);
  EXPECT_NEAR(w.az_deg(), 90.0f, 1.5f);
  EXPECT_NEAR(w.rig.theta(), 90.0, 2.0);
  EXPECT_EQ(w.status().wind_stows, 1u);
}

TEST(Wind, OtherMovesAreRefusedUntilCalmForTheCalmTime) {
  WindRig w("ham4", 200.0);
  Controller& c = w.rig.controller();
  ASSERT_EQ(w.rig.settings().set(Id::kWindCalmMin, 2).error, Error::kOk);
  w.anemometer.set_wind_mps(25.0);
  w.run_ms(60000);
  ASSERT_EQ(w.status().wind_state, WindState::kStowed);
  EXPECT_NEAR(w.az_deg(), 90.0f, 1.5f);
  EXPECT_EQ(c.go_to(150.0f, std::nullopt), Error::kStowed);
  EXPECT_EQ(c.move(AxisId::kAz, Direction::kCw), Error::kStowed);
  EXPECT_EQ(c.park(), Error::kStowed);
  TrackRequest fixed;
  fixed.az_deg = 150.0f;
  EXPECT_EQ(c.track(fixed), TrackError::kStowed);
  w.run_ms(5000);
  EXPECT_NEAR(w.az_deg(), 90.0f, 1.5f);  // nothing moved
  // Below wind.stow_mps but not calm (wind.calm_mps 15): still stowed.
  w.anemometer.set_wind_mps(17.0);
  w.run_ms(300000);
  EXPECT_EQ(c.go_to(150.0f, std::nullopt), Error::kStowed);
  // Calm for two minutes: obeyed again.
  w.anemometer.set_wind_mps(6.0);
  w.run_ms(110000);
  EXPECT_EQ(c.go_to(150.0f, std::nullopt), Error::kStowed);
  w.run_ms(15000);
  EXPECT_EQ(w.status().wind_state, WindState::kCalm);
  EXPECT_EQ(c.go_to(150.0f, std::nullopt), Error::kOk);
  w.run_ms(30000);
  EXPECT_NEAR(w.az_deg(), 150.0f, 1.5f);
  EXPECT_EQ(w.status().wind_stows, 1u);
}

TEST(Wind, StopStillWorksAndResetCarriesTheStowOn) {
  WindRig w("ham4", 300.0);
  Controller& c = w.rig.controller();
  w.anemometer.set_wind_mps(25.0);
  w.run_ms(15000);
  ASSERT_EQ(w.status().mode, Mode::kStow);
  ASSERT_TRUE(w.az_driven());
  c.stop();
  w.run_ms(5000);
  EXPECT_FALSE(w.az_driven());
  const float stopped_at = w.az_deg();
  EXPECT_GT(stopped_at, 200.0f);  // stopped short of 90
  // Not commanded again by itself; other moves still refused.
  w.run_ms(30000);
  EXPECT_NEAR(w.az_deg(), stopped_at, 1.0f);
  EXPECT_TRUE(c.wind().stopped());
  EXPECT_EQ(c.go_to(150.0f, std::nullopt), Error::kStowed);
  // RESET: the stow goes on.
  EXPECT_EQ(c.reset(), Error::kOk);
  w.run_ms(60000);
  EXPECT_NEAR(w.az_deg(), 90.0f, 1.5f);
}

TEST(Wind, AnOperatorOverridesForASetTimeThenItStowsAgain) {
  WindRig w("ham4", 200.0);
  Controller& c = w.rig.controller();
  ASSERT_EQ(w.rig.settings().set(Id::kWindOverrideMin, 2).error, Error::kOk);
  w.anemometer.set_wind_mps(25.0);
  w.run_ms(60000);
  ASSERT_NEAR(w.az_deg(), 90.0f, 1.5f);
  ASSERT_EQ(c.wind_override(0), Error::kOk);  // wind.override_min: 2
  EXPECT_EQ(w.status().wind_state, WindState::kOverride);
  EXPECT_EQ(c.go_to(180.0f, std::nullopt), Error::kOk);
  w.run_ms(40000);
  EXPECT_NEAR(w.az_deg(), 180.0f, 1.5f);
  // Two minutes after the override, still windy: stowed again.
  w.run_ms(85000);
  EXPECT_EQ(w.status().wind_state, WindState::kStowed);
  w.run_ms(40000);
  EXPECT_NEAR(w.az_deg(), 90.0f, 1.5f);
  EXPECT_EQ(w.status().wind_stows, 2u);
  EXPECT_EQ(w.status().wind_overrides, 1u);
  // Nothing to override when calm.
  WindRig calm("ham4", 200.0);
  calm.run_ms(5000);
  EXPECT_EQ(calm.rig.controller().wind_override(0), Error::kNotFound);
}

TEST(Wind, GustsBelowTheThresholdNeverStow) {
  WindRig w("g5500", 200.0);
  sim::Rng rng(5);
  // An hour of 10 m/s with gusts to 19.5 m/s lasting up to 15 s.
  for (int n = 0; n < 240; ++n) {
    w.anemometer.set_wind_mps(10.0 + 4.0 * rng.uniform());
    w.run_ms(10000);
    w.anemometer.set_wind_mps(15.0 + 4.5 * rng.uniform());
    w.run_ms(5000);
  }
  EXPECT_EQ(w.status().wind_stows, 0u);
  EXPECT_EQ(w.status().wind_state, WindState::kCalm);
  // A gust over the threshold shorter than wind.hold_s does not stow either.
  w.anemometer.set_wind_mps(30.0);
  w.run_ms(8000);
  w.anemometer.set_wind_mps(10.0);
  w.run_ms(10000);
  EXPECT_EQ(w.status().wind_stows, 0u);
}

TEST(Wind, FromMqttReadingsWithTheBoomIntoTheWind) {
  Rig r("g5500", 200.0);
  Controller& c = r.controller();
  settings::Settings& s = r.settings();
  ASSERT_EQ(s.set(Id::kWindSource, 1).error, Error::kOk);
  ASSERT_EQ(s.set(Id::kWindMqttUnit, 1).error, Error::kOk);  // km/h
  ASSERT_EQ(s.set(Id::kWindIntoWind, 1).error, Error::kOk);
  r.tick();
  // A weather station every 5 s: 90 km/h (25 m/s) from 300 deg.
  Millis began_ms = -1;
  Millis held_ms = -1;
  for (Millis t = 0; t < 40000; t += 10) {
    if (t % 5000 == 0) {
      c.wind_speed_message("90");
      c.wind_direction_message("300");
      if (held_ms < 0) held_ms = r.now() + 10000;
    }
    r.tick();
    if (began_ms < 0 && c.status().az.state == AxisState::kStarting) began_ms = r.now();
  }
  ASSERT_GT(began_ms, 0);
  std::printf("MQTT: stow began %lld ms after the readings held 20 m/s for wind.hold_s\n",
              static_cast<long long>(began_ms - held_ms));
  EXPECT_LE(began_ms - held_ms, 2000);
  EXPECT_GE(began_ms - held_ms, 0);
  r.run_ms(40000);
  EXPECT_NEAR(r.az().position_deg, 300.0f, 1.5f);
  // The wind veers by 40 deg: the boom follows.
  for (Millis t = 0; t < 60000; t += 10) {
    if (t % 5000 == 0) {
      c.wind_speed_message("90");
      c.wind_direction_message("340");
    }
    r.tick();
  }
  EXPECT_NEAR(r.az().position_deg, 340.0f, 1.5f);
  // Garbage, a negative speed, a wrong direction: counted, nothing moves.
  c.wind_speed_message("{\"speed\": 3}");
  c.wind_speed_message("-4");
  c.wind_direction_message("720");
  r.run_ms(1000);
  EXPECT_EQ(c.wind().rejected(care::WindReject::kGarbage), 1u);
  EXPECT_EQ(c.wind().rejected(care::WindReject::kNegative), 1u);
  EXPECT_EQ(c.wind().rejected(care::WindReject::kBadDirection), 1u);
  EXPECT_NEAR(c.wind().speed_mps(), 25.0f, 0.01f);
  EXPECT_NEAR(r.az().position_deg, 340.0f, 1.5f);
}

TEST(Wind, AStowHeadingOutsideTheTravelIsRefused) {
  // As every front end saves one key (settings' save_from_text).
  Rig r("ham4", 200.0);
  settings::Settings& s = r.settings();
  // Unused (no source): any value may stand.
  ASSERT_EQ(s.save_from_text(Id::kWindStowAzDeg, "400").error, Error::kOk);
  EXPECT_EQ(s.save_from_text(Id::kWindSource, "pulses").error, Error::kOutOfRange);
  EXPECT_EQ(s.i(Id::kWindSource), 0);
  ASSERT_EQ(s.save_from_text(Id::kWindStowAzDeg, "90").error, Error::kOk);
  ASSERT_EQ(s.save_from_text(Id::kWindSource, "pulses").error, Error::kOk);
  const settings::Rejection outside = s.save_from_text(Id::kWindStowAzDeg, "400");
  EXPECT_EQ(outside.error, Error::kOutOfRange);
  std::printf("refused: %s\n", outside.reason);
  // A calm speed above the stow speed.
  EXPECT_EQ(s.save_from_text(Id::kWindCalmMps, "30").error, Error::kOutOfRange);
  EXPECT_EQ(s.get(Id::kWindStowAzDeg), 90.0);
  EXPECT_EQ(s.get(Id::kWindCalmMps), 15.0);
}

TEST(Wind, OffByDefault) {
  WindRig w("ham4", 200.0);
  ASSERT_EQ(w.rig.settings().set(Id::kWindSource, 0).error, Error::kOk);
  w.anemometer.set_wind_mps(40.0);
  w.run_ms(60000);
  EXPECT_EQ(w.status().wind_state, WindState::kOff);
  EXPECT_EQ(w.rig.controller().go_to(150.0f, std::nullopt), Error::kOk);
  EXPECT_EQ(settings::Settings().i(Id::kWindSource), 0);
}

}  // namespace
}  // namespace rotord
