// Self-commissioning's known bearing (docs/commissioning.md) on the
// simulator, in virtual time: an absolute sensor mounted off north (the
// simulated MA3 and magnetometer read the antenna's bearing plus a mounting
// angle), the owner gives the bearing the antenna points at, and the
// proposed zero, once accepted, makes the reading that bearing. Nothing
// moves and nothing is written before the owner accepts; bad input is
// refused with the reason.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>
#include <string>

#include "motion/angles.hpp"
#include "rotator/controller.hpp"
#include "sim/profiles.hpp"
#include "sim/sim_rotator.hpp"

namespace rotord {
namespace {

using settings::Id;

struct Bench {
  /// The profile's settings, its azimuth at `theta_deg` with its absolute
  /// sensors mounted `mount_deg` off north.
  Bench(const char* name, double theta_deg, double mount_deg) : profile(*sim::find_profile(name)) {
    for (const auto& o : profile.overrides) settings.set(*settings::find(o.key), o.value);
    rotator = std::make_unique<sim::SimRotator>(profile, 7);
    rotator->set_theta_deg(AxisId::kAz, theta_deg);
    rotator->set_sensor_mount_deg(AxisId::kAz, mount_deg);
    controller =
        std::make_unique<Controller>(settings, rotator->io(AxisId::kAz), rotator->io(AxisId::kEl));
    controller->begin(now);
  }
  /// The azimuth on the simulated magnetometer, calibrated to its true
  /// extremes (x = 300 +- 1200, y = -150 +- 900), so its heading is the
  /// antenna's bearing plus the mounting angle plus the declination.
  void use_magnetometer(double declination_deg) {
    ASSERT_EQ(settings.set(Id::kAzSensor, 2).error, Error::kOk);
    settings.set(Id::kMagXMin, -900);
    settings.set(Id::kMagXMax, 1500);
    settings.set(Id::kMagYMin, -1050);
    settings.set(Id::kMagYMax, 750);
    ASSERT_EQ(settings.set(Id::kMagDeclinationDeg, declination_deg).error, Error::kOk);
  }
  void run_ms(Millis ms) {
    for (const Millis end = now + ms; now < end;) {
      now += 10;
      rotator->advance_to(now);
      controller->tick(now);
    }
  }
  float position_deg() { return controller->status().az.position_deg; }
  Error bearing(float bearing_deg, AxisId axis = AxisId::kAz) {
    Commissioning::Request r;
    r.axis = axis;
    r.step = Commissioning::Step::kBearing;
    r.bearing_deg = bearing_deg;
    return controller->commission(r, &why);
  }
  /// The run's one proposal: the setting and its value.
  std::pair<Id, double> proposal() const {
    const Commissioning& c = controller->commissioning();
    EXPECT_EQ(c.state(), Commissioning::State::kDone) << c.reason();
    EXPECT_EQ(c.proposal_count(), 1u);
    if (c.proposal_count() == 0) return {Id::kAzMa3ZeroDeg, NAN};
    return {c.proposal(0).id, c.proposal(0).value};
  }
  /// Accepts, lets the new zero take effect, and returns the reading.
  float accept_and_read() {
    EXPECT_EQ(controller->accept_commissioning().error, Error::kOk);
    run_ms(1000);
    return position_deg();
  }

