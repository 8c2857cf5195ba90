// `rotord --outputs-off` (outputs_off.hpp), the unit's ExecStopPost step, on
// the fake at the libgpiod boundary and a fake PWM sysfs tree: after rotord
// died with its relays energised (kill -9 leaves every line at its last
// value), every wired output is requested inactive and released, inputs are
// left alone, and one output that fails does not keep the others on.
#include "outputs_off.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <set>
#include <vector>

#include "fake_gpio_chip.hpp"
#include "fake_sysfs.hpp"
#include "gpiod_io.hpp"
#include "rotator/controller.hpp"

namespace rotord::linux_port {
namespace {

using settings::Id;
using testing::FakeBoard;
using testing::FakeGpioChip;
using testing::FakeSysfs;

// The defaults of the gpiod.* rows.
constexpr int kAzCw = 17, kAzCcw = 27, kAzSpeed = 22, kAzBrake = 23, kElUp = 24, kElDown = 25;
constexpr int kAzL1 = 5, kAzL2 = 6, kAzT1 = 16;

class OutputsOffTest : public ::testing::Test {
 protected:
  void set(Id id, double value) {
    ASSERT_EQ(s.set(id, value).error, Error::kOk) << settings::def(id).key;
  }
  OutputsOffResult run() {
    return drive_outputs_off(
        s,
        [this](std::string& error) -> std::unique_ptr<GpioChip> {
          ++chip_opens;
          if (!chip_present) {
            error = "cannot open GPIO chip /dev/gpiochip0 (gpiod.chip = 0): No such file";
            return nullptr;
          }
          return std::make_unique<FakeGpioChip>(board);
        },
        pwm.root());
  }
  /// The lines as the kernel leaves them when rotord dies holding them on.
  void left_on(std::initializer_list<int> offsets) {
    for (const int offset : offsets) {
      board->lines[offset].active = true;
      board->lines[offset].released = true;
    }
  }
  long long pwm_file(const std::string& f) {
    std::ifstream in(pwm.root() + "/pwmchip0/" + f);
    long long v = -1;
    in >> v;
    return v;
  }

