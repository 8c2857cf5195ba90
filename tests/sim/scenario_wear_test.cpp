// The wear odometer and the starts-per-hour ceiling (docs/care.md), on the
// physics simulator in virtual time: what the relays and the motor were
// given is counted, and a go-to stream cannot start the motor more often
// than care.max_starts_h.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "../unit/memory_storage.hpp"
#include "care/odometer_record.hpp"
#include "care/odometer_saver.hpp"
#include "care_rig.hpp"

namespace rotord {
namespace {

using care::AxisWear;

const AxisWear& wear(Rig& r) {
  return r.controller().odometer().axis(AxisId::kAz).wear();
}

TEST(Wear, GoTosAreCountedAsTheRelaysAndTheMotorSawThem) {
  // A Ham IV: brake, relay drive. Out to 250, back to 150 (a reversal).
  Rig r("ham4", 200.0);
  r.run_ms(1000);
  ASSERT_EQ(r.controller().go_to(250.0f, std::nullopt), Error::kOk);
  r.run_ms(40000);
  ASSERT_EQ(r.controller().go_to(150.0f, std::nullopt), Error::kOk);
  r.run_ms(60000);
  const AxisWear& w = wear(r);
  std::printf(
      "ham4 200 -> 250 -> 150: starts %u, reversals %u, run %.1f s, turned %u deg, "
      "brake %u, relays %u\n",
      w.starts, w.reversals, static_cast<double>(w.run_ms) / 1000.0, w.turned_deg, w.brake_cycles,
      w.relay_switchings);
  EXPECT_EQ(w.starts, r.az().moves);  // every start the axis made, corrections included
  EXPECT_GE(w.starts, 2u);
  EXPECT_GE(w.reversals, 1u);
  EXPECT_EQ(w.brake_cycles, w.starts);           // the brake is released for every start
  EXPECT_GE(w.relay_switchings, 2u * w.starts);  // a direction relay and the brake each
  EXPECT_NEAR(static_cast<double>(w.turned_deg), 150.0, 6.0);
  // The motor ran for the turn, at the Ham IV's speed or slower.
  const double run_s = static_cast<double>(w.run_ms) / 1000.0;
  EXPECT_GT(run_s, 150.0 / 10.0);
  EXPECT_EQ(w.faults_total(), 0u);
}

TEST(Wear, AFaultIsCountedByItsKind) {
  Rig r("g5500", 200.0);
  r.run_ms(1000);
  r.sim().jam(AxisId::kAz, 100.0);
  ASSERT_EQ(r.controller().go_to(260.0f, std::nullopt), Error::kOk);
  ASSERT_GT(r.run_until_fault(10000), 0);
  EXPECT_EQ(wear(r).faults[static_cast<std::size_t>(r.az().fault)], 1u);
  EXPECT_EQ(wear(r).faults_total(), 1u);
}

TEST(Wear, TheCountsSurviveARestartAndADamagedRecordStartsFromZero) {
  testing::MemoryStorage storage;
  char buf[2048];
  AxisWear before;
  {
    Rig r("g5500", 200.0);
    care::OdometerSaver saver(r.controller().odometer(), storage, buf, sizeof buf, 60000);
    ASSERT_EQ(saver.load(r.now()), care::OdometerSaver::Load::kNothingStored);
    ASSERT_EQ(r.controller().go_to(240.0f, std::nullopt), Error::kOk);
    for (int n = 0; n < 7000; ++n) {  // 70 s: one save interval passes
      r.tick();
      saver.poll(r.now(), r.controller().status().moving());
    }
    EXPECT_EQ(saver.writes(), 1u);
    before = wear(r);
    ASSERT_GE(before.starts, 1u);
  }
  {
    Rig r("g5500", 240.0);  // the power came back
    care::OdometerSaver saver(r.controller().odometer(), storage, buf, sizeof buf, 60000);
    ASSERT_EQ(saver.load(r.now()), care::OdometerSaver::Load::kLoaded);
    EXPECT_EQ(wear(r).starts, before.starts);
    EXPECT_EQ(wear(r).turned_deg, before.turned_deg);
    EXPECT_EQ(wear(r).run_ms, before.run_ms);
    // Loaded is not changed: nothing is written back until it counts more.
    r.run_ms(70000);
    EXPECT_EQ(saver.poll(r.now()), care::OdometerSaver::Result::kIdle);
  }
  storage.document.replace(storage.document.find("\"az.starts\":"), 12, "\"az.starts\":-");
  {
    Rig r("g5500", 240.0);
    care::OdometerSaver saver(r.controller().odometer(), storage, buf, sizeof buf, 60000);
    ASSERT_EQ(saver.load(r.now()), care::OdometerSaver::Load::kDamaged);
    std::printf("a damaged record: %s\n", saver.why());
    EXPECT_EQ(wear(r).starts, 0u);
    // The next save replaces it.
    EXPECT_EQ(saver.flush(r.now()), care::OdometerSaver::Result::kSaved);
    AxisWear az;
    AxisWear el;
    std::int64_t date = 0;
    const char* why = "";
    EXPECT_TRUE(care::decode_record(storage.document, az, el, date, why)) << why;
  }
}

TEST(Wear, AResetIsDatedAndWrittenAtOnce) {
  testing::MemoryStorage storage;
  char buf[2048];
  Rig r("g5500", 200.0);
  care::OdometerSaver saver(r.controller().odometer(), storage, buf, sizeof buf, 600000);
  saver.load(r.now());
  ASSERT_EQ(r.controller().go_to(230.0f, std::nullopt), Error::kOk);
  r.run_ms(20000);
  EXPECT_EQ(saver.poll(r.now()), care::OdometerSaver::Result::kWaiting);
  r.controller().odometer().reset(1795000000);
  EXPECT_EQ(saver.poll(r.now()), care::OdometerSaver::Result::kSaved);
  EXPECT_EQ(wear(r).starts, 0u);
  EXPECT_NE(storage.document.find("\"reset_unix_s\":1795000000"), std::string::npos);
}

/// A tracker's go-to stream: a new target every `step_s` moving at
/// `rate_deg_s`, for `minutes`; returns the starts of the azimuth.
std::uint32_t run_stream(Rig& r, double rate_deg_s, int step_s, int minutes, float& worst_err) {
  float target = 100.0f;
  worst_err = 0.0f;
  const std::uint32_t starts0 = r.az().moves;
  for (int s = 0; s < minutes * 60; s += step_s) {
    target += static_cast<float>(rate_deg_s * step_s);
    if (target > 440.0f || target < 10.0f) rate_deg_s = -rate_deg_s;
    EXPECT_EQ(r.controller().go_to(target, std::nullopt, AzTarget::kUnwrapped), Error::kOk);
    r.run_ms(step_s * 1000);
    worst_err = std::fmax(worst_err, std::fabs(r.az().position_deg - target));
  }
  return r.az().moves - starts0;
}

TEST(StartsCeiling, AGoToStreamCannotPassIt) {
  // A G-5500 following a target at 0.05 deg/s with a go-to every 10 s: with
  // a tolerance of 1 deg about 180 starts an hour; the ceiling is 60.
  Rig free_run("g5500", 100.0);
  float free_err = 0.0f;
  const std::uint32_t free_starts = run_stream(free_run, 0.1, 10, 60, free_err);
  Rig r("g5500", 100.0);
  r.settings().set(settings::Id::kCareMaxStartsH, 60);
  float held_err = 0.0f;
  const std::uint32_t starts = run_stream(r, 0.1, 10, 60, held_err);
  std::printf(
      "an hour of go-tos at 0.1 deg/s: %u starts without a ceiling (worst lag %.2f deg), "
      "%u with care.max_starts_h 60 (worst lag %.2f deg), %u holds\n",
      free_starts, static_cast<double>(free_err), starts, static_cast<double>(held_err),
      r.controller().starts_held(AxisId::kAz));
  EXPECT_GT(free_starts, 60u);
  EXPECT_LE(starts, 60u);
  EXPECT_LE(r.controller().start_ceiling(AxisId::kAz).starts_in_hour(), 60u);
  EXPECT_GT(r.controller().starts_held(AxisId::kAz), 0u);
  // The tolerance widened, the antenna still follows: within a few
  // minutes' travel of the target.
  EXPECT_LT(held_err, 0.1f * 6.0f * 60.0f);
  // Jogs are never held, STOP works while a go-to waits.
  r.controller().stop();
  r.run_ms(1000);
  EXPECT_FALSE(r.az().start_held);
  EXPECT_EQ(r.controller().move(AxisId::kAz, Direction::kCw), Error::kOk);
  r.run_ms(2000);
  EXPECT_NE(r.az().state, AxisState::kIdle);
  r.controller().stop();
}

TEST(StartsCeiling, OffByDefault) {
  Rig r("g5500", 100.0);
  float err = 0.0f;
  run_stream(r, 0.1, 10, 20, err);
  EXPECT_EQ(r.controller().starts_held(AxisId::kAz), 0u);
}

}  // namespace
}  // namespace rotord
