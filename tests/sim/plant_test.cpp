// Plant dynamics (sim/plant.hpp) against the shared step reference and
// closed-form results.
#include "sim/plant.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <string>
#include <vector>

#include "plant_test_support.hpp"

namespace rotord::sim {
namespace {

using test::kDt_s;
using test::outputs_with;
using test::profile_axis;
using test::run;

struct ReferenceRow {
  std::string preset;
  std::string test;
  std::string theta0_deg;
  std::string sim_theta_deg;
  std::string analytic_theta_deg;
};

std::vector<std::string> split_csv(const std::string& line) {
  std::vector<std::string> fields(1);
  for (char c : line) {
    if (c == ',') {
      fields.emplace_back();
    } else if (c != '\r') {
      fields.back().push_back(c);
    }
  }
  return fields;
}

std::vector<ReferenceRow> load_reference() {
  std::ifstream in(std::string(ROTORD_TEST_DATA_DIR) + "/plant_step_reference.csv");
  std::vector<ReferenceRow> rows;
  std::string line;
  std::getline(in, line);  // header
  while (std::getline(in, line)) {
    const auto f = split_csv(line);
    if (f.size() < 5) continue;
    rows.push_back({f[0], f[1], f[2], f[3], f[4]});
  }
  return rows;
}

const AxisProfile& preset_axis(const std::string& preset) {
  if (preset == "G5500_AZ_LIKE") return profile_axis("g5500", false);
  if (preset == "G5500_EL_LIKE") return profile_axis("g5500", true);
  return profile_axis("spid", false);  // SPID_RAS_LIKE_24V
}

// +1 / -1 in the drive's own terms: relays or full H-bridge duty.
DriveOutputs drive(const AxisPlantParams& p, int direction) {
  DriveOutputs o;
  if (direction == 0) return o;
  if (p.drive == DriveKind::kHBridge) {
    o.set(direction > 0 ? OutputChannel::kPwmCw : OutputChannel::kPwmCcw, 1.0f);
  } else {
    o.set(direction > 0 ? OutputChannel::kRelayCw : OutputChannel::kRelayCcw, 1.0f);
  }
  return o;
}

TEST(PlantReference, MatchesAllRowsOfTheSharedStepReference) {
  const auto rows = load_reference();
  ASSERT_EQ(rows.size(), 9u) << "tests/data/plant_step_reference.csv not found or changed";
  int checked = 0;
  for (const auto& row : rows) {
    SCOPED_TRACE(row.preset + " " + row.test);
    const AxisPlantParams& p = preset_axis(row.preset).plant;
    AxisPlant plant(p);
    if (row.test == "drive_+1_for_10s_then_off_observe_at_13s") {
      plant.set_theta_deg(std::stod(row.theta0_deg));
      run(plant, drive(p, +1), 10.0);
      run(plant, drive(p, 0), 3.0);
      EXPECT_NEAR(plant.theta_deg(), std::stod(row.sim_theta_deg), 1e-3);
      EXPECT_NEAR(plant.theta_deg(), std::stod(row.analytic_theta_deg), 1e-3);
      ++checked;
    } else if (row.test == "drive_+1_5s_then_-1_5s_then_off_observe_at_13s") {
      plant.set_theta_deg(std::stod(row.theta0_deg));
      run(plant, drive(p, +1), 5.0);
      run(plant, drive(p, -1), 5.0);
      run(plant, drive(p, 0), 3.0);
      EXPECT_NEAR(plant.theta_deg(), std::stod(row.sim_theta_deg), 1e-3);
      EXPECT_NEAR(plant.theta_deg(), std::stod(row.analytic_theta_deg), 1e-3);
      ++checked;
    } else if (row.test == "coast_distance_from_full_speed") {
      plant.set_theta_deg(100.0);
      run(plant, drive(p, +1), 10.0);
      // Power actually drops one relay delay after the command.
      run(plant, drive(p, 0), p.relay_delay_s);
      const double theta_at_cut_deg = plant.theta_deg();
      EXPECT_NEAR(plant.w_deg_s(), p.v_max_deg_s, 1e-6);
      run(plant, drive(p, 0), 3.0);
      EXPECT_FALSE(plant.powered());
      EXPECT_NEAR(plant.theta_deg() - theta_at_cut_deg, std::stod(row.analytic_theta_deg), 1e-3);
      EXPECT_NEAR(plant.w_deg_s(), 0.0, 1e-6);
      ++checked;
    } else {
      ADD_FAILURE() << "unknown reference test";
    }
  }
  EXPECT_EQ(checked, 9);
}

TEST(Plant, ClosedFormRampMatchesAtAnyTime) {
  // G5500 az, 2 s after the command: x = v (t - tau (1 - e^(-t/tau))) - b/2,
  // with t the powered time (command time minus the 10 ms relay delay).
  const AxisPlantParams& p = profile_axis("g5500", false).plant;
  AxisPlant plant(p);
  plant.set_theta_deg(100.0);
  run(plant, outputs_with(OutputChannel::kRelayCw), 2.0);
  const double t_s = 2.0 - p.relay_delay_s;
  const double expected = 100.0 +
                          p.v_max_deg_s * (t_s - p.tau_m_s * (1.0 - std::exp(-t_s / p.tau_m_s))) -
                          0.5 * p.backlash_deg;
  EXPECT_NEAR(plant.theta_deg(), expected, 1e-9);
  EXPECT_NEAR(plant.w_deg_s(), p.v_max_deg_s * (1.0 - std::exp(-t_s / p.tau_m_s)), 1e-9);
}

TEST(Plant, ResultDoesNotDependOnTheCallersStepSize) {
  const AxisPlantParams& p = profile_axis("g5500", false).plant;
  AxisPlant fine(p);
  AxisPlant coarse(p);
  fine.set_theta_deg(10.0);
  coarse.set_theta_deg(10.0);
  const auto cw = outputs_with(OutputChannel::kRelayCw);
  for (int n = 0; n < 6000; ++n) fine.step(0.0005, cw);
  for (int n = 0; n < 60; ++n) coarse.step(0.05, cw);  // subdivided internally
  EXPECT_NEAR(fine.theta_deg(), coarse.theta_deg(), 1e-9);
  EXPECT_NEAR(fine.theta_deg(), 10.0 + 6.0 * 2.79 - 0.5, 1e-6);
}

TEST(Plant, RelayDelayHoldsOffPowerFor10ms) {
  AxisPlant plant(profile_axis("g5500", false).plant);
  plant.set_theta_deg(50.0);
  const auto cw = outputs_with(OutputChannel::kRelayCw);
  run(plant, cw, 0.009);
  EXPECT_FALSE(plant.powered());
  EXPECT_EQ(plant.w_deg_s(), 0.0);
  run(plant, cw, 0.001);
  EXPECT_TRUE(plant.powered());
}

TEST(Plant, HBridgeHasNoDelay) {
  AxisPlant plant(profile_axis("spid", false).plant);
  plant.step(kDt_s, outputs_with(OutputChannel::kPwmCw));
  EXPECT_TRUE(plant.powered());
  EXPECT_NEAR(plant.w_deg_s(), 6.0 * (1.0 - std::exp(-0.001 / 0.1)), 1e-12);
}

TEST(Plant, BothRelaysOnIsNoDrive) {
  AxisPlant plant(profile_axis("g5500", false).plant);
  plant.set_theta_deg(50.0);
  DriveOutputs both = outputs_with(OutputChannel::kRelayCw);
  both.set(OutputChannel::kRelayCcw, 1.0f);
  run(plant, both, 1.0);
  EXPECT_FALSE(plant.powered());
  EXPECT_EQ(plant.theta_deg(), 50.0);
}

TEST(Plant, BacklashIsTakenUpBeforeTheOutputMoves) {
  // G5500 el: b = 1.5. The motor side moves b/2 before theta moves, then
  // theta trails phi by exactly b/2.
  AxisPlant plant(profile_axis("g5500", true).plant);
  plant.set_theta_deg(45.0);
  run(plant, outputs_with(OutputChannel::kRelayCw), 0.2);
  EXPECT_GT(plant.phi_deg(), 45.0);
  EXPECT_LT(plant.phi_deg(), 45.75);
  EXPECT_EQ(plant.theta_deg(), 45.0);
  run(plant, outputs_with(OutputChannel::kRelayCw), 2.0);
  EXPECT_NEAR(plant.phi_deg() - plant.theta_deg(), 0.75, 1e-12);
}

TEST(Plant, ClampsAtTheEndStopAndReportsStallWhilePowered) {
  const AxisProfile& az = profile_axis("g5500", false);
  AxisPlant plant(az.plant);
  EXPECT_EQ(az.plant.stop_max_deg, 453.0);
  plant.set_theta_deg(448.0);
  const auto cw = outputs_with(OutputChannel::kRelayCw);
  run(plant, cw, 5.0);
  EXPECT_EQ(plant.theta_deg(), 453.0);
  EXPECT_EQ(plant.w_deg_s(), 0.0);
  EXPECT_TRUE(plant.powered());
  EXPECT_TRUE(plant.stalled());
  run(plant, DriveOutputs{}, 0.02);
  EXPECT_FALSE(plant.stalled());
  EXPECT_EQ(plant.theta_deg(), 453.0);
  // Backing off works, after the full gap is taken up: 2 s CCW from rest.
  run(plant, outputs_with(OutputChannel::kRelayCcw), 2.0);
  EXPECT_FALSE(plant.stalled());
  EXPECT_NEAR(plant.theta_deg(), 453.0 - (6.0 * (1.99 - 0.2 * (1.0 - std::exp(-9.95))) - 1.0),
              1e-9);
}

TEST(Plant, ClampsAtTheLowerStop) {
  AxisPlant plant(profile_axis("spid", false).plant);
  plant.set_theta_deg(-178.0);
  run(plant, outputs_with(OutputChannel::kPwmCcw), 3.0);
  EXPECT_EQ(plant.theta_deg(), -183.0);
  EXPECT_TRUE(plant.stalled());
}

TEST(Plant, ContinuousAxisHasNoStops) {
  AxisPlantParams p = profile_axis("spid", false).plant;
  p.continuous = true;
  AxisPlant plant(p);
  plant.set_theta_deg(530.0);
  run(plant, outputs_with(OutputChannel::kPwmCw), 10.0);
  EXPECT_NEAR(plant.theta_deg(), 530.0 + 6.0 * 9.9 - 0.15, 1e-6);
  EXPECT_FALSE(plant.stalled());
}

TEST(Plant, EngagedBrakeHoldsAPoweredMotor) {
  AxisPlant plant(profile_axis("ham4", false).plant);
  plant.set_theta_deg(100.0);
  run(plant, outputs_with(OutputChannel::kRelayCw), 2.0);  // brake not released
  EXPECT_EQ(plant.theta_deg(), 100.0);
  EXPECT_EQ(plant.w_deg_s(), 0.0);
  EXPECT_TRUE(plant.stalled());
}

TEST(Plant, ReleasedBrakeLetsTheMotorRun) {
  const AxisPlantParams& p = profile_axis("ham4", false).plant;
  AxisPlant plant(p);
  plant.set_theta_deg(100.0);
  DriveOutputs run_cw = outputs_with(OutputChannel::kRelayCw);
  run_cw.set(OutputChannel::kBrake, 1.0f);
  run(plant, run_cw, 2.0);
  EXPECT_FALSE(plant.stalled());
  const double t_s = 2.0 - p.relay_delay_s;
  EXPECT_NEAR(plant.theta_deg(), 100.0 + 6.0 * (t_s - 0.25 * (1.0 - std::exp(-t_s / 0.25))) - 0.5,
              1e-9);
}

TEST(Plant, BrakeDroppedOnAMovingBellStopsItInVSquaredOver2A) {
  AxisPlant plant(profile_axis("ham4", false).plant);
  plant.set_theta_deg(100.0);
  DriveOutputs run_cw = outputs_with(OutputChannel::kRelayCw);
  run_cw.set(OutputChannel::kBrake, 1.0f);
  run(plant, run_cw, 5.0);
  run(plant, DriveOutputs{}, 0.010);  // relay delay: power and brake change now
  const double theta_at_cut_deg = plant.theta_deg();
  const double w_at_cut_deg_s = plant.w_deg_s();
  EXPECT_NEAR(w_at_cut_deg_s, 6.0, 1e-6);
  run(plant, DriveOutputs{}, 0.05);
  EXPECT_NEAR(plant.w_deg_s(), w_at_cut_deg_s - 60.0 * 0.05, 1e-9);
  run(plant, DriveOutputs{}, 1.0);
  EXPECT_EQ(plant.w_deg_s(), 0.0);
  // 6^2 / (2 * 60) = 0.3 deg, versus 0.9 deg of free coast.
  EXPECT_NEAR(plant.theta_deg() - theta_at_cut_deg, 0.3, 1e-6);
}

TEST(Plant, JamStopsMotionForItsDurationThenReleases) {
  AxisPlant plant(profile_axis("spid", false).plant);
  plant.set_theta_deg(0.0);
  const auto cw = outputs_with(OutputChannel::kPwmCw);
  run(plant, cw, 2.0);
  plant.jam(1.0);
  const double theta_at_jam_deg = plant.theta_deg();
  run(plant, cw, 0.5);
  EXPECT_EQ(plant.theta_deg(), theta_at_jam_deg);
  EXPECT_EQ(plant.w_deg_s(), 0.0);
  EXPECT_TRUE(plant.jammed());
  EXPECT_TRUE(plant.stalled());
  run(plant, cw, 0.5);
  EXPECT_FALSE(plant.jammed());
  run(plant, cw, 1.0);
  EXPECT_FALSE(plant.stalled());
  // Restarts from rest, backlash still taken up: 1 s of ramp.
  EXPECT_NEAR(plant.theta_deg() - theta_at_jam_deg, 6.0 * (1.0 - 0.1 * (1.0 - std::exp(-10.0))),
              1e-6);
}

TEST(Plant, JammedButUnpoweredIsNotStalled) {
  AxisPlant plant(profile_axis("spid", false).plant);
  plant.jam(kForever_s);
  run(plant, DriveOutputs{}, 0.1);
  EXPECT_FALSE(plant.stalled());
}

TEST(Plant, SlipScalesTheSteadySpeed) {
  AxisPlant plant(profile_axis("spid", false).plant);
  plant.slip(0.5, 10.0);
  run(plant, outputs_with(OutputChannel::kPwmCw), 2.0);
  EXPECT_NEAR(plant.w_deg_s(), 3.0, 1e-6);
  run(plant, outputs_with(OutputChannel::kPwmCw), 9.0);  // slip over after 10 s
  EXPECT_NEAR(plant.w_deg_s(), 6.0 * (1.0 - 0.5 * std::exp(-10.0)), 1e-6);
}

TEST(Plant, TwoSpeedRelayRunsSlowUnlessFastIsOn) {
  AxisPlantParams p = profile_axis("g5500", false).plant;
  p.drive = DriveKind::kRelayTwoSpeed;
  p.slow_speed_ratio = 0.4;
  AxisPlant plant(p);
  DriveOutputs o = outputs_with(OutputChannel::kRelayCw);
  run(plant, o, 4.0);
  EXPECT_NEAR(plant.w_deg_s(), 2.4, 1e-6);
  o.set(OutputChannel::kVoltageFast, 1.0f);  // the other drive's channel: ignored
  run(plant, o, 4.0);
  EXPECT_NEAR(plant.w_deg_s(), 2.4, 1e-6);
  o.set(OutputChannel::kSpeedFast, 1.0f);
  run(plant, o, 4.0);
  EXPECT_NEAR(plant.w_deg_s(), 6.0, 1e-6);
}

TEST(Plant, VoltageSelectRelayCreepsUnlessFastSupplyIsOn) {
  AxisPlantParams p = profile_axis("g5500", false).plant;
  p.drive = DriveKind::kRelayVoltageSelect;
  p.slow_speed_ratio = 0.25;
  AxisPlant plant(p);
  plant.set_theta_deg(200.0);
  DriveOutputs o = outputs_with(OutputChannel::kRelayCcw);
  o.set(OutputChannel::kSpeedFast, 1.0f);  // the other drive's channel: ignored
  run(plant, o, 4.0);
  EXPECT_NEAR(plant.w_deg_s(), -1.5, 1e-6);
  o.set(OutputChannel::kVoltageFast, 1.0f);
  run(plant, o, 4.0);
  EXPECT_NEAR(plant.w_deg_s(), -6.0, 1e-6);
}

TEST(Plant, PwmDeadBandMapping) {
  EXPECT_EQ(pwm_speed_ratio(0.0, 0.3), 0.0);
  EXPECT_EQ(pwm_speed_ratio(0.3, 0.3), 0.0);
  EXPECT_NEAR(pwm_speed_ratio(0.65, 0.3), 0.5, 1e-12);
  EXPECT_NEAR(pwm_speed_ratio(-0.65, 0.3), -0.5, 1e-12);
  EXPECT_NEAR(pwm_speed_ratio(1.0, 0.3), 1.0, 1e-12);
  EXPECT_NEAR(pwm_speed_ratio(1.7, 0.3), 1.0, 1e-12);  // duty is clamped
}

TEST(Plant, PwmBelowTheDeadBandDoesNotTurn) {
  AxisPlant plant(profile_axis("spid", false).plant);
  plant.set_theta_deg(10.0);
  run(plant, outputs_with(OutputChannel::kPwmCw, 0.25f), 2.0);
  EXPECT_TRUE(plant.powered());
  EXPECT_EQ(plant.theta_deg(), 10.0);
  run(plant, outputs_with(OutputChannel::kPwmCw, 0.65f), 2.0);
  EXPECT_NEAR(plant.w_deg_s(), 3.0, 1e-4);  // float duty 0.65f
  DriveOutputs net_ccw = outputs_with(OutputChannel::kPwmCcw, 1.0f);
  net_ccw.set(OutputChannel::kPwmCw, 0.35f);  // net duty -0.65
  run(plant, net_ccw, 2.0);
  EXPECT_NEAR(plant.w_deg_s(), -3.0, 1e-4);
}

}  // namespace
}  // namespace rotord::sim
