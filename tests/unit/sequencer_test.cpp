#include "axis/sequencer.hpp"

#include <gtest/gtest.h>

#include "axis/sequences.hpp"

namespace rotord {
namespace {

TEST(Sequencer, PlaysStepsAtTheirTimes) {
  // A soft start of a relay-switched 6 V creep / 48 V fast motor, as data.
  Sequence seq;
  seq.add(StepTarget::kBrake, 1.0f, 200);
  seq.add(StepTarget::kVoltageFast, 0.0f, 0);
  seq.add(StepTarget::kDirRelay, 1.0f, 500);
  seq.add(StepTarget::kVoltageFast, 1.0f, 0);
  EXPECT_EQ(seq.total_ms(), 700);

  Sequencer s;
  DriveOutputs out;
  s.start(seq, Direction::kCcw, 1000);
  EXPECT_TRUE(s.run(1000, out));
  EXPECT_TRUE(out.on(OutputChannel::kBrake));
  EXPECT_FALSE(out.on(OutputChannel::kRelayCcw));  // brake release delay first
  EXPECT_TRUE(s.run(1199, out));
  EXPECT_FALSE(out.on(OutputChannel::kRelayCcw));
  EXPECT_TRUE(s.run(1200, out));
  EXPECT_TRUE(out.on(OutputChannel::kRelayCcw));
  EXPECT_FALSE(out.on(OutputChannel::kRelayCw));
  EXPECT_FALSE(out.on(OutputChannel::kVoltageFast));  // creeps for 500 ms
  EXPECT_TRUE(s.run(1699, out));
  EXPECT_FALSE(out.on(OutputChannel::kVoltageFast));
  EXPECT_FALSE(s.run(1700, out));
  EXPECT_TRUE(out.on(OutputChannel::kVoltageFast));
}

TEST(Sequencer, DirectionRelayNeverLeavesTheOtherOneOn) {
  DriveOutputs out;
  out.set(OutputChannel::kRelayCcw, 1.0f);
  Sequencer::apply({StepTarget::kDirRelay, 1.0f, 0}, Direction::kCw, out);
  EXPECT_TRUE(out.on(OutputChannel::kRelayCw));
  EXPECT_FALSE(out.on(OutputChannel::kRelayCcw));
}

TEST(Sequencer, CapacityIsBounded) {
  Sequence seq;
  for (int n = 0; n < Sequence::kMaxSteps; ++n) EXPECT_TRUE(seq.add(StepTarget::kBrake, 0, 1));
  EXPECT_FALSE(seq.add(StepTarget::kBrake, 0, 1));
  EXPECT_EQ(seq.size(), Sequence::kMaxSteps);
}

TEST(Sequences, BrakeIsReleasedBeforeDriveAndEngagedAfterCoast) {
  AxisConfig cfg;
  cfg.has_brake = true;
  cfg.brake_release_ms = 500;
  cfg.brake_engage_ms = 3000;
  const Sequence start = make_start_sequence(cfg);
  ASSERT_GE(start.size(), 2);
  EXPECT_EQ(start[0].target, StepTarget::kBrake);
  EXPECT_EQ(start[0].hold_ms, 500);
  EXPECT_EQ(start[1].target, StepTarget::kDirRelay);

  const Sequence stop = make_stop_sequence(cfg, false);
  EXPECT_EQ(stop[0].target, StepTarget::kDirRelay);
  EXPECT_EQ(stop[0].value, 0.0f);
  EXPECT_EQ(stop[stop.size() - 1].target, StepTarget::kBrake);
  EXPECT_EQ(stop[stop.size() - 1].value, 0.0f);
  EXPECT_EQ(stop.total_ms(), 3000);
}

TEST(Sequences, VoltageSelectSoftStopCreepsBeforeCutting) {
  AxisConfig cfg;
  cfg.drive = DriveType::kRelayVoltageSelect;
  cfg.soft_ms = 800;
  cfg.dir_settle_ms = 100;
  const Sequence stop = make_stop_sequence(cfg, false);
  EXPECT_EQ(stop[0].target, StepTarget::kVoltageFast);
  EXPECT_EQ(stop[0].hold_ms, 800);
  EXPECT_EQ(stop[stop.size() - 1].target, StepTarget::kDirRelay);
  // A hard stop (limit switch) skips the creep.
  EXPECT_EQ(make_stop_sequence(cfg, true).total_ms(), 0);
}

}  // namespace
}  // namespace rotord
