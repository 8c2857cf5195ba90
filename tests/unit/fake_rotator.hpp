#pragma once
// Fakes at the hardware boundary for core unit tests: an ADC whose counts a
// test sets, switches, and a drive sink that records what the axis wrote. The
// "plant" here is the test itself: it moves the pot by hand. Whole-plant
// behaviour (coast, backlash, noise) is tested in tests/sim with the simulator.
#include <memory>

#include "axis/axis_io.hpp"
#include "command/buttons.hpp"
#include "rotator/controller.hpp"
#include "settings/settings.hpp"

namespace rotord::testing {

/// A 13-bit converter, so 0.1 deg per count spans the whole 0..450 deg travel.
class FakeAdc final : public hal::AnalogIn {
 public:
  std::uint16_t counts = 2048;
  std::uint16_t read_counts() override { return counts; }
  std::uint16_t full_scale_counts() const override { return 8191; }
  float reference_v() const override { return 3.3f; }
};

class FakeSwitch final : public hal::DigitalIn {
 public:
  bool on = false;
  bool active() override { return on; }
};

class FakePwmIn final : public hal::PwmIn {
 public:
  hal::PwmPeriod period{0, 4097, true};
  hal::PwmPeriod read() override { return period; }
};

class RecordingDrive final : public DriveSink {
 public:
  DriveOutputs last;
  int applies = 0;
  void apply(const DriveOutputs& outputs) override {
    last = outputs;
    ++applies;
  }
  bool cw() const { return last.on(OutputChannel::kRelayCw) || last.on(OutputChannel::kPwmCw); }
  bool ccw() const { return last.on(OutputChannel::kRelayCcw) || last.on(OutputChannel::kPwmCcw); }
};

/// The hardware of one axis: a pot at 0.1 deg per count (0 counts = 0 deg),
/// so tests can set angles directly. Below 0.8 deg the ADC is at its rail,
/// which the sensor rightly reports as a fault.
struct FakeAxisHardware {
  FakeAdc adc;
  FakePwmIn ma3;
  FakeSwitch limit_cw, limit_ccw, t1, t2;
  FakeSwitch button_fwd, button_rev;
  RecordingDrive drive;

  void set_deg(float deg) { adc.counts = static_cast<std::uint16_t>(deg * 10.0f + 0.5f); }
  AxisIo io() {
    return {&adc, &ma3, &limit_cw, &limit_ccw, &t1, &t2, &drive, &button_fwd, &button_rev};
  }
};

/// A controller on fake hardware: az 0..450 (pot 0.1 deg/count), optional el
/// 0..180, relay drives, no soft start, short dead times.
struct FakeRotator {
  settings::Settings settings;
  FakeAxisHardware az, el;
  std::unique_ptr<Controller> controller;
  /// The manual buttons' front end, polled before each tick as a port does
  /// (made again for a controller a test replaced).
  std::unique_ptr<command::Buttons> buttons;
  const Controller* buttons_for = nullptr;
  Millis now = 0;

  explicit FakeRotator(bool with_el = true) {
    using settings::Id;
    auto set = [this](Id id, double v) { settings.set(id, v); };
    set(Id::kElEnabled, with_el ? 1 : 0);
    set(Id::kAzMinDeg, 0);
    set(Id::kAzMaxDeg, 450);
    set(Id::kAzPotCalLoCounts, 100);
    set(Id::kAzPotCalLoDeg, 10);
    set(Id::kAzPotCalHiCounts, 4000);
    set(Id::kAzPotCalHiDeg, 400);
    set(Id::kElPotCalLoCounts, 100);
    set(Id::kElPotCalLoDeg, 10);
    set(Id::kElPotCalHiCounts, 1800);
    set(Id::kElPotCalHiDeg, 180);
    az.set_deg(100);
    el.set_deg(20);
    controller = std::make_unique<Controller>(settings, az.io(), el.io());
    controller->begin(now);
  }

  /// Advances time in 10 ms ticks.
  void run_ms(Millis ms) {
    for (Millis t = 0; t < ms; t += 10) {
      now += 10;
      if (buttons_for != controller.get()) {
        buttons = std::make_unique<command::Buttons>(*controller, az.io(), el.io());
        buttons_for = controller.get();
      }
      buttons->poll(now);
      controller->tick(now);
    }
  }
};

}  // namespace rotord::testing
