#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <vector>

#include "fake_rotator.hpp"
#include "sensors/mag_sensor.hpp"
#include "sensors/magnetometer.hpp"

namespace rotord {
namespace {

// An I2C bus with one device whose registers a test fills in: reads return
// consecutive registers, writes land in them and are logged.
class FakeI2c final : public hal::I2c {
 public:
  std::uint8_t address = 0;
  std::array<std::uint8_t, 256> regs{};
  bool present = true;
  std::vector<std::pair<std::uint8_t, std::uint8_t>> writes;

  bool write(std::uint8_t addr, const std::uint8_t* data, std::size_t length) override {
    if (!present || addr != address || length < 1) return false;
    for (std::size_t n = 1; n < length; ++n) {
      regs[static_cast<std::uint8_t>(data[0] + n - 1)] = data[n];
      writes.emplace_back(static_cast<std::uint8_t>(data[0] + n - 1), data[n]);
    }
    return true;
  }
  bool write_read(std::uint8_t addr, const std::uint8_t* wdata, std::size_t wlength,
                  std::uint8_t* rdata, std::size_t rlength) override {
    if (!present || addr != address || wlength != 1) return false;
    for (std::size_t n = 0; n < rlength; ++n)
      rdata[n] = regs[static_cast<std::uint8_t>(wdata[0] + n)];
    return true;
  }