  settings::Settings s;
  FakeSysfs pwm;  ///< /sys/class/pwm
  std::shared_ptr<FakeBoard> board = std::make_shared<FakeBoard>();
  bool chip_present = true;
  int chip_opens = 0;
};

TEST_F(OutputsOffTest, RelaysLeftOnByAKilledDaemonAreRequestedInactiveAndReleased) {
  set(Id::kAzDrive, 1);  // relay_two_speed: the speed line too
  set(Id::kAzHasBrake, 1);
  left_on({kAzCw, kAzSpeed, kAzBrake});
  const OutputsOffResult r = run();
  EXPECT_TRUE(r.ok()) << r.errors;
  EXPECT_EQ(r.lines_off, 4);
  for (const int out : {kAzCw, kAzCcw, kAzSpeed, kAzBrake}) {
    const FakeBoard::Line& line = board->lines[out];
    EXPECT_TRUE(line.requested) << out;
    EXPECT_EQ(line.request.mode, LineMode::kOutput) << out;
    EXPECT_FALSE(line.request.active_low) << out;
    EXPECT_FALSE(line.active) << out;
    EXPECT_GE(line.writes, 1) << out;  // written inactive, not only requested
    EXPECT_TRUE(line.released) << out;
  }
  EXPECT_TRUE(board->closed);
  // Limit switches, overlap inputs, the MA3: not outputs, not touched.
  for (const int in : {kAzL1, kAzL2, kAzT1}) EXPECT_FALSE(board->lines[in].requested) << in;
  EXPECT_NE(r.done.find("gpiod.az_cw line 17"), std::string::npos) << r.done;
}

TEST_F(OutputsOffTest, ItDrivesOffWhatTheDaemonDroveOn) {
  // The daemon moves the rotator, then dies without its exit path (its
  // lines keep their values); --outputs-off finds every line it drove.
  set(Id::kAzDrive, 1);
  set(Id::kAzHasBrake, 1);
  set(Id::kElEnabled, 1);
  set(Id::kAzSensor, 1);  // MA3: no ADC needed here
  set(Id::kElSensor, 1);
  set(Id::kGpiodElMa3, 12);
  FakeSysfs none;
  std::string error;
  auto hw = GpiodRotator::open(
      s, std::make_unique<FakeGpioChip>(board),
      GpiodHost{none.root(), pwm.root(), none.root(), nullptr, [] { return std::uint64_t{0}; }},
      error);
  ASSERT_TRUE(hw) << error;
  std::set<int> outputs;
  for (const auto& [offset, line] : board->lines)
    if (line.request.mode == LineMode::kOutput) outputs.insert(offset);
  EXPECT_EQ(outputs, (std::set<int>{kAzCw, kAzCcw, kAzSpeed, kAzBrake, kElUp, kElDown}));
  // kill -9: no destructor runs, nothing is written off. Kept reachable
  // (not leaked) so LeakSanitizer stays quiet under asan_suites.
  static std::vector<std::unique_ptr<GpiodRotator>> killed;
  killed.push_back(std::move(hw));
  left_on({kAzCw, kAzBrake, kElUp});
  board->closed = false;
  const OutputsOffResult r = run();
  EXPECT_TRUE(r.ok()) << r.errors;
  for (const int out : outputs) {
    EXPECT_FALSE(board->output_active(out)) << out;
    EXPECT_TRUE(board->lines[out].released) << out;
  }
  EXPECT_EQ(r.lines_off, static_cast<int>(outputs.size()));
}

TEST_F(OutputsOffTest, ElevationLinesOnlyWhenTheAxisIsEnabled) {
  EXPECT_TRUE(run().ok());
  EXPECT_FALSE(board->lines[kElUp].requested);
  set(Id::kElEnabled, 1);
  EXPECT_TRUE(run().ok());
  EXPECT_TRUE(board->lines[kElUp].requested);
  EXPECT_TRUE(board->lines[kElDown].requested);
}

TEST_F(OutputsOffTest, AnActiveLowRelayBoardIsRequestedInverted) {
  // Inactive on an active-low board is a high level: the kernel inverts.
  set(Id::kGpiodOutputsActiveLow, 1);
  EXPECT_TRUE(run().ok());
  EXPECT_TRUE(board->lines[kAzCw].request.active_low);
  EXPECT_FALSE(board->lines[kAzCw].active);
}

TEST_F(OutputsOffTest, ABusyLineIsNamedAndTheOthersStillGoOff) {
  set(Id::kAzHasBrake, 1);
  left_on({kAzCcw, kAzBrake});
  board->busy.insert(kAzCw);
  const OutputsOffResult r = run();
  EXPECT_FALSE(r.ok());
  EXPECT_NE(r.errors.find("gpiod.az_cw = 17"), std::string::npos) << r.errors;
  EXPECT_FALSE(board->output_active(kAzCcw));
  EXPECT_FALSE(board->output_active(kAzBrake));
  EXPECT_EQ(r.lines_off, 2);
}

TEST_F(OutputsOffTest, UnwiredLinesAreSkippedAndNoChipIsOpenedForNone) {
  set(Id::kGpiodAzCw, -1);
  set(Id::kGpiodAzCcw, -1);
  const OutputsOffResult r = run();
  EXPECT_TRUE(r.ok()) << r.errors;
  EXPECT_EQ(chip_opens, 0);
  EXPECT_TRUE(r.done.empty());
}

TEST_F(OutputsOffTest, HBridgeChannelsGetDutyZeroAndAreDisabledEvenWithoutAGpioChip) {
  set(Id::kAzDrive, 3);  // hbridge on pwmchip0 channels 0 and 1
  set(Id::kPwmChip, 0);
  set(Id::kElEnabled, 1);  // relays on GPIO lines, but no chip here
  chip_present = false;
  for (const char* ch : {"pwm0", "pwm1"}) {  // running at 80 % when rotord died
    pwm.write(std::string("pwmchip0/") + ch + "/period", "50000\n");
    pwm.write(std::string("pwmchip0/") + ch + "/duty_cycle", "40000\n");
    pwm.write(std::string("pwmchip0/") + ch + "/enable", "1\n");
  }
  const OutputsOffResult r = run();
  EXPECT_FALSE(r.ok());
  EXPECT_NE(r.errors.find("/dev/gpiochip0"), std::string::npos) << r.errors;
  EXPECT_EQ(r.channels_off, 2);
  for (const char* ch : {"pwm0", "pwm1"}) {
    EXPECT_EQ(pwm_file(std::string(ch) + "/duty_cycle"), 0) << ch;
    EXPECT_EQ(pwm_file(std::string(ch) + "/enable"), 0) << ch;
  }
  EXPECT_FALSE(board->lines[kAzCw].requested);  // an H-bridge has no relay lines
}

}  // namespace
}  // namespace rotord::linux_port