  sim::Profile profile;
  settings::Settings settings;
  std::unique_ptr<sim::SimRotator> rotator;
  std::unique_ptr<Controller> controller;
  Millis now = 0;
  const char* why = "";
};

// How far a reading is from a bearing, across north.
double off_deg(double reading_deg, double bearing_deg) {
  return std::fabs(wrap_180(static_cast<float>(reading_deg - bearing_deg)));
}

TEST(KnownBearing, MagnetometerReading350AtBearing10ProposesAHeadingOffsetOf20) {
  // The antenna points at 10 deg; the chip's north is 20 deg off, so it
  // reads 350: the offset that corrects it is +20, across north.
  Bench b("g5500", 10.0, -20.0);
  b.use_magnetometer(0.0);
  b.run_ms(2000);
  const float before = b.position_deg();
  ASSERT_LT(off_deg(before, 350.0), 0.5) << before;
  ASSERT_EQ(b.bearing(10.0f), Error::kOk) << b.why;
  const auto [id, value] = b.proposal();
  EXPECT_EQ(id, Id::kMagDeclinationDeg);
  EXPECT_NEAR(value, 20.0, 0.5);
  // Proposed, not written: the value in force and the reading stay.
  EXPECT_EQ(b.settings.f(Id::kMagDeclinationDeg), 0.0f);
  b.run_ms(500);
  EXPECT_LT(off_deg(b.position_deg(), 350.0), 0.5);
  const float after = b.accept_and_read();
  std::printf(
      "magnetometer: read %.2f at bearing 10, proposed mag.declination_deg %.3f, reads %.2f\n",
      static_cast<double>(before), value, static_cast<double>(after));
  EXPECT_LT(off_deg(after, 10.0), 0.3) << after;
  EXPECT_NEAR(b.settings.f(Id::kMagDeclinationDeg), value, 1e-3);
}

TEST(KnownBearing, MagnetometerOffsetWrapsIntoItsRange) {
  // Reading 10 where the bearing is 350, with a declination of -170 in
  // force: the offset turns by -20, to -190, which is +170.
  Bench b("g5500", 350.0, 190.0);  // 350 + 190 - 170 = 370: reads 10
  b.use_magnetometer(-170.0);
  b.run_ms(2000);
  ASSERT_LT(off_deg(b.position_deg(), 10.0), 0.5) << b.position_deg();
  ASSERT_EQ(b.bearing(350.0f), Error::kOk) << b.why;
  const auto [id, value] = b.proposal();
  EXPECT_EQ(id, Id::kMagDeclinationDeg);
  EXPECT_NEAR(value, 170.0, 0.5);
  EXPECT_LT(off_deg(b.accept_and_read(), 350.0), 0.3);
}

TEST(KnownBearing, Ma3ZeroFromABearingAcrossNorth) {
  // The spid's MA3 coupled 20 deg short of north: the antenna at 10 reads
  // 350. The MA3 reads its code less the zero, so the zero becomes 340.
  Bench b("spid", 10.0, -20.0);
  b.run_ms(1000);
  const float before = b.position_deg();
  ASSERT_LT(off_deg(before, 350.0), 0.2) << before;
  ASSERT_EQ(b.bearing(10.0f), Error::kOk) << b.why;
  const auto [id, value] = b.proposal();
  EXPECT_EQ(id, Id::kAzMa3ZeroDeg);
  EXPECT_NEAR(value, 340.0, 0.2);
  EXPECT_EQ(b.settings.f(Id::kAzMa3ZeroDeg), 0.0f);
  const float after = b.accept_and_read();
  std::printf("MA3: read %.2f at bearing 10, proposed az.ma3_zero_deg %.3f, reads %.2f\n",
              static_cast<double>(before), value, static_cast<double>(after));
  EXPECT_LT(off_deg(after, 10.0), 0.15) << after;
}

TEST(KnownBearing, Ma3ZeroTurnsTheZeroInForce) {
  // A zero of 5 in force and the coupling 30 deg past north: the antenna at
  // 200 reads 225; the zero becomes 30.
  Bench b("spid", 200.0, 30.0);
  ASSERT_EQ(b.settings.set(Id::kAzMa3ZeroDeg, 5.0).error, Error::kOk);
  b.run_ms(1000);
  ASSERT_LT(off_deg(b.position_deg(), 225.0), 0.2) << b.position_deg();
  ASSERT_EQ(b.bearing(200.0f), Error::kOk) << b.why;
  EXPECT_NEAR(b.proposal().second, 30.0, 0.2);
  EXPECT_LT(off_deg(b.accept_and_read(), 200.0), 0.15);
}

TEST(KnownBearing, BadInputIsRefusedWithTheReason) {
  Bench b("spid", 100.0, 0.0);
  b.run_ms(1000);
  for (const float bad : {-0.5f, 360.5f, NAN}) {
    EXPECT_EQ(b.bearing(bad), Error::kOutOfRange) << bad;
    EXPECT_STREQ(b.why, "the bearing is a number from 0 to 360");
  }
  // The ends of 0 and 360 are the same bearing, and both taken.
  EXPECT_EQ(b.bearing(360.0f), Error::kOk) << b.why;
  EXPECT_EQ(b.bearing(0.0f), Error::kOk) << b.why;
  // Moving: the reading is not where the antenna points.
  ASSERT_EQ(b.controller->go_to(150.0f, std::nullopt), Error::kOk);
  b.run_ms(3000);
  EXPECT_EQ(b.bearing(100.0f), Error::kBusy);
  EXPECT_STREQ(b.why, "the antenna is moving");
  EXPECT_EQ(b.controller->commissioning().state(), Commissioning::State::kDone);

  // A pot has no zero to set: its calibration comes from the ends.
  Bench pot("g5500", 100.0, 0.0);
  pot.run_ms(1000);
  EXPECT_EQ(pot.bearing(100.0f), Error::kNotSupported);
  EXPECT_STREQ(pot.why, "a pot has no zero: the ends step calibrates it");
  EXPECT_EQ(pot.controller->commissioning().proposal_count(), 0u);
  // No elevation axis on a Ham IV.
  Bench ham4("ham4", 100.0, 0.0);
  EXPECT_EQ(ham4.bearing(10.0f, AxisId::kEl), Error::kNotSupported);
}

}  // namespace
}  // namespace rotord
