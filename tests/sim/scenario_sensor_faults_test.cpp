// Sensor faults told apart from jams (docs/care.md), on the physics
// simulator in virtual time: a noise burst is held off by the robust filter
// (the position wanders by at most the tolerance) and named SENSOR_JUMP; a
// reading that freezes while the motor turns the antenna is named
// SENSOR_STUCK within a second, long before the stall rule (stall_ms); a jam
// is still a STALL.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <functional>
#include <memory>

#include "care_rig.hpp"
#include "sim/fault_window.hpp"

namespace rotord {
namespace {

struct Burst {
  Millis fault_after_ms = -1;
  double before_deg = 0.0;   // reported position against the plant, jogging before ...
  double max_off_deg = 0.0;  // ... and during the burst
  AxisFault fault = AxisFault::kNone;
};

/// Jogs clockwise at full speed, then the sensor's noise rises to
/// `sigma_deg` for ever; runs until a fault, tracking how far the position
/// the controller reports strays from the antenna's true angle.
Burst burst_while_jogging(const char* profile, double sigma_deg, std::uint64_t seed) {
  Rig r(profile, 200.0, seed);
  EXPECT_EQ(r.controller().move(AxisId::kAz, Direction::kCw, 100), Error::kOk);
  Burst b;
  r.run_ms(500);  // up to speed
  for (Millis t = 0; t < 1000; t += 10) {
    r.tick();
    b.before_deg = std::max(b.before_deg, std::fabs(r.az().position_deg - r.theta()));
  }
  r.sim().sensor_noise_burst(AxisId::kAz, sigma_deg, sim::kForever_s);
  for (Millis t = 0; t < 3000; t += 10) {
    r.tick();
    const AxisStatus& a = r.az();
    b.max_off_deg = std::max(b.max_off_deg, std::fabs(a.position_deg - r.theta()));
    if (a.fault != AxisFault::kNone) {
      b.fault_after_ms = t + 10;
      b.fault = a.fault;
      break;
    }
  }
  r.run_ms(50);  // the drive's own delay
  EXPECT_FALSE(r.sim().plant(AxisId::kAz).powered());
  return b;
}

/// The worst of 20 bursts (seeds 1..20) of `sigma_deg` while jogging: each
/// must end in SENSOR_JUMP; `each` checks a burst further.
struct Worst {
  double off_deg = 0.0;    // the position against the antenna, at most
  double added_deg = 0.0;  // ... and further off than before the burst
};
Worst worst_of_bursts(const char* profile, const char* sensor, double sigma_deg,
                      const std::function<void(const Burst&, std::uint64_t seed)>& each) {
  Worst w;
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    const Burst b = burst_while_jogging(profile, sigma_deg, seed);
    w.added_deg = std::max(w.added_deg, b.max_off_deg - b.before_deg);
    EXPECT_EQ(b.fault, AxisFault::kSensorJump) << "seed " << seed;
    each(b, seed);
    w.off_deg = std::max(w.off_deg, b.max_off_deg);
  }
  std::printf(
      "%s burst of %.0f deg rms, 20 seeds: position at most %.2f deg off the antenna, at most "
      "%.2f deg further off than before the burst\n",
      sensor, sigma_deg, w.off_deg, w.added_deg);
  return w;
}

TEST(SensorFaults, ANoiseBurstMovesThePositionByLessThanTheTolerance) {
  // As the HIL scenario sensor-burst-ma3: 60 deg rms on a SPID's MA3. The
  // tolerance (az.tolerance_deg) is 1 deg; before the gate, readings within
  // az.jump_deg (15) of the last were taken and the position strayed ~4 deg.
  const Worst w = worst_of_bursts("spid", "MA3", 60.0, [](const Burst& b, std::uint64_t seed) {
    EXPECT_GE(b.fault_after_ms, 50) << "five readings in a row first";
    EXPECT_LE(b.fault_after_ms, 1500) << "seed " << seed;
  });
  EXPECT_LE(w.added_deg, 1.0);
  EXPECT_LE(w.off_deg, 1.0);
}

TEST(SensorFaults, AModerateBurstOnAPotIsHeldOffToo) {
  // 5 deg rms on a G-5500's pot (a wiper going bad): most readings miss the
  // gate; the position the controller steers by stays within the tolerance.
  const Worst w = worst_of_bursts("g5500", "pot", 5.0, [](const Burst&, std::uint64_t) {});
  EXPECT_LE(w.added_deg, 1.0);  // az.tolerance_deg
}

/// Jogs, freezes the sensor after `run_ms`, and reports when the fault came
/// and how far the antenna turned unseen.
struct Freeze {
  AxisFault fault = AxisFault::kNone;
  Millis after_ms = -1;
  double unseen_deg = 0.0;
};

Freeze freeze_while_jogging(const char* profile, Millis run_ms) {
  Rig r(profile, 200.0);
  EXPECT_EQ(r.controller().move(AxisId::kAz, Direction::kCw, 100), Error::kOk);
  r.run_ms(run_ms);
  const double frozen_at = r.theta();
  r.sim().sensor_stuck(AxisId::kAz, sim::kForever_s);
  Freeze f;
  f.after_ms = r.run_until_fault(5000);
  f.fault = r.az().fault;
  r.run_ms(1000);  // the coast
  f.unseen_deg = r.theta() - frozen_at;
  EXPECT_FALSE(r.sim().plant(AxisId::kAz).powered());
  return f;
}

/// freeze_while_jogging after 1.5 s, printed as `sensor`'s: SENSOR_STUCK
/// within a second of the freeze.
Freeze stuck_within_a_second(const char* profile, const char* sensor) {
  const Freeze f = freeze_while_jogging(profile, 1500);
  std::printf("frozen %s: SENSOR_STUCK %lld ms after the freeze, %.1f deg turned unseen\n", sensor,
              static_cast<long long>(f.after_ms), f.unseen_deg);
  EXPECT_EQ(f.fault, AxisFault::kSensorStuck);
  EXPECT_GT(f.after_ms, 0);
  EXPECT_LE(f.after_ms, 1000);
  return f;
}

TEST(SensorFaults, AFrozenPotIsASensorFaultWithinOneSecond) {
  // As the HIL scenario sensor-stuck-pot: the stall rule alone cut the drive
  // 3 s (az.stall_ms) after the freeze, the antenna having turned ~17 deg.
  const Freeze f = stuck_within_a_second("g5500", "pot");
  EXPECT_LT(f.unseen_deg, 7.0);
}

TEST(SensorFaults, AFrozenMa3IsASensorFaultWithinOneSecond) {
  stuck_within_a_second("spid", "MA3");
}

TEST(SensorFaults, AJamWhileTurningIsStillAStall) {
  // The sensor's noise goes on at a jam: its raw value keeps changing.
  Rig r("g5500", 200.0);
  ASSERT_EQ(r.controller().move(AxisId::kAz, Direction::kCw, 100), Error::kOk);
  r.run_ms(1500);
  r.sim().jam(AxisId::kAz, sim::kForever_s);
  const Millis after_ms = r.run_until_fault(5000);
  EXPECT_EQ(r.az().fault, AxisFault::kStall);
  EXPECT_GE(after_ms, 2500);
}

TEST(SensorFaults, AFreezeAtRestIsNoFault) {
  // A quiet sensor at rest reads the same value for ever; so does a frozen
  // one. Only motion tells them apart: nothing latches at rest.
  Rig r("spid", 200.0);
  r.sim().sensor_stuck(AxisId::kAz, sim::kForever_s);
  r.run_ms(10000);
  EXPECT_EQ(r.az().fault, AxisFault::kNone);
}

TEST(SensorFaults, GoToAfterAGoToOnAQuietEncoderIsNoFalseFreeze) {
  // The SPID's worm gear stops within a code or two: its encoder then reads
  // one code for as long as the axis rests. The next start must not take
  // that old, unchanged reading for a freeze.
  Rig r("spid", 200.0);
  for (float target : {240.0f, 180.0f, 185.0f, 300.0f, 100.0f}) {
    ASSERT_EQ(r.controller().go_to(target, std::nullopt, AzTarget::kUnwrapped), Error::kOk);
    for (int n = 0; n < 1000 && (r.az().has_target || r.az().state != AxisState::kIdle); ++n)
      r.run_ms(100);
    EXPECT_EQ(r.az().fault, AxisFault::kNone) << "to " << target;
    EXPECT_NEAR(r.az().position_deg, target, 1.0);
    r.run_ms(5000);
  }
}

TEST(SensorFaults, AnHourOfGoTosOnEveryProfileRejectsNoHealthyReading) {
  // The filter must not take a healthy sensor's noise for a burst: an hour
  // of go-tos across the travel on each profile (sensor noise as the
  // profile sets it), no reading turned away and no fault. (The 24 h run
  // with gusts is bench/care.)
  for (const char* profile : {"g5500", "spid", "ham4"}) {
    Rig r(profile, 200.0);
    int faults = 0;
    for (int n = 0; n < 60; ++n) {
      const float az = 20.0f + static_cast<float>((n * 137) % 330);
      const float el = 5.0f + static_cast<float>((n * 53) % 80);
      ASSERT_EQ(
          r.controller().go_to(az, r.sim().has_el() ? std::optional<float>(el) : std::nullopt),
          Error::kOk);
      r.run_ms(60000);
      if (r.controller().status().any_fault()) {
        ++faults;
        (void)r.controller().reset();
      }
    }
    const RotatorStatus s = r.controller().status();
    std::printf("%s, 60 go-tos in an hour: %u + %u readings rejected, %u + %u slips, %d faults\n",
                profile, s.az.readings_rejected, s.el.readings_rejected, s.az.slips, s.el.slips,
                faults);
    EXPECT_EQ(s.az.slips + s.el.slips, 0u) << profile;
    EXPECT_EQ(s.az.readings_rejected, 0u) << profile;
    EXPECT_EQ(s.el.readings_rejected, 0u) << profile;
    EXPECT_EQ(faults, 0) << profile;
  }
}

}  // namespace
}  // namespace rotord
