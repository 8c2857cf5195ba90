#include "gpiod_io.hpp"

#include <gtest/gtest.h>

#include <fstream>

#include "fake_gpio_chip.hpp"
#include "fake_i2c_kernel.hpp"
#include "fake_sysfs.hpp"
#include "rotator/controller.hpp"
#include "safe_stop.hpp"
#include "sim/profiles.hpp"
#include "sim/sensors.hpp"

namespace rotord::linux_port {
namespace {

using settings::Id;
using testing::FakeBoard;
using testing::FakeGpioChip;
using testing::FakeI2cKernel;
using testing::FakeSysfs;

// The defaults of the gpiod.* rows (a relay G-5500-style azimuth).
constexpr int kAzCw = 17, kAzCcw = 27, kAzSpeed = 22, kAzBrake = 23;
constexpr int kAzL1 = 5, kAzL2 = 6, kAzT1 = 16, kAzT2 = 26, kAzMa3 = 4;

class GpiodIoTest : public ::testing::Test {
 protected:
  GpiodIoTest() {
    // A pot on an ADS1115 channel 0: 1000 counts = 0 deg, 31000 = 450 deg.
    set(Id::kAzPotCalLoCounts, 1000);
    set(Id::kAzPotCalHiCounts, 31000);
    set_az_deg(200.0);
  }
  void set(Id id, double value) {
    ASSERT_EQ(s.set(id, value).error, Error::kOk) << settings::def(id).key;
  }
  void set_az_deg(double deg) { sys.add_ads1115(0, 0, static_cast<int>(1000 + deg * 30000 / 450)); }

  std::unique_ptr<GpiodRotator> open() {
    return GpiodRotator::open(
        s, std::make_unique<FakeGpioChip>(board),
        GpiodHost{sys.root(), pwm.root(), dev.root(), &kernel, [] { return std::uint64_t{0}; }},
        error);
  }
  /// The controller's ticks as the daemon runs them: sample, then tick.
  void run_ms(Controller& c, GpiodRotator& hw, Millis ms) {
    for (Millis end = now + ms; now < end;) {
      now += 10;
      hw.sample();
      c.tick(now);
    }
  }