  // A QMC5883L: id 0xFF at 0x0D, X/Y/Z little-endian from 0x00.
  void qmc(std::int16_t x, std::int16_t y, std::int16_t z = 0) {
    address = Magnetometer::kQmcAddress;
    regs[0x0D] = 0xFF;
    put_le(0x00, x);
    put_le(0x02, y);
    put_le(0x04, z);
  }
  // An HMC5883L: "H43" at 0x0A, X, Z, Y big-endian from 0x03.
  void hmc(std::int16_t x, std::int16_t y, std::int16_t z = 0) {
    address = Magnetometer::kHmcAddress;
    regs[0x0A] = 'H';
    regs[0x0B] = '4';
    regs[0x0C] = '3';
    put_be(0x03, x);
    put_be(0x05, z);
    put_be(0x07, y);
  }
  void put_le(std::uint8_t reg, std::int16_t v) {
    regs[reg] = static_cast<std::uint8_t>(v & 0xFF);
    regs[reg + 1] = static_cast<std::uint8_t>((v >> 8) & 0xFF);
  }
  void put_be(std::uint8_t reg, std::int16_t v) {
    regs[reg] = static_cast<std::uint8_t>((v >> 8) & 0xFF);
    regs[reg + 1] = static_cast<std::uint8_t>(v & 0xFF);
  }
};

// Field of a magnetometer at `heading_deg` with a hard-iron offset and unequal
// axis gains, as a sensor near a steel mast reads it.
void field(FakeI2c& bus, bool hmc, float heading_deg) {
  const float rad = heading_deg * 3.14159265f / 180.0f;
  const auto x = static_cast<std::int16_t>(std::lround(300.0f + 1200.0f * std::cos(rad)));
  const auto y = static_cast<std::int16_t>(std::lround(-150.0f + 900.0f * std::sin(rad)));
  if (hmc)
    bus.hmc(x, y, 400);
  else
    bus.qmc(x, y, 400);
}

MagCalibration calibration() {
  MagCalibration c;
  c.x_min = 300.0f - 1200.0f;
  c.x_max = 300.0f + 1200.0f;
  c.y_min = -150.0f - 900.0f;
  c.y_max = -150.0f + 900.0f;
  return c;
}

TEST(Magnetometer, QmcStartsContinuousModeAndReadsLittleEndian) {
  FakeI2c bus;
  bus.qmc(1234, -567, 89);
  Magnetometer mag(bus);
  ASSERT_EQ(mag.begin(), Magnetometer::Status::kOk);
  EXPECT_EQ(bus.regs[0x0B], 0x01);         // SET/RESET period, as the datasheet asks
  EXPECT_EQ(bus.regs[0x09] & 0x03, 0x01);  // continuous mode
  MagSample s;
  ASSERT_EQ(mag.read(s), Magnetometer::Status::kOk);
  EXPECT_EQ(s.x, 1234);
  EXPECT_EQ(s.y, -567);
  EXPECT_EQ(s.z, 89);
  bus.regs[0x06] = 0x02;  // OVL
  EXPECT_EQ(mag.read(s), Magnetometer::Status::kOverflow);
}

TEST(Magnetometer, HmcReadsXZYBigEndian) {
  FakeI2c bus;
  bus.hmc(-1000, 2000, 300);
  Magnetometer mag(bus);
  mag.set_chip(MagChip::kHmc5883l);
  ASSERT_EQ(mag.begin(), Magnetometer::Status::kOk);
  EXPECT_EQ(bus.regs[0x02], 0x00);  // continuous measurement
  MagSample s;
  ASSERT_EQ(mag.read(s), Magnetometer::Status::kOk);
  EXPECT_EQ(s.x, -1000);
  EXPECT_EQ(s.y, 2000);
  EXPECT_EQ(s.z, 300);
  bus.put_be(0x07, -4096);  // the HMC's overflow code
  EXPECT_EQ(mag.read(s), Magnetometer::Status::kOverflow);
}

TEST(Magnetometer, WrongChipAndNoAnswerAreReported) {
  FakeI2c bus;
  bus.hmc(0, 0);
  Magnetometer mag(bus);  // configured for a QMC at 0x0D: nobody answers
  EXPECT_EQ(mag.begin(), Magnetometer::Status::kNoAnswer);
  bus.address = Magnetometer::kQmcAddress;  // something at 0x0D, but not a QMC
  bus.regs[0x0D] = 0x12;
  EXPECT_EQ(mag.begin(), Magnetometer::Status::kWrongChip);
  EXPECT_FALSE(mag.started());
}

TEST(Magnetometer, ReconnectsAfterTheBusFails) {
  FakeI2c bus;
  bus.qmc(100, 0);
  Magnetometer mag(bus);
  MagSample s;
  ASSERT_EQ(mag.read(s), Magnetometer::Status::kOk);  // read() starts it
  bus.present = false;
  EXPECT_EQ(mag.read(s), Magnetometer::Status::kNoAnswer);
  bus.present = true;
  bus.writes.clear();
  bus.regs[0x09] = 0;  // the chip lost power: back in standby
  ASSERT_EQ(mag.read(s), Magnetometer::Status::kOk);
  EXPECT_EQ(bus.regs[0x09] & 0x03, 0x01);  // configured again
}

TEST(MagHeading, HardIronCalibrationRecoversTheHeading) {
  const MagCalibration cal = calibration();
  FakeI2c bus;
  Magnetometer mag(bus);
  for (float h = 0.0f; h < 360.0f; h += 15.0f) {
    field(bus, false, h);
    MagSample s;
    ASSERT_EQ(mag.read(s), Magnetometer::Status::kOk);
    const auto deg = mag_heading_deg(s, cal);
    ASSERT_TRUE(deg);
    EXPECT_NEAR(std::remainder(*deg - h, 360.0f), 0.0f, 0.2f) << h;
  }
  // Without the calibration the same readings are off by up to tens of degrees.
  field(bus, false, 90.0f);
  MagSample s;
  mag.read(s);
  EXPECT_GT(std::fabs(*mag_heading_deg(s, MagCalibration{}) - 90.0f), 5.0f);
}

TEST(MagHeading, DeclinationAndReverse) {
  MagCalibration cal = calibration();
  FakeI2c bus;
  Magnetometer mag(bus);
  field(bus, false, 30.0f);
  MagSample s;
  ASSERT_EQ(mag.read(s), Magnetometer::Status::kOk);
  cal.declination_deg = -5.0f;
  EXPECT_NEAR(*mag_heading_deg(s, cal), 25.0f, 0.2f);
  cal.declination_deg = 0.0f;
  cal.reverse = true;
  EXPECT_NEAR(*mag_heading_deg(s, cal), 330.0f, 0.2f);
}

TEST(MagHeading, AFieldFarInsideTheCalibrationIsNoHeading) {
  const MagCalibration cal = calibration();
  MagSample centre{300, -150, 0};  // exactly the hard-iron offset: no direction
  EXPECT_FALSE(mag_heading_deg(centre, cal));
  MagCalibration bad = cal;
  bad.x_max = bad.x_min;
  EXPECT_FALSE(mag_heading_deg(MagSample{1000, 0, 0}, bad));
}

TEST(HeadingFilter, AveragesAcrossNorthWithoutRunaway) {
  HeadingFilter f(0.5f);
  EXPECT_FLOAT_EQ(f.step(359.0f), 359.0f);
  const float a = f.step(1.0f);
  EXPECT_NEAR(std::remainder(a, 360.0f), 0.0f, 1e-3f);  // 0, not 180
  // Jitter across north for a long time stays at north.
  float out = a;
  for (int n = 0; n < 1000; ++n) out = f.step(n % 2 == 0 ? 358.5f : 1.5f);
  EXPECT_NEAR(std::remainder(out, 360.0f), 0.0f, 1.0f);
  EXPECT_GE(out, 0.0f);
  EXPECT_LT(out, 360.0f);
}

TEST(HeadingFilter, FollowsManyTurnsWithoutDrift) {
  HeadingFilter f(0.3f);
  float out = 0.0f;
  float h = 0.0f;
  for (int n = 0; n < 5000; ++n) {  // 3 deg per sample: 41 turns
    h += 3.0f;
    out = f.step(std::fmod(h, 360.0f));
  }
  // A first-order lag of (1 - a) / a samples: 7 deg behind, and no more.
  EXPECT_NEAR(std::remainder(std::fmod(h, 360.0f) - out, 360.0f), 7.0f, 0.1f);
}

TEST(MagSensor, ReadsCalibratedFilteredHeadingAndReportsFaults) {
  FakeI2c bus;
  MagSensor sensor(bus);
  sensor.configure(MagChip::kHmc5883l, calibration(), 0);
  field(bus, true, 359.5f);
  PositionReading r = sensor.read(0);
  ASSERT_TRUE(r.ok);
  EXPECT_NEAR(r.deg, 359.5f, 0.2f);
  EXPECT_TRUE(sensor.single_turn());

  bus.present = false;
  r = sensor.read(10);
  EXPECT_FALSE(r.ok);
  EXPECT_EQ(r.fault, SensorFault::kNoSignal);

  bus.present = true;
  bus.hmc(300, -150, 0);  // the field vanished (a magnet on the sensor)
  r = sensor.read(20);
  EXPECT_FALSE(r.ok);
  EXPECT_EQ(r.fault, SensorFault::kImplausible);
}

TEST(MagSensor, LowPassCrossesNorthTheShortWay) {
  FakeI2c bus;
  MagSensor sensor(bus);
  sensor.configure(MagChip::kQmc5883l, calibration(), 100);
  field(bus, false, 355.0f);
  ASSERT_TRUE(sensor.read(0).ok);
  field(bus, false, 5.0f);
  float deg = 0.0f;
  for (Millis t = 10; t <= 2000; t += 10) deg = sensor.read(t).deg;
  EXPECT_NEAR(deg, 5.0f, 0.3f);
  // On the way it never passed through the south.
  sensor.configure(MagChip::kQmc5883l, calibration(), 100);
  field(bus, false, 355.0f);
  for (Millis t = 2010; t <= 3000; t += 10) sensor.read(t);
  field(bus, false, 5.0f);
  for (Millis t = 3010; t <= 3300; t += 10) {
    const float d = sensor.read(t).deg;
    EXPECT_TRUE(d >= 354.0f || d <= 6.0f) << d;
  }
}

TEST(MagSensor, ANewCalibrationTakesEffectAtOnceInsteadOfSlewing) {
  // The spin calibration corrects the heading by tens of degrees. Through a
  // 100 ms low-pass that would look like the antenna turning for half a
  // second after the save; the first reading must already be the new heading.
  FakeI2c bus;
  MagSensor sensor(bus);
  MagCalibration off = calibration();
  off.x_min -= 400.0f;  // the centre 200 counts left of the truth
  sensor.configure(MagChip::kQmc5883l, off, 100);
  field(bus, false, 90.0f);
  for (Millis t = 0; t <= 2000; t += 10) sensor.read(t);
  const float wrong_deg = sensor.read(2010).deg;
  ASSERT_GT(std::fabs(wrong_deg - 90.0f), 5.0f) << "the bad calibration must show";
  sensor.configure(MagChip::kQmc5883l, calibration(), 100);
  EXPECT_NEAR(sensor.read(2020).deg, 90.0f, 0.3f);
  // Configuring again with the same calibration keeps the smoothing going.
  field(bus, false, 100.0f);
  sensor.configure(MagChip::kQmc5883l, calibration(), 100);
  const float smoothed_deg = sensor.read(2030).deg;
  EXPECT_GT(smoothed_deg, 90.0f);
  EXPECT_LT(smoothed_deg, 95.0f);
}

TEST(MagAxis, TheAxisUnwrapsTheHeadingThroughNorth) {
  // A 0..450 rotator read by a QMC5883L: from 350 deg CW through north to
  // 370 (an unwrapped 10 deg), with the position following the turn.
  using settings::Id;
  testing::FakeRotator r(false);
  FakeI2c bus;
  field(bus, false, 350.0f);
  const MagCalibration cal = calibration();
  r.settings.set(Id::kMagXMin, cal.x_min);
  r.settings.set(Id::kMagXMax, cal.x_max);
  r.settings.set(Id::kMagYMin, cal.y_min);
  r.settings.set(Id::kMagYMax, cal.y_max);
  r.settings.set(Id::kMagLowpassMs, 0);
  ASSERT_EQ(r.settings.set_from_text(Id::kAzSensor, "mag").error, Error::kOk);
  ASSERT_EQ(r.settings.check_consistency().error, Error::kOk);
  AxisIo io = r.az.io();
  io.i2c = &bus;
  r.controller = std::make_unique<Controller>(r.settings, io, r.el.io());
  r.controller->begin(0);
  r.run_ms(50);
  ASSERT_TRUE(r.controller->status().az.position_valid);
  EXPECT_NEAR(r.controller->status().az.position_deg, 350.0f, 0.3f);
  for (float h = 350.0f; h <= 370.0f; h += 0.5f) {
    field(bus, false, std::fmod(h, 360.0f));
    r.run_ms(20);
  }
  EXPECT_NEAR(r.controller->status().az.position_deg, 370.0f, 0.3f);
  EXPECT_EQ(r.controller->status().az.fault, AxisFault::kNone);
}

TEST(MagAxis, StatusCarriesTheRawFieldForTheCalibrationAndANewOneTakesEffect) {
  using settings::Id;
  testing::FakeRotator r(false);
  FakeI2c bus;
  bus.qmc(700, -400, 55);
  ASSERT_EQ(r.settings.set_from_text(Id::kAzSensor, "mag").error, Error::kOk);
  r.settings.set(Id::kMagLowpassMs, 0);
  AxisIo io = r.az.io();
  io.i2c = &bus;
  r.controller = std::make_unique<Controller>(r.settings, io, r.el.io());
  r.controller->begin(0);
  r.run_ms(50);
  AxisStatus a = r.controller->status().az;
  ASSERT_TRUE(a.mag_valid);
  EXPECT_EQ(a.mag_x, 700);
  EXPECT_EQ(a.mag_y, -400);
  EXPECT_EQ(a.mag_z, 55);
  EXPECT_EQ(a.raw_full_scale, 0.0f);  // raw is a heading, not a converter code
  // The web page's spin calibration saves the extremes it saw; the heading
  // moves in one step and that is no implausible jump.
  const float before = a.position_deg;
  r.settings.set(Id::kMagXMax, 2700);  // x now reads as -1 radius, y as 0: about south
  r.settings.set(Id::kMagXMin, 700);
  r.settings.set(Id::kMagYMin, -1400);
  r.settings.set(Id::kMagYMax, 600);
  r.run_ms(100);
  a = r.controller->status().az;
  EXPECT_EQ(a.fault, AxisFault::kNone);
  EXPECT_TRUE(a.position_valid);
  EXPECT_GT(std::fabs(a.position_deg - before), 90.0f);
  bus.present = false;  // a silent chip has no raw sample to show
  r.run_ms(20);
  EXPECT_FALSE(r.controller->status().az.mag_valid);
}

}  // namespace
}  // namespace rotord
