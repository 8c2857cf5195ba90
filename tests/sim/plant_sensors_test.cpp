// Hardware-boundary sensor fakes: pot ADC codes, MA3 PWM frames, switches.
#include "sim/sensors.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>

#include "plant_test_support.hpp"
#include "sim/adc_scale.hpp"

namespace rotord::sim {
namespace {

using test::profile_axis;

// The MA3 datasheet decoding, written out independently of the fake.
double ma3_decoded_code(const hal::PwmPeriod& p) {
  return static_cast<double>(p.high_us) * 4098.0 / static_cast<double>(p.high_us + p.low_us) - 1.0;
}

SimPot::Config g5500_az_pot(double sigma_v) {
  // 0.05 V at 0 deg .. 3.0 V at 450 deg.
  return {.v0_v = 0.05, .k_v_per_deg = 2.95 / 450.0, .sigma_v = sigma_v};
}

TEST(SimPot, NoiseFreeCodeForAKnownAngle) {
  AxisPlant plant(profile_axis("g5500", false).plant);
  SimPot pot(plant, g5500_az_pot(0.0), 1);
  plant.set_theta_deg(225.0);
  // V = 0.05 + 225 * 2.95 / 450 = 1.525 V -> 1.525 / 3.3 * 4095 = 1892.39
  EXPECT_EQ(pot.read_counts(), 1892);
  plant.set_theta_deg(0.0);
  EXPECT_EQ(pot.read_counts(), 62);  // 0.05 V
  plant.set_theta_deg(450.0);
  EXPECT_EQ(pot.read_counts(), 3723);  // 3.0 V
  EXPECT_EQ(pot.full_scale_counts(), 4095);
  EXPECT_FLOAT_EQ(pot.reference_v(), 3.3f);
}

TEST(SimPot, ClampsToTheConverterRange) {
  AxisPlant plant(profile_axis("g5500", false).plant);
  SimPot pot(plant, {.v0_v = 1.0, .k_v_per_deg = 0.01, .sigma_v = 0.0}, 1);
  plant.set_theta_deg(300.0);  // 4.0 V > vref
  EXPECT_EQ(pot.read_counts(), 4095);
  plant.set_theta_deg(-3.0);  // 0.97 V
  EXPECT_EQ(pot.read_counts(), 1204);
}

TEST(SimPot, NoiseHasTheConfiguredSpread) {
  AxisPlant plant(profile_axis("g5500", false).plant);
  SimPot pot(plant, g5500_az_pot(2.8 * kAdcLsb_v), 7);
  plant.set_theta_deg(225.0);
  constexpr int kReads = 20000;
  double sum = 0.0;
  double sum_sq = 0.0;
  for (int n = 0; n < kReads; ++n) {
    const double c = pot.read_counts();
    sum += c;
    sum_sq += c * c;
  }
  const double mean = sum / kReads;
  const double sigma = std::sqrt(sum_sq / kReads - mean * mean);
  EXPECT_NEAR(mean, 1892.386, 0.1);
  EXPECT_NEAR(sigma, 2.8, 0.15);  // plus the 1/sqrt(12) LSB of rounding
}

TEST(SimPot, LossReadsZeroForItsDuration) {
  AxisPlant plant(profile_axis("g5500", false).plant);
  SimPot pot(plant, g5500_az_pot(0.0), 1);
  plant.set_theta_deg(225.0);
  pot.update(10.0);
  pot.inject_loss(2.0);
  EXPECT_EQ(pot.read_counts(), 0);
  pot.update(11.9);
  EXPECT_EQ(pot.read_counts(), 0);
  pot.update(12.0);
  EXPECT_EQ(pot.read_counts(), 1892);
}

TEST(SimPot, NoiseBurstAndStuck) {
  AxisPlant plant(profile_axis("g5500", false).plant);
  SimPot pot(plant, g5500_az_pot(0.0), 3);
  plant.set_theta_deg(225.0);
  pot.inject_noise_burst(0.1, 1.0);  // 124 LSB
  int far = 0;
  for (int n = 0; n < 100; ++n) far += std::abs(pot.read_counts() - 1892) > 20 ? 1 : 0;
  EXPECT_GT(far, 70);
  pot.update(1.0);
  EXPECT_EQ(pot.read_counts(), 1892);

  pot.inject_stuck(kForever_s);
  plant.set_theta_deg(100.0);
  EXPECT_EQ(pot.read_counts(), 1892);
  pot.clear_faults();
  EXPECT_EQ(pot.read_counts(), 876);  // 0.05 + 100 * 2.95 / 450 = 0.7056 V -> 875.5
}

TEST(SimMa3, PwmFrameDecodesToTheCode) {
  AxisPlant plant(profile_axis("spid", false).plant);
  SimMa3 ma3(plant, 0.0, 1);
  struct Case {
    double theta_deg;
    int code;
  };
  // code = floor(mod(theta, 360) / 360 * 4096)
  for (const Case c : {Case{123.4, 1404}, Case{-10.0, 3982}, Case{450.0, 1024}, Case{0.0, 0},
                       Case{359.99, 4095}, Case{-180.0, 2048}}) {
    SCOPED_TRACE(c.theta_deg);
    plant.set_theta_deg(c.theta_deg);
    ma3.sample();
    const hal::PwmPeriod p = ma3.read();
    ASSERT_TRUE(p.valid);
    EXPECT_EQ(ma3.code(), c.code);
    EXPECT_EQ(p.high_us + p.low_us, 4098u);  // ~4.1 ms frame
    EXPECT_DOUBLE_EQ(ma3_decoded_code(p), c.code);
  }
  plant.set_theta_deg(123.4);
  ma3.sample();
  const double decoded_deg = ma3_decoded_code(ma3.read()) * 360.0 / 4096.0;
  EXPECT_NEAR(decoded_deg, 123.4, 360.0 / 4096.0);
  EXPECT_LE(decoded_deg, 123.4);  // floor: reads up to one count low
}

TEST(SimMa3, RefreshesEvery4100us) {
  AxisPlant plant(profile_axis("spid", false).plant);
  SimMa3 ma3(plant, 0.0, 1);
  plant.set_theta_deg(90.0);
  ma3.update(0.0040);
  EXPECT_EQ(ma3.code(), 0);  // latched at construction (theta was 0)
  ma3.update(0.0041);
  EXPECT_EQ(ma3.code(), 1024);
  plant.set_theta_deg(180.0);
  ma3.update(0.0081);
  EXPECT_EQ(ma3.code(), 1024);
  ma3.update(0.0082);
  EXPECT_EQ(ma3.code(), 2048);
}

TEST(SimMa3, NominalNoiseIsAFractionOfACount) {
  AxisPlant plant(profile_axis("spid", false).plant);
  SimMa3 ma3(plant, SimMa3::kNominalSigma_deg, 5);
  plant.set_theta_deg(1138.5 * 360.0 / 4096.0);  // the middle of code 1138
  int other = 0;
  for (int n = 0; n < 1000; ++n) {
    ma3.sample();
    other += ma3.code() != 1138 ? 1 : 0;
  }
  // Half a count is 0.044 deg: P(|N(0, 0.03 deg)| > 0.044 deg) = 14.3 %.
  EXPECT_GT(other, 100);
  EXPECT_LT(other, 190);
}

TEST(SimMa3, LossMakesTheInputInvalid) {
  AxisPlant plant(profile_axis("spid", false).plant);
  SimMa3 ma3(plant, 0.0, 1);
  ma3.update(1.0);
  ma3.inject_loss(0.5);
  EXPECT_FALSE(ma3.read().valid);
  ma3.update(1.5);
  EXPECT_TRUE(ma3.read().valid);
}

TEST(SimMa3, StuckRepeatsTheLastCode) {
  AxisPlant plant(profile_axis("spid", false).plant);
  SimMa3 ma3(plant, 0.0, 1);
  plant.set_theta_deg(45.0);
  ma3.sample();
  ma3.inject_stuck(kForever_s);
  plant.set_theta_deg(90.0);
  ma3.update(1.0);
  EXPECT_EQ(ma3.code(), 512);
  ma3.clear_faults();
  ma3.update(2.0);
  EXPECT_EQ(ma3.code(), 1024);
}

TEST(SimSwitch, ActiveOnItsSideOfTheThreshold) {
  AxisPlant plant(profile_axis("g5500", false).plant);
  SimSwitch cw(plant, SimSwitch::Sense::kAtOrAbove, 451.0);
  SimSwitch ccw(plant, SimSwitch::Sense::kAtOrBelow, -1.0);
  plant.set_theta_deg(450.9);
  EXPECT_FALSE(cw.active());
  plant.set_theta_deg(451.0);
  EXPECT_TRUE(cw.active());
  EXPECT_FALSE(ccw.active());
  plant.set_theta_deg(-1.0);
  EXPECT_TRUE(ccw.active());
  cw.inject_stuck(true, 2.0);
  EXPECT_TRUE(cw.active());
  cw.update(2.0);
  EXPECT_FALSE(cw.active());
}

}  // namespace
}  // namespace rotord::sim