  settings::Settings s;
  FakeSysfs sys;  ///< /sys/bus/iio/devices
  FakeSysfs pwm;  ///< /sys/class/pwm
  FakeSysfs dev;  ///< /dev, for i2c-N
  FakeI2cKernel kernel;
  std::shared_ptr<FakeBoard> board = std::make_shared<FakeBoard>();
  std::string error;
  Millis now = 0;
};

TEST_F(GpiodIoTest, RequestsOnlyTheLinesTheSettingsUseOutputsInactive) {
  auto hw = open();
  ASSERT_TRUE(hw) << error;
  for (int out : {kAzCw, kAzCcw}) {
    ASSERT_TRUE(board->lines[out].requested) << out;
    EXPECT_EQ(board->lines[out].request.mode, LineMode::kOutput);
    EXPECT_FALSE(board->lines[out].request.active_low);  // gpiod.outputs_active_low = false
    EXPECT_FALSE(board->output_active(out));
  }
  for (int in : {kAzL1, kAzL2, kAzT1, kAzT2}) {
    ASSERT_TRUE(board->lines[in].requested) << in;
    EXPECT_EQ(board->lines[in].request.mode, LineMode::kInput);
    EXPECT_TRUE(board->lines[in].request.active_low);  // switch to ground
    EXPECT_EQ(board->lines[in].request.bias, LineBias::kPullUp);
  }
  // A plain relay drive, no brake, a pot, az only: nothing else is touched.
  for (int unused : {kAzSpeed, kAzBrake, kAzMa3, 24, 25, 20, 21})
    EXPECT_FALSE(board->lines[unused].requested) << unused;
  EXPECT_NE(hw->summary().find("iio:device0/in_voltage0_raw"), std::string::npos) << hw->summary();
}

TEST_F(GpiodIoTest, RelaysFollowTheAxisAndALimitStopsThatDirectionOnly) {
  auto hw = open();
  ASSERT_TRUE(hw) << error;
  Controller c(s, hw->io(AxisId::kAz), hw->io(AxisId::kEl));
  c.begin(now);
  run_ms(c, *hw, 100);
  EXPECT_NEAR(c.status().az.position_deg, 200.0f, 0.5f);
  ASSERT_EQ(c.move(AxisId::kAz, Direction::kCw), Error::kOk);
  run_ms(c, *hw, 500);
  EXPECT_TRUE(board->output_active(kAzCw));
  EXPECT_FALSE(board->output_active(kAzCcw));
  for (double deg = 200.2; deg < 201.1; deg += 0.2) {  // the rotator turns, 20 deg/s
    set_az_deg(deg);
    run_ms(c, *hw, 10);
  }
  run_ms(c, *hw, 50);

  board->lines[kAzL2].active = true;  // CW end switch closes
  run_ms(c, *hw, 10);
  EXPECT_FALSE(board->output_active(kAzCw));  // cut on the first tick
  EXPECT_TRUE(c.status().az.limit_cw);
  EXPECT_EQ(c.move(AxisId::kAz, Direction::kCw), Error::kLimit);
  ASSERT_EQ(c.move(AxisId::kAz, Direction::kCcw), Error::kOk);
  run_ms(c, *hw, 2000);
  EXPECT_TRUE(board->output_active(kAzCcw));
  EXPECT_FALSE(board->output_active(kAzCw));
}

TEST_F(GpiodIoTest, OutputsAreOffAtShutdownAndAfterRelease) {
  set(Id::kAzDrive, 1);  // relay_two_speed: the speed line too
  set(Id::kAzHasBrake, 1);
  {
    auto hw = open();
    ASSERT_TRUE(hw) << error;
    ASSERT_TRUE(board->lines[kAzSpeed].requested);
    ASSERT_TRUE(board->lines[kAzBrake].requested);
    Controller c(s, hw->io(AxisId::kAz), hw->io(AxisId::kEl));
    c.begin(now);
    ASSERT_EQ(c.move(AxisId::kAz, Direction::kCcw), Error::kOk);
    run_ms(c, *hw, 3000);
    ASSERT_TRUE(board->output_active(kAzCcw));
    ASSERT_TRUE(board->output_active(kAzBrake));  // released
    c.shutdown();                                 // what SIGINT / SIGTERM do
    for (int out : {kAzCw, kAzCcw, kAzSpeed, kAzBrake})
      EXPECT_FALSE(board->output_active(out)) << out;
    board->lines[kAzCcw].active = true;  // as if a write had been lost
  }
  for (int out : {kAzCw, kAzCcw, kAzSpeed, kAzBrake}) {
    EXPECT_FALSE(board->output_active(out)) << out;  // written off once more before release
    EXPECT_TRUE(board->lines[out].released) << out;
  }
  EXPECT_TRUE(board->closed);
}

TEST_F(GpiodIoTest, TheSignalPathStopsTheMotorsAndDrivesEveryLineOff) {
  // What rotord does on SIGTERM, SIGHUP, SIGQUIT, ... (safe_stop.hpp): the
  // controller's STOP, all outputs off through the drive sink, then every
  // line written inactive once more; the exit log reads the lines' state.
  set(Id::kAzDrive, 1);  // relay_two_speed: the speed line too
  set(Id::kAzHasBrake, 1);
  auto hw = open();
  ASSERT_TRUE(hw) << error;
  Controller c(s, hw->io(AxisId::kAz), hw->io(AxisId::kEl));
  c.begin(now);
  ASSERT_EQ(c.go_to(400.0f, std::nullopt), Error::kOk);
  run_ms(c, *hw, 3000);
  ASSERT_TRUE(board->output_active(kAzCw));
  ASSERT_TRUE(board->output_active(kAzBrake));
  ASSERT_NE(describe_outputs(hw->written(AxisId::kAz), nullptr), "az off");

  stop_motors(&c, hw.get());
  for (int out : {kAzCw, kAzCcw, kAzSpeed, kAzBrake})
    EXPECT_FALSE(board->output_active(out)) << out;
  EXPECT_EQ(c.status().mode, Mode::kIdle);
  EXPECT_FALSE(c.status().az.has_target);  // stopped, not paused: nothing resumes
  EXPECT_EQ(describe_outputs(hw->written(AxisId::kAz), nullptr), "az off");
  run_ms(c, *hw, 1000);
  EXPECT_FALSE(board->output_active(kAzCw));
}

TEST_F(GpiodIoTest, TheExitLogNamesEveryOutputStillOn) {
  auto hw = open();
  ASSERT_TRUE(hw) << error;
  Controller c(s, hw->io(AxisId::kAz), hw->io(AxisId::kEl));
  c.begin(now);
  ASSERT_EQ(c.move(AxisId::kAz, Direction::kCw), Error::kOk);
  run_ms(c, *hw, 500);
  ASSERT_TRUE(board->output_active(kAzCw));
  EXPECT_EQ(describe_outputs(hw->written(AxisId::kAz), nullptr), "az relay_cw=1");
}

TEST_F(GpiodIoTest, TheEmergencyStopLineCutsTheRelaysAndLatches) {
  constexpr int kEstop = 12;
  set(Id::kGpiodEstop, kEstop);  // normally closed (the default): closed = run
  auto hw = open();
  ASSERT_TRUE(hw) << error;
  ASSERT_TRUE(board->lines[kEstop].requested);
  board->lines[kEstop].active = true;
  EXPECT_EQ(board->lines[kEstop].request.mode, LineMode::kInput);
  EXPECT_TRUE(board->lines[kEstop].request.active_low);  // a contact to ground
  ASSERT_NE(hw->estop(), nullptr);
  Controller c(s, hw->io(AxisId::kAz), hw->io(AxisId::kEl));
  c.attach_estop(hw->estop());
  c.begin(now);
  ASSERT_EQ(c.move(AxisId::kAz, Direction::kCw), Error::kOk);
  run_ms(c, *hw, 500);
  ASSERT_TRUE(board->output_active(kAzCw));

  board->lines[kEstop].active = false;  // pressed, or the wire broke
  run_ms(c, *hw, 10);
  EXPECT_FALSE(board->output_active(kAzCw));  // on the first tick
  EXPECT_EQ(c.status().az.fault, AxisFault::kEstop);
  EXPECT_EQ(c.reset(), Error::kFaulted);

  board->lines[kEstop].active = true;  // released: still latched until RESET
  run_ms(c, *hw, 10);
  EXPECT_EQ(c.move(AxisId::kAz, Direction::kCw), Error::kFaulted);
  EXPECT_EQ(c.reset(), Error::kOk);
  EXPECT_EQ(c.move(AxisId::kAz, Direction::kCw), Error::kOk);
}

TEST_F(GpiodIoTest, ActiveLowRelayBoardsAreRequestedInverted) {
  set(Id::kGpiodOutputsActiveLow, 1);
  set(Id::kGpiodInputBias, 3);  // as_is
  auto hw = open();
  ASSERT_TRUE(hw) << error;
  EXPECT_TRUE(board->lines[kAzCw].request.active_low);
  EXPECT_EQ(board->lines[kAzL1].request.bias, LineBias::kAsIs);
}

TEST_F(GpiodIoTest, ABusyLineRefusesToStartNamingKeyAndLine) {
  board->busy.insert(kAzCcw);
  EXPECT_FALSE(open());
  EXPECT_NE(error.find("gpiod.az_ccw = 27"), std::string::npos) << error;
  EXPECT_NE(error.find("busy"), std::string::npos) << error;
  EXPECT_TRUE(board->lines[kAzCw].released);  // what was requested is let go
  EXPECT_FALSE(board->output_active(kAzCw));
}

TEST_F(GpiodIoTest, AMissingLineRefusesToStart) {
  set(Id::kGpiodAzL1, 60);
  board->line_count = 54;
  EXPECT_FALSE(open());
  EXPECT_NE(error.find("gpiod.az_l1 = 60"), std::string::npos) << error;
}

TEST_F(GpiodIoTest, AnUnwiredRequiredLineIsNamed) {
  set(Id::kGpiodAzCw, -1);
  EXPECT_FALSE(open());
  EXPECT_EQ(error, "az.drive = relay needs gpiod.az_cw");
  set(Id::kGpiodAzCw, 17);
  set(Id::kAzHasBrake, 1);
  set(Id::kGpiodAzBrake, -1);
  EXPECT_FALSE(open());
  EXPECT_EQ(error, "az.has_brake needs gpiod.az_brake");
}

TEST_F(GpiodIoTest, HBridgeDrivesNeedKernelPwmNeverSoftwarePwm) {
  set(Id::kAzDrive, 3);
  EXPECT_FALSE(open());
  EXPECT_NE(error.find("az.drive = hbridge needs pwm.chip"), std::string::npos) << error;
  EXPECT_NE(error.find("software PWM"), std::string::npos) << error;
  EXPECT_TRUE(board->lines.empty());  // refused before any line was requested
  set(Id::kPwmChip, 0);
  EXPECT_FALSE(open());  // no such chip in the (empty) PWM tree
  EXPECT_NE(error.find("pwm.az_cw = 0: no PWM chip " + pwm.root() + "/pwmchip0"), std::string::npos)
      << error;
}

TEST_F(GpiodIoTest, HBridgeHalvesFollowTheAxisOnKernelPwmChannels) {
  set(Id::kAzDrive, 3);
  set(Id::kPwmChip, 0);
  set(Id::kPwmHz, 20000);
  for (const char* ch : {"pwm0", "pwm1"}) {  // as after dtoverlay=pwm-2chan and export
    for (const char* f : {"period", "duty_cycle", "enable"})
      pwm.write(std::string("pwmchip0/") + ch + "/" + f, "0\n");
  }
  // A regular file keeps the tail of a longer old value after a shorter
  // write at offset 0 ("0" over "50000" reads "00000"); sysfs takes just the
  // bytes written. Reading the number covers both.
  const auto file = [&](const std::string& f) {
    std::ifstream in(pwm.root() + "/pwmchip0/" + f);
    long long v = -1;
    in >> v;
    return v;
  };
  {
    auto hw = open();
    ASSERT_TRUE(hw) << error;
    EXPECT_EQ(file("pwm0/period"), 50000);  // 20 kHz
    EXPECT_EQ(file("pwm0/enable"), 1);
    EXPECT_EQ(file("pwm0/duty_cycle"), 0);
    EXPECT_FALSE(board->lines[kAzCw].requested);  // no relay lines for an H-bridge
    Controller c(s, hw->io(AxisId::kAz), hw->io(AxisId::kEl));
    c.begin(now);
    ASSERT_EQ(c.move(AxisId::kAz, Direction::kCw, 100), Error::kOk);
    run_ms(c, *hw, 2000);
    EXPECT_EQ(file("pwm0/duty_cycle"), 50000);  // pwm_fast_duty 1.0
    EXPECT_EQ(file("pwm1/duty_cycle"), 0);
    c.shutdown();
    EXPECT_EQ(file("pwm0/duty_cycle"), 0);
  }
  EXPECT_EQ(file("pwm0/enable"), 0);  // disabled when rotord lets go
  EXPECT_EQ(file("pwm1/enable"), 0);
}

/// az.sensor = mag on /dev/i2c-1 (the default i2c.bus), calibrated to the
/// simulated QMC5883L's field, which turns with `plant`.
class GpiodMagTest : public GpiodIoTest {
 protected:
  GpiodMagTest() {
    set(Id::kAzSensor, 2);
    set(Id::kMagXMin, sim::SimMag::kOffsetX - sim::SimMag::kGainX);
    set(Id::kMagXMax, sim::SimMag::kOffsetX + sim::SimMag::kGainX);
    set(Id::kMagYMin, sim::SimMag::kOffsetY - sim::SimMag::kGainY);
    set(Id::kMagYMax, sim::SimMag::kOffsetY + sim::SimMag::kGainY);
    set(Id::kMagLowpassMs, 0);
    dev.write("i2c-1", "");
    plant.set_theta_deg(123.0);
    kernel.device = &mag;
  }
  sim::AxisPlant plant{sim::find_profile("g5500")->az.plant};
  sim::SimMag mag{plant, 0.0, 1};
};

TEST_F(GpiodMagTest, TheMagnetometerOnI2cGivesTheAzimuth) {
  auto hw = open();
  ASSERT_TRUE(hw) << error;
  EXPECT_NE(hw->summary().find("magnetometer QMC5883L at 0x0D on " + dev.root() + "/i2c-1"),
            std::string::npos)
      << hw->summary();
  Controller c(s, hw->io(AxisId::kAz), hw->io(AxisId::kEl));
  c.begin(now);
  run_ms(c, *hw, 100);
  EXPECT_NEAR(c.status().az.position_deg, 123.0f, 0.2f);
  for (double deg = 123.0; deg <= 200.0; deg += 0.1) {  // 10 deg/s by hand
    plant.set_theta_deg(deg);
    run_ms(c, *hw, 10);
  }
  run_ms(c, *hw, 100);
  EXPECT_NEAR(c.status().az.position_deg, 200.0f, 0.2f);
  EXPECT_EQ(c.status().az.fault, AxisFault::kNone);
  // Every register read is one transaction: the register number written,
  // then the data read after a repeated start, to the same address.
  ASSERT_FALSE(kernel.transactions.empty());
  int reads = 0;
  for (const auto& t : kernel.transactions) {
    for (const auto& m : t) EXPECT_EQ(m.address, sim::SimMag::kAddress);
    if (t.size() == 2) {
      ++reads;
      EXPECT_FALSE(t[0].read);
      EXPECT_EQ(t[0].length, 1u);
      EXPECT_TRUE(t[1].read);
    } else {
      ASSERT_EQ(t.size(), 1u);  // a control register write
      EXPECT_FALSE(t[0].read);
      EXPECT_EQ(t[0].length, 2u);
    }
  }
  EXPECT_GE(reads, 20);  // one per tick
}

TEST_F(GpiodMagTest, AChipThatDoesNotAnswerIsRefusedWithItsAddressAndBus) {
  kernel.device = nullptr;
  EXPECT_FALSE(open());
  EXPECT_NE(error.find("mag.chip = qmc5883l: nothing answers at 0x0D on " + dev.root() + "/i2c-1"),
            std::string::npos)
      << error;
  EXPECT_NE(error.find("i2cdetect -y 1"), std::string::npos) << error;
  // The simulated chip is a QMC5883L; an HMC5883L is looked for at 0x1E.
  kernel.device = &mag;
  set(Id::kMagChip, 1);
  EXPECT_FALSE(open());
  EXPECT_NE(error.find("nothing answers at 0x1E"), std::string::npos) << error;
}

TEST_F(GpiodMagTest, AnotherChipAtTheAddressIsRefused) {
  struct Zeros final : hal::I2c {  // answers, but its id register reads 0
    bool write(std::uint8_t, const std::uint8_t*, std::size_t) override { return true; }
    bool write_read(std::uint8_t, const std::uint8_t*, std::size_t, std::uint8_t* r,
                    std::size_t n) override {
      std::fill(r, r + n, std::uint8_t{0});
      return true;
    }
  } zeros;
  kernel.device = &zeros;
  EXPECT_FALSE(open());
  EXPECT_NE(error.find("does not identify as one (is mag.chip right?)"), std::string::npos)
      << error;
}

TEST_F(GpiodMagTest, AMissingOrWrongAdapterNamesTheSettingAndTheFile) {
  set(Id::kI2cBus, 3);
  EXPECT_FALSE(open());
  EXPECT_NE(error.find("i2c.bus = 3: cannot open " + dev.root() + "/i2c-3: No such file"),
            std::string::npos)
      << error;
  EXPECT_NE(error.find("dtparam=i2c_arm=on"), std::string::npos) << error;

  kernel.funcs = I2C_FUNC_SMBUS_EMUL;
  set(Id::kI2cBus, 1);
  EXPECT_FALSE(open());
  EXPECT_NE(error.find("SMBus-only"), std::string::npos) << error;

  set(Id::kI2cBus, -1);
  EXPECT_FALSE(open());
  EXPECT_EQ(error, "az.sensor = mag needs i2c.bus");
}

TEST_F(GpiodMagTest, TheRealKernelRefusesAFileThatIsNoAdapter) {
  // The real I2C_FUNCS ioctl on a plain file: what a wrong path gives.
  const auto hw = GpiodRotator::open(
      s, std::make_unique<FakeGpioChip>(board),
      GpiodHost{sys.root(), pwm.root(), dev.root(), &linux_port::linux_i2c_kernel(),
                [] { return std::uint64_t{0}; }},
      error);
  EXPECT_FALSE(hw);
  EXPECT_NE(error.find(dev.root() + "/i2c-1 is not an I2C adapter"), std::string::npos) << error;
}

TEST_F(GpiodIoTest, AMissingAdcNamesTheSettingAndTheFile) {
  set(Id::kIioAzDevice, 3);
  EXPECT_FALSE(open());
  EXPECT_NE(error.find("iio.az_device"), std::string::npos) << error;
  EXPECT_NE(error.find(sys.root() + "/iio:device3/in_voltage0_raw"), std::string::npos) << error;
  set(Id::kIioAzDevice, -1);
  EXPECT_FALSE(open());
  EXPECT_EQ(error, "az.sensor = pot needs iio.az_device");
}

TEST_F(GpiodIoTest, Ma3AxisRequestsABothEdgesLineWithoutInversion) {
  set(Id::kAzSensor, 1);
  auto hw = open();
  ASSERT_TRUE(hw) << error;
  ASSERT_TRUE(board->lines[kAzMa3].requested);
  EXPECT_EQ(board->lines[kAzMa3].request.mode, LineMode::kBothEdges);
  EXPECT_FALSE(board->lines[kAzMa3].request.active_low);
  EXPECT_NE(hw->io(AxisId::kAz).ma3, nullptr);
  EXPECT_EQ(hw->io(AxisId::kAz).pot, nullptr);
}

TEST_F(GpiodIoTest, AnAnemometerOnItsLineStowsTheAntenna) {
  // A cup anemometer's reed contact to ground on line 13 (docs/care.md).
  constexpr int kWind = 13;
  set(Id::kWindSource, 2);
  set(Id::kGpiodWind, kWind);
  set(Id::kWindStowAzDeg, 90);
  auto hw = open();
  ASSERT_TRUE(hw) << error;
  ASSERT_TRUE(board->lines[kWind].requested);
  EXPECT_EQ(board->lines[kWind].request.mode, LineMode::kBothEdges);
  EXPECT_TRUE(board->lines[kWind].request.active_low);  // a contact to ground
  EXPECT_EQ(board->lines[kWind].request.bias, LineBias::kPullUp);
  EXPECT_NE(hw->summary().find("anemometer on line 13"), std::string::npos) << hw->summary();
  ASSERT_NE(hw->wind_pulses(), nullptr);
  Controller c(s, hw->io(AxisId::kAz), hw->io(AxisId::kEl));
  c.attach_wind_pulses(hw->wind_pulses());
  c.begin(now);
  // 40 pulses a second (26.7 m/s at 1.5 pulses per m/s) for 13 s.
  std::uint64_t t_ns = 0;
  for (int n = 0; n < 1300; ++n) {
    if (n % 10 == 0)
      for (int k = 0; k < 4; ++k) {
        board->lines[kWind].edges.push_back({true, t_ns});
        board->lines[kWind].edges.push_back({false, t_ns + 1000000});
        t_ns += 25000000;
      }
    run_ms(c, *hw, 10);
  }
  EXPECT_NEAR(c.wind().speed_mps(), 26.7f, 0.7f);
  EXPECT_EQ(c.wind().state(), care::WindState::kStowed);
  // Turning from 200 to the stow heading, 90: counter-clockwise.
  EXPECT_TRUE(board->output_active(kAzCcw));
  EXPECT_EQ(c.go_to(250.0f, std::nullopt), Error::kStowed);
}

TEST_F(GpiodIoTest, ElevationLinesAreRequestedWhenEnabled) {
  set(Id::kElEnabled, 1);
  sys.add_ads1115(0, 1, 1000);  // iio.el_channel = 1
  auto hw = open();
  ASSERT_TRUE(hw) << error;
  for (int line : {24, 25, 20, 21}) EXPECT_TRUE(board->lines[line].requested) << line;
  EXPECT_NE(hw->io(AxisId::kEl).drive, nullptr);
  EXPECT_NE(hw->io(AxisId::kEl).pot, nullptr);
}

TEST_F(GpiodIoTest, BothPotsOnOneAdcChannelAreRefused) {
  set(Id::kElEnabled, 1);
  set(Id::kIioElChannel, 0);
  EXPECT_FALSE(open());
  EXPECT_EQ(error, "iio.az_channel and iio.el_channel both read channel 0 of IIO device 0");
  EXPECT_TRUE(board->lines.empty());
}

TEST(GpiodRulesTest, ConflictingLinesAreRefusedNamingBothKeys) {
  settings::Settings s;
  EXPECT_EQ(s.check_consistency().error, Error::kOk);
  ASSERT_EQ(s.set(Id::kGpiodBtnCw, 5).error, Error::kOk);  // gpiod.az_l1's line
  const settings::Rejection r = s.check_consistency();
  EXPECT_EQ(r.error, Error::kOutOfRange);
  EXPECT_STREQ(r.reason, "gpiod.az_l1 and gpiod.btn_cw both use line 5");
  ASSERT_EQ(s.set(Id::kGpiodBtnCw, -1).error, Error::kOk);
  ASSERT_EQ(s.set(Id::kPwmElUp, 1).error, Error::kOk);  // pwm.az_ccw's channel
  EXPECT_STREQ(s.check_consistency().reason, "pwm.az_ccw and pwm.el_up both use PWM channel 1");
  ASSERT_EQ(s.set(Id::kPwmElUp, -1).error, Error::kOk);
  ASSERT_EQ(s.set(Id::kGpiodBtnCw, -1).error, Error::kOk);
  ASSERT_EQ(s.set(Id::kGpiodBtnCcw, -1).error, Error::kOk);
  EXPECT_EQ(s.check_consistency().error, Error::kOk);  // unwired lines never clash
}

}  // namespace
}  // namespace rotord::linux_port
