#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <initializer_list>
#include <vector>

#include "sensors/pot_calibration.hpp"
#include "sensors/pot_filter.hpp"
#include "sensors/pot_sensor.hpp"
#include "settings/pot_table.hpp"
#include "settings/settings.hpp"

namespace rotord {
namespace {

// An RP2040-like 12-bit ADC that plays back a script of conversions, then
// repeats the last one.
class ScriptedAdc final : public hal::AnalogIn {
 public:
  std::vector<std::uint16_t> script;
  std::size_t next = 0;
  std::uint16_t read_counts() override {
    if (script.empty()) return 0;
    const std::uint16_t v = script[next < script.size() ? next : script.size() - 1];
    ++next;
    return v;
  }
  std::uint16_t full_scale_counts() const override { return 4095; }
  float reference_v() const override { return 3.3f; }
  void hold(std::uint16_t counts) {
    script = {counts};
    next = 0;
  }
};

TEST(PotCalibration, TwoPointsAreTheClassicLine) {
  const auto cal = PotCalibration::two_point(100.0f, 0.0f, 4000.0f, 450.0f);
  EXPECT_TRUE(cal.valid());
  EXPECT_FLOAT_EQ(cal.to_deg(100.0f), 0.0f);
  EXPECT_FLOAT_EQ(cal.to_deg(4000.0f), 450.0f);
  EXPECT_FLOAT_EQ(cal.to_deg(2050.0f), 225.0f);
  EXPECT_NEAR(cal.to_deg(4026.0f), 453.0f, 1e-3f);  // extrapolated past the end
}

TEST(PotCalibration, ReversedPotWithFallingCounts) {
  const auto cal = PotCalibration::two_point(4000.0f, 0.0f, 100.0f, 450.0f);
  EXPECT_TRUE(cal.valid());
  EXPECT_FLOAT_EQ(cal.to_deg(100.0f), 450.0f);
  EXPECT_FLOAT_EQ(cal.to_deg(2050.0f), 225.0f);
}

/// A calibration table of `points` ({counts, deg}), in their order.
PotCalibration table(std::initializer_list<std::array<float, 2>> points) {
  PotCalibration cal;
  cal.count = 0;
  for (const auto& [counts, deg] : points) cal.add(counts, deg);
  return cal;
}

TEST(PotCalibration, MultiPointInterpolatesEachSegment) {
  // A pot that is steep at first, then flat: 0 deg at 200, 90 at 1200, 450 at 3600.
  const PotCalibration cal = table({{200.0f, 0.0f}, {1200.0f, 90.0f}, {3600.0f, 450.0f}});
  ASSERT_TRUE(cal.valid());
  EXPECT_FLOAT_EQ(cal.to_deg(700.0f), 45.0f);    // first segment: 0.09 deg/count
  EXPECT_FLOAT_EQ(cal.to_deg(1200.0f), 90.0f);   // at the knee
  EXPECT_FLOAT_EQ(cal.to_deg(2400.0f), 270.0f);  // second segment: 0.15 deg/count
  EXPECT_FLOAT_EQ(cal.to_deg(100.0f), -9.0f);    // below: first segment extended
  EXPECT_FLOAT_EQ(cal.to_deg(3700.0f), 465.0f);  // beyond: last segment extended
}

TEST(PotCalibration, MultiPointWithFallingCounts) {
  const PotCalibration cal = table({{3600.0f, 0.0f}, {2400.0f, 100.0f}, {1000.0f, 180.0f}});
  ASSERT_TRUE(cal.valid());
  EXPECT_FLOAT_EQ(cal.to_deg(3000.0f), 50.0f);
  EXPECT_FLOAT_EQ(cal.to_deg(1700.0f), 140.0f);
}

TEST(PotCalibration, NonMonotonicTablesAreRejected) {
  // The third point's counts turn back.
  PotCalibration cal =
      table({{200.0f, 0.0f}, {1200.0f, 90.0f}, {1100.0f, 180.0f}, {3600.0f, 450.0f}});
  EXPECT_EQ(cal.first_bad_point(), 2);
  cal.points[2] = {2000.0f, 80.0f};  // degrees turn back
  EXPECT_EQ(cal.first_bad_point(), 2);
  cal.points[2] = {2000.0f, 180.0f};
  EXPECT_TRUE(cal.valid());
  cal.points[3] = {2000.0f, 450.0f};  // repeated counts
  EXPECT_EQ(cal.first_bad_point(), 3);
  cal.count = 1;
  EXPECT_FALSE(cal.valid());
}

TEST(PotTable, SettingsBuildTheTableInOrder) {
  using settings::Id;
  settings::Settings s;
  ASSERT_EQ(s.set(Id::kAzPotCalLoCounts, 200).error, Error::kOk);
  ASSERT_EQ(s.set(Id::kAzPotCalLoDeg, 0).error, Error::kOk);
  ASSERT_EQ(s.set(Id::kAzPotCalHiCounts, 3600).error, Error::kOk);
  ASSERT_EQ(s.set(Id::kAzPotCalHiDeg, 450).error, Error::kOk);
  EXPECT_EQ(settings::pot_calibration_from(s, AxisId::kAz).count, 2);  // extra points off

  ASSERT_EQ(s.set(Id::kAzPotCalMidPoints, 2).error, Error::kOk);
  ASSERT_EQ(s.set(Id::kAzPotCalM1Counts, 1200).error, Error::kOk);
  ASSERT_EQ(s.set(Id::kAzPotCalM1Deg, 90).error, Error::kOk);
  ASSERT_EQ(s.set(Id::kAzPotCalM2Counts, 2400).error, Error::kOk);
  ASSERT_EQ(s.set(Id::kAzPotCalM2Deg, 270).error, Error::kOk);
  const PotCalibration cal = settings::pot_calibration_from(s, AxisId::kAz);
  ASSERT_EQ(cal.count, 4);
  EXPECT_FLOAT_EQ(cal.points[2].counts, 2400.0f);
  EXPECT_FLOAT_EQ(cal.points[3].deg, 450.0f);
  EXPECT_EQ(s.check_consistency().error, Error::kOk);

  ASSERT_EQ(s.set(Id::kAzPotCalM2Counts, 1000).error, Error::kOk);  // out of order
  const settings::Rejection r = s.check_consistency();
  EXPECT_EQ(r.error, Error::kOutOfRange);
  EXPECT_STREQ(r.reason,
               "az.pot_cal_m2_counts: counts and degrees must rise or fall together from "
               "az.pot_cal_lo_counts through the extra points to az.pot_cal_hi_counts");
}

TEST(PotBurst, AveragesAroundTheMedianAndDropsSpikes) {
  std::array<std::uint16_t, 8> s{2000, 2002, 1998, 4095, 2001, 1999, 0, 2000};
  const BurstResult r = reduce_burst(s.data(), 8, 4095, 8);
  ASSERT_TRUE(r.ok);
  EXPECT_FLOAT_EQ(r.counts, 2000.0f);  // the two rail spikes are not in the mean
}

TEST(PotBurst, RailsAreOutOfRange) {
  std::array<std::uint16_t, 4> open{0, 1, 0, 2};
  EXPECT_EQ(reduce_burst(open.data(), 4, 4095, 8).fault, SensorFault::kOutOfRange);
  std::array<std::uint16_t, 4> shorted{4095, 4094, 4095, 4095};
  EXPECT_EQ(reduce_burst(shorted.data(), 4, 4095, 8).fault, SensorFault::kOutOfRange);
}

TEST(PotBurst, ABurstThatDisagreesWithItselfIsImplausible) {
  // A wiper bouncing on a dirty track: no value holds a majority.
  std::array<std::uint16_t, 6> s{500, 1500, 2500, 3500, 1000, 3000};
  const BurstResult r = reduce_burst(s.data(), 6, 4095, 8);
  EXPECT_FALSE(r.ok);
  EXPECT_EQ(r.fault, SensorFault::kImplausible);
}

TEST(PotFilter, MedianOfThreeRemovesASingleBadReading) {
  PotFilter f;
  f.configure({8, true, 0});
  EXPECT_FLOAT_EQ(f.step(1000.0f, 10), 1000.0f);  // no history yet: passes through
  EXPECT_FLOAT_EQ(f.step(1001.0f, 20), 1001.0f);
  EXPECT_FLOAT_EQ(f.step(1002.0f, 30), 1001.0f);
  EXPECT_FLOAT_EQ(f.step(1900.0f, 40), 1002.0f);  // one spike: ignored
  EXPECT_FLOAT_EQ(f.step(1003.0f, 50), 1003.0f);
  EXPECT_FLOAT_EQ(f.step(1003.0f, 60), 1003.0f);
  // A real step passes after two readings.
  EXPECT_FLOAT_EQ(f.step(1500.0f, 70), 1003.0f);
  EXPECT_FLOAT_EQ(f.step(1500.0f, 80), 1500.0f);
}

TEST(PotFilter, LowPassFollowsItsTimeConstant) {
  PotFilter f;
  f.configure({8, false, 100});
  EXPECT_FLOAT_EQ(f.step(0.0f, 0), 0.0f);
  float y = 0.0f;
  for (Millis t = 10; t <= 100; t += 10) y = f.step(1000.0f, t);
  // One time constant: 1 - (100/110)^10 = 61 % (the continuous filter: 63 %).
  EXPECT_NEAR(y, 614.0f, 2.0f);
  for (Millis t = 110; t <= 1000; t += 10) y = f.step(1000.0f, t);
  EXPECT_NEAR(y, 1000.0f, 0.1f);
  // The same time constant at a different tick rate gives about the same answer.
  PotFilter g;
  g.configure({8, false, 100});
  g.step(0.0f, 0);
  float z = 0.0f;
  for (Millis t = 5; t <= 100; t += 5) z = g.step(1000.0f, t);
  EXPECT_NEAR(z, 623.0f, 2.0f);
}

TEST(PotFilter, OffPassesReadingsUnchanged) {
  PotFilter f;
  f.configure({8, false, 0});
  EXPECT_FLOAT_EQ(f.step(1000.0f, 10), 1000.0f);
  EXPECT_FLOAT_EQ(f.step(3000.0f, 20), 3000.0f);
  EXPECT_FLOAT_EQ(f.step(1000.0f, 30), 1000.0f);
}

/// A pot of 100..4000 counts for 0..450 deg on the scripted ADC, its
/// readings filtered as `filter` says.
struct Pot450 {
  ScriptedAdc adc;
  PotSensor pot{adc};
  explicit Pot450(PotFilterConfig filter) {
    pot.configure(PotCalibration::two_point(100.0f, 0.0f, 4000.0f, 450.0f), filter);
  }
};

TEST(PotSensor, OversamplesCalibratesAndFilters) {
  Pot450 p({4, true, 0});
  p.adc.script = {2050, 2049, 2051, 2050};
  PositionReading r = p.pot.read(0);
  ASSERT_TRUE(r.ok);
  EXPECT_NEAR(r.deg, 225.0f, 0.01f);
  EXPECT_EQ(p.adc.next, 4u);  // exactly pot_samples conversions per reading
  EXPECT_NEAR(r.raw, 2050.0f, 0.01f);
}

TEST(PotSensor, OpenWiperIsOutOfRangeAndRecoversWithoutDrag) {
  Pot450 p({8, true, 200});
  p.adc.hold(1000);
  for (Millis t = 0; t < 100; t += 10) p.pot.read(t);
  p.adc.hold(0);
  const PositionReading open = p.pot.read(100);
  EXPECT_FALSE(open.ok);
  EXPECT_EQ(open.fault, SensorFault::kOutOfRange);
  // Back at another place: the filters start afresh instead of sliding from 1000.
  p.adc.hold(3000);
  const PositionReading back = p.pot.read(110);
  ASSERT_TRUE(back.ok);
  EXPECT_NEAR(back.raw, 3000.0f, 0.01f);
}

TEST(PotSensor, SamplesAreClampedToTheBuffer) {
  Pot450 p({1000, false, 0});
  p.adc.hold(2050);
  EXPECT_TRUE(p.pot.read(0).ok);
  EXPECT_EQ(p.adc.next, static_cast<std::size_t>(PotFilterConfig::kMaxSamples));
}

}  // namespace
}  // namespace rotord
