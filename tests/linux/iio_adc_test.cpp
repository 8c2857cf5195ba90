#include "iio_adc.hpp"

#include <gtest/gtest.h>

#include "fake_sysfs.hpp"

namespace rotord::linux_port {
namespace {

using testing::FakeSysfs;

TEST(IioAdcTest, ReadsAnAds1115ChannelWithItsScale) {
  FakeSysfs sys;
  sys.add_ads1115(0, 1, 12345);
  IioAdc adc;
  std::string error;
  ASSERT_TRUE(adc.open(sys.root(), 0, 1, 0, error)) << error;
  EXPECT_EQ(adc.raw_path(), sys.root() + "/iio:device0/in_voltage1_raw");
  EXPECT_EQ(adc.read_counts(), 12345);  // open() takes the first conversion
  EXPECT_EQ(adc.full_scale_counts(), 32767);
  EXPECT_NEAR(adc.reference_v(), 0.125 * 32767 / 1000.0, 1e-3);  // the PGA's 4.096 V range
}

TEST(IioAdcTest, EachSampleReadsTheFileAgainAndTheTickSeesOneValue) {
  FakeSysfs sys;
  sys.add_ads1115(2, 0, 100);
  IioAdc adc;
  std::string error;
  ASSERT_TRUE(adc.open(sys.root(), 2, 0, 0, error)) << error;
  sys.write("iio:device2/in_voltage0_raw", "20000\n");
  EXPECT_EQ(adc.read_counts(), 100);  // not sampled yet: the previous conversion
  ASSERT_TRUE(adc.sample());
  EXPECT_EQ(adc.read_counts(), 20000);
  EXPECT_EQ(adc.read_counts(), 20000);
}

TEST(IioAdcTest, NegativeSingleEndedCodesClampToZero) {
  FakeSysfs sys;
  sys.add_ads1115(0, 0, -3);
  IioAdc adc;
  std::string error;
  ASSERT_TRUE(adc.open(sys.root(), 0, 0, 0, error)) << error;
  EXPECT_EQ(adc.read_counts(), 0);
}

TEST(IioAdcTest, Mcp3008IsKnownByNameWithASharedScale) {
  FakeSysfs sys;
  sys.write("iio:device1/name", "mcp3008\n");
  sys.write("iio:device1/in_voltage3_raw", "1000\n");
  sys.write("iio:device1/in_voltage_scale", "3.222656250\n");
  IioAdc adc;
  std::string error;
  ASSERT_TRUE(adc.open(sys.root(), 1, 3, 0, error)) << error;
  EXPECT_EQ(adc.full_scale_counts(), 1023);
  EXPECT_NEAR(adc.reference_v(), 3.2967f, 1e-3f);
  EXPECT_EQ(adc.read_counts(), 1000);
}

TEST(IioAdcTest, UnknownChipNeedsTheFullScaleSetting) {
  FakeSysfs sys;
  sys.write("iio:device0/name", "mystery-adc\n");
  sys.write("iio:device0/in_voltage0_raw", "7\n");
  IioAdc adc;
  std::string error;
  EXPECT_FALSE(adc.open(sys.root(), 0, 0, 0, error));
  EXPECT_NE(error.find("iio.full_scale_counts"), std::string::npos) << error;
  IioAdc with_setting;
  ASSERT_TRUE(with_setting.open(sys.root(), 0, 0, 4095, error)) << error;
  EXPECT_EQ(with_setting.full_scale_counts(), 4095);
  EXPECT_EQ(with_setting.read_counts(), 7);
}

TEST(IioAdcTest, MissingChannelNamesTheFile) {
  FakeSysfs sys;
  sys.add_ads1115(0, 0, 5);
  IioAdc adc;
  std::string error;
  EXPECT_FALSE(adc.open(sys.root(), 0, 2, 0, error));
  EXPECT_NE(error.find(sys.root() + "/iio:device0/in_voltage2_raw"), std::string::npos) << error;
  EXPECT_FALSE(adc.open(sys.root(), 5, 0, 0, error));
  EXPECT_NE(error.find("iio:device5/in_voltage0_raw"), std::string::npos) << error;
}

TEST(IioAdcTest, ABadReadGivesZeroCountsAndAnError) {
  FakeSysfs sys;
  sys.add_ads1115(0, 0, 5000);
  IioAdc adc;
  std::string error;
  ASSERT_TRUE(adc.open(sys.root(), 0, 0, 0, error)) << error;
  sys.write("iio:device0/in_voltage0_raw", "garbage\n");
  EXPECT_FALSE(adc.sample());
  EXPECT_EQ(adc.read_counts(), 0);  // the pot sensor reports a rail fault
  EXPECT_NE(adc.last_error().find("in_voltage0_raw"), std::string::npos);
  sys.write("iio:device0/in_voltage0_raw", "5001\n");
  EXPECT_TRUE(adc.sample());
  EXPECT_EQ(adc.read_counts(), 5001);
  EXPECT_TRUE(adc.last_error().empty());
}

TEST(IioAdcTest, FullScaleFromScanElementTypes) {
  EXPECT_EQ(iio_full_scale_from_type("le:s16/16>>0"), 32767);
  EXPECT_EQ(iio_full_scale_from_type("be:s12/16>>4"), 2047);
  EXPECT_EQ(iio_full_scale_from_type("be:u10/16>>0"), 1023);
  EXPECT_EQ(iio_full_scale_from_type("nonsense"), 0);
  EXPECT_EQ(iio_full_scale_for("ads1015"), 0);  // ambiguous: 12 or 16 bits
}

}  // namespace
}  // namespace rotord::linux_port
