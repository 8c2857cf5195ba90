#include <gtest/gtest.h>

#include "fake_rotator.hpp"
#include "input/debouncer.hpp"
#include "input/manual_buttons.hpp"

namespace rotord {
namespace {

using settings::Id;

TEST(Debouncer, ChangesOnlyAfterTheLevelHolds) {
  Debouncer d(30);
  EXPECT_FALSE(d.update(false, 0));
  EXPECT_FALSE(d.update(true, 10));
  EXPECT_FALSE(d.update(true, 30));  // held 20 ms
  EXPECT_TRUE(d.update(true, 40));   // held 30 ms
  EXPECT_TRUE(d.pressed());
  EXPECT_TRUE(d.update(true, 50));
  EXPECT_FALSE(d.pressed());  // an edge is reported once
  EXPECT_TRUE(d.update(false, 60));
  EXPECT_FALSE(d.update(false, 90));
  EXPECT_TRUE(d.released());
}

TEST(Debouncer, BounceRestartsTheWait) {
  Debouncer d(30);
  d.update(false, 0);
  // A contact that bounces every 10 ms for 100 ms never changes the state.
  for (Millis t = 10; t <= 100; t += 10) EXPECT_FALSE(d.update(t % 20 == 10, t)) << t;
  // Then it closes for good.
  for (Millis t = 110; t < 140; t += 10) EXPECT_FALSE(d.update(true, t));
  EXPECT_TRUE(d.update(true, 140));
}

TEST(Debouncer, SettlesOnTheFirstStableLevel) {
  Debouncer d(30);
  d.update(true, 1000);
  EXPECT_FALSE(d.settled());
  d.update(true, 1030);
  EXPECT_TRUE(d.settled());
  EXPECT_TRUE(d.state());
}

struct Panel {
  testing::FakeSwitch cw, ccw, up, down;
  ManualButtons buttons{{&cw, &ccw}, {&up, &down}};
  Millis now = 0;
  Panel() { buttons.configure(true, 30); }
  /// Polls for `ms`; returns the last command seen per axis.
  std::array<ManualButtons::Command, kMaxAxes> run(Millis ms) {
    std::array<ManualButtons::Command, kMaxAxes> last{};
    for (Millis t = 0; t < ms; t += 10) {
      now += 10;
      const auto c = buttons.poll(now);
      for (std::size_t n = 0; n < c.size(); ++n)
        if (c[n].changed) last[n] = c[n];
    }
    return last;
  }
};

TEST(ManualButtons, HeldMovesReleasedStops) {
  Panel p;
  EXPECT_FALSE(p.run(100)[0].changed);
  p.cw.on = true;
  auto c = p.run(50);
  EXPECT_TRUE(c[0].changed);
  EXPECT_EQ(c[0].dir, Direction::kCw);
  EXPECT_FALSE(c[1].changed);
  EXPECT_FALSE(p.run(500)[0].changed);  // held: no repeated commands
  p.cw.on = false;
  c = p.run(50);
  EXPECT_TRUE(c[0].changed);
  EXPECT_EQ(c[0].dir, Direction::kNone);
  p.down.on = true;
  c = p.run(50);
  EXPECT_EQ(c[1].dir, Direction::kCcw);
}

TEST(ManualButtons, BothOfAPairMeansStop) {
  Panel p;
  p.run(100);
  p.ccw.on = true;
  EXPECT_EQ(p.run(50)[0].dir, Direction::kCcw);
  p.cw.on = true;
  auto c = p.run(50);
  EXPECT_TRUE(c[0].changed);
  EXPECT_EQ(c[0].dir, Direction::kNone);
}

TEST(ManualButtons, AButtonHeldAtPowerOnDoesNothingUntilReleased) {
  Panel p;
  p.cw.on = true;  // stuck, or leaned on while plugging in
  EXPECT_FALSE(p.run(1000)[0].changed);
  p.cw.on = false;
  EXPECT_FALSE(p.run(100)[0].changed);
  p.cw.on = true;
  EXPECT_EQ(p.run(50)[0].dir, Direction::kCw);
}

TEST(ManualButtons, DisabledButtonsCommandNothing) {
  Panel p;
  p.buttons.configure(false, 30);
  p.run(100);
  p.cw.on = true;
  EXPECT_FALSE(p.run(200)[0].changed);
}

class ButtonController : public ::testing::Test {
 protected:
  testing::FakeRotator r{false};
  void SetUp() override {
    ASSERT_EQ(r.settings.set(Id::kPinBtnCw, 13).error, Error::kOk);
    ASSERT_EQ(r.settings.set(Id::kPinBtnCcw, 4).error, Error::kOk);
    ASSERT_EQ(r.settings.set(Id::kButtonsEnabled, 1).error, Error::kOk);
    ASSERT_EQ(r.settings.check_consistency().error, Error::kOk);
    r.settings.set(Id::kAzReverseDeadMs, 100);
    r.settings.set(Id::kAzMinDwellMs, 0);
    r.run_ms(100);
  }
  const AxisStatus& az() {
    status_ = r.controller->status();
    return status_.az;
  }
  RotatorStatus status_;
};

TEST_F(ButtonController, HoldingCwDrivesCwUntilReleased) {
  r.az.button_fwd.on = true;
  r.run_ms(200);
  EXPECT_TRUE(r.az.drive.cw());
  EXPECT_FALSE(r.az.drive.ccw());
  EXPECT_EQ(r.controller->status().mode, Mode::kManual);
  r.az.button_fwd.on = false;
  r.run_ms(100);
  EXPECT_FALSE(r.az.drive.cw());
  EXPECT_FALSE(az().jogging);
}

TEST_F(ButtonController, ReleasingDoesNotCancelAClientGoto) {
  r.az.button_rev.on = true;
  r.run_ms(100);
  ASSERT_TRUE(az().jogging);
  // A client sends a go-to while the button is still held.
  ASSERT_EQ(r.controller->go_to(300.0f, std::nullopt, AzTarget::kUnwrapped), Error::kOk);
  r.az.button_rev.on = false;
  r.run_ms(100);
  EXPECT_TRUE(az().has_target);
}

TEST_F(ButtonController, TheLimitStillWins) {
  r.az.limit_cw.on = true;
  r.az.button_fwd.on = true;
  r.run_ms(300);
  EXPECT_FALSE(r.az.drive.cw());
}

TEST_F(ButtonController, DisabledInSettingsMeansIgnored) {
  r.settings.set(Id::kButtonsEnabled, 0);
  r.az.button_fwd.on = true;
  r.run_ms(300);
  EXPECT_FALSE(r.az.drive.cw());
  EXPECT_FALSE(az().jogging);
}

// The buttons are a front end of the command layer (command/buttons.hpp)
// with no access rule: a control lock taken through the web holds back the
// network's clients, not a hand on the box.
TEST_F(ButtonController, TheControlLockDoesNotHoldBackAHandOnTheBox) {
  r.controller->control_lock().take(access::LockHolder{}, r.now + 60'000);
  r.az.button_fwd.on = true;
  r.run_ms(200);
  EXPECT_TRUE(r.az.drive.cw());
  r.az.button_fwd.on = false;
  r.run_ms(100);
  EXPECT_FALSE(r.az.drive.cw());
  EXPECT_TRUE(r.controller->control_lock().held());
}

// Settings changed at run time reach the buttons before the next poll, as
// when the controller polled them in its tick: enabled again, they move.
TEST_F(ButtonController, EnablingAgainInSettingsTakesEffectAtOnce) {
  r.settings.set(Id::kButtonsEnabled, 0);
  r.run_ms(100);
  r.settings.set(Id::kButtonsEnabled, 1);
  r.az.button_fwd.on = true;
  r.run_ms(200);
  EXPECT_TRUE(r.az.drive.cw());
}

TEST(ButtonSettings, EnablingNeedsBothAzimuthPinsOfEitherPort) {
  settings::Settings s;
  ASSERT_EQ(s.set(Id::kButtonsEnabled, 1).error, Error::kOk);
  const settings::Rejection r = s.check_consistency();
  EXPECT_EQ(r.error, Error::kOutOfRange);
  EXPECT_STREQ(r.reason,
               "buttons.enabled needs pins.btn_cw and pins.btn_ccw (Pico W) or gpiod.btn_cw and "
               "gpiod.btn_ccw (Raspberry Pi)");
  // One Raspberry Pi line is not enough; both are.
  ASSERT_EQ(s.set(Id::kGpiodBtnCw, 13).error, Error::kOk);
  EXPECT_EQ(s.check_consistency().error, Error::kOutOfRange);
  ASSERT_EQ(s.set(Id::kGpiodBtnCcw, 19).error, Error::kOk);
  EXPECT_EQ(s.check_consistency().error, Error::kOk) << s.check_consistency().reason;
}

}  // namespace
}  // namespace rotord
