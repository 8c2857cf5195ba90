// Profiles and the whole simulated rotator (wiring, virtual time, faults).
#include "sim/sim_rotator.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <set>
#include <string>
#include <vector>

#include "sim/adc_scale.hpp"

namespace rotord::sim {
namespace {

const Profile& profile(const char* name) {
  const Profile* p = find_profile(name);
  EXPECT_NE(p, nullptr) << name;
  return *p;
}

double override_value(const Profile& p, const char* key) {
  for (const auto& o : p.overrides) {
    if (std::strcmp(o.key, key) == 0) return o.value;
  }
  ADD_FAILURE() << "no override " << key << " in " << p.name;
  return NAN;
}

bool has_override(const Profile& p, const char* key) {
  for (const auto& o : p.overrides) {
    if (std::strcmp(o.key, key) == 0) return true;
  }
  return false;
}

// The controller's two-point pot calibration, as the overrides describe it.
double pot_deg(const Profile& p, const char* axis, double counts) {
  const std::string a(axis);
  const double lo_c = override_value(p, (a + ".pot_cal_lo_counts").c_str());
  const double lo_d = override_value(p, (a + ".pot_cal_lo_deg").c_str());
  const double hi_c = override_value(p, (a + ".pot_cal_hi_counts").c_str());
  const double hi_d = override_value(p, (a + ".pot_cal_hi_deg").c_str());
  return lo_d + (counts - lo_c) * (hi_d - lo_d) / (hi_c - lo_c);
}

TEST(Profiles, FindByName) {
  EXPECT_EQ(all_profiles().size(), 3u);
  for (const Profile* p : all_profiles()) EXPECT_EQ(find_profile(p->name), p);
  EXPECT_EQ(find_profile("nope"), nullptr);
  EXPECT_NE(find_profile(kDefaultProfileName), nullptr);
}

TEST(Profiles, OverridesUseOnlyTheControllersKeys) {
  const std::set<std::string> allowed = {"el.enabled",
                                         "az.min_deg",
                                         "az.max_deg",
                                         "el.min_deg",
                                         "el.max_deg",
                                         "az.drive",
                                         "el.drive",
                                         "az.has_brake",
                                         "az.sensor",
                                         "el.sensor",
                                         "az.pot_cal_lo_counts",
                                         "az.pot_cal_lo_deg",
                                         "az.pot_cal_hi_counts",
                                         "az.pot_cal_hi_deg",
                                         "el.pot_cal_lo_counts",
                                         "el.pot_cal_lo_deg",
                                         "el.pot_cal_hi_counts",
                                         "el.pot_cal_hi_deg",
                                         "az.ma3_zero_deg",
                                         "el.ma3_zero_deg"};
  for (const Profile* p : all_profiles()) {
    std::set<std::string> seen;
    for (const auto& o : p->overrides) {
      EXPECT_TRUE(allowed.count(o.key)) << p->name << ": " << o.key;
      EXPECT_TRUE(seen.insert(o.key).second) << p->name << " repeats " << o.key;
    }
  }
}

TEST(Profiles, G5500) {
  const Profile& p = profile("g5500");
  EXPECT_TRUE(p.has_el);
  EXPECT_EQ(override_value(p, "el.enabled"), 1.0);
  EXPECT_EQ(override_value(p, "az.min_deg"), 0.0);
  EXPECT_EQ(override_value(p, "az.max_deg"), 450.0);
  EXPECT_EQ(override_value(p, "el.max_deg"), 180.0);
  EXPECT_EQ(override_value(p, "az.drive"), 0.0);
  EXPECT_EQ(override_value(p, "el.drive"), 0.0);
  EXPECT_EQ(override_value(p, "az.has_brake"), 0.0);
  EXPECT_EQ(override_value(p, "az.sensor"), 0.0);
  EXPECT_NEAR(override_value(p, "az.pot_cal_lo_counts"), 0.05 / 3.3 * 4095, 1e-9);
  EXPECT_NEAR(override_value(p, "az.pot_cal_hi_counts"), 3.0 / 3.3 * 4095, 1e-9);
  EXPECT_EQ(override_value(p, "az.pot_cal_hi_deg"), 450.0);
  EXPECT_EQ(override_value(p, "el.pot_cal_hi_deg"), 180.0);
  EXPECT_FALSE(has_override(p, "az.ma3_zero_deg"));
  EXPECT_EQ(p.az.plant.v_max_deg_s, 6.0);
  EXPECT_EQ(p.el.plant.v_max_deg_s, 2.7);
  EXPECT_EQ(p.az.plant.stop_min_deg, -3.0);
  EXPECT_EQ(p.az.plant.stop_max_deg, 453.0);
  EXPECT_EQ(p.az.limit_cw_deg, 451.0);
  EXPECT_EQ(p.az.limit_ccw_deg, -1.0);
}

TEST(Profiles, Ham4) {
  const Profile& p = profile("ham4");
  EXPECT_FALSE(p.has_el);
  EXPECT_EQ(override_value(p, "el.enabled"), 0.0);
  EXPECT_EQ(override_value(p, "az.max_deg"), 360.0);
  EXPECT_EQ(override_value(p, "az.has_brake"), 1.0);
  EXPECT_EQ(override_value(p, "az.drive"), 0.0);
  EXPECT_FALSE(has_override(p, "el.max_deg"));
  EXPECT_TRUE(p.az.plant.has_brake);
  EXPECT_EQ(p.az.plant.tau_c_s, 0.15);
}

TEST(Profiles, Spid) {
  const Profile& p = profile("spid");
  EXPECT_TRUE(p.has_el);
  EXPECT_EQ(override_value(p, "az.min_deg"), -180.0);
  EXPECT_EQ(override_value(p, "az.max_deg"), 540.0);
  EXPECT_EQ(override_value(p, "az.drive"), 3.0);
  EXPECT_EQ(override_value(p, "el.drive"), 3.0);
  EXPECT_EQ(override_value(p, "az.sensor"), 1.0);
  EXPECT_EQ(override_value(p, "el.sensor"), 1.0);
  EXPECT_EQ(override_value(p, "az.ma3_zero_deg"), 0.0);
  EXPECT_FALSE(has_override(p, "az.pot_cal_lo_counts"));
  EXPECT_EQ(p.az.plant.pwm_dead_band, 0.30);
  EXPECT_EQ(p.az.plant.relay_delay_s, 0.0);
}

TEST(Profiles, PotCalibrationOverridesReadTheTrueAngle) {
  for (const char* name : {"g5500", "ham4"}) {
    SCOPED_TRACE(name);
    SimRotator rot(profile(name), 1, SensorNoise::kOff);
    for (double theta_deg : {0.0, 17.3, 123.4, 359.0}) {
      rot.set_theta_deg(AxisId::kAz, theta_deg);
      const double counts = rot.io(AxisId::kAz).pot->read_counts();
      // Only the converter's rounding remains: half a count.
      const AxisProfile& a = rot.axis_profile(AxisId::kAz);
      const double half_count_deg = 0.5 * kAdcLsb_v / a.pot.k_v_per_deg(a.min_deg, a.max_deg);
      EXPECT_NEAR(pot_deg(profile(name), "az", counts), theta_deg, half_count_deg + 1e-9);
    }
  }
  SimRotator rot(profile("g5500"), 1, SensorNoise::kOff);
  rot.set_theta_deg(AxisId::kEl, 63.0);
  EXPECT_NEAR(pot_deg(profile("g5500"), "el", rot.io(AxisId::kEl).pot->read_counts()), 63.0, 0.025);
}

TEST(SimRotator, WiringFollowsTheProfile) {
  SimRotator g5500(profile("g5500"), 1);
  const AxisIo az = g5500.io(AxisId::kAz);
  EXPECT_NE(az.pot, nullptr);
  EXPECT_EQ(az.ma3, nullptr);
  EXPECT_NE(az.limit_cw, nullptr);
  EXPECT_NE(az.limit_ccw, nullptr);
  EXPECT_NE(az.t1, nullptr);  // 360..450 overlap
  EXPECT_EQ(az.t2, nullptr);  // nothing below 0
  EXPECT_NE(az.drive, nullptr);
  const AxisIo el = g5500.io(AxisId::kEl);
  EXPECT_NE(el.pot, nullptr);
  EXPECT_EQ(el.t1, nullptr);
  EXPECT_EQ(el.t2, nullptr);

  SimRotator ham4(profile("ham4"), 1);
  EXPECT_FALSE(ham4.has_el());
  EXPECT_EQ(ham4.io(AxisId::kAz).t1, nullptr);
  EXPECT_EQ(ham4.io(AxisId::kAz).t2, nullptr);
  const AxisIo none = ham4.io(AxisId::kEl);
  EXPECT_EQ(none.pot, nullptr);
  EXPECT_EQ(none.limit_cw, nullptr);
  EXPECT_EQ(none.drive, nullptr);

  SimRotator spid(profile("spid"), 1);
  const AxisIo spid_az = spid.io(AxisId::kAz);
  EXPECT_EQ(spid_az.pot, nullptr);
  EXPECT_NE(spid_az.ma3, nullptr);
  EXPECT_NE(spid_az.t1, nullptr);
  EXPECT_NE(spid_az.t2, nullptr);
}

TEST(SimRotator, OverlapAndLimitSwitches) {
  SimRotator rot(profile("spid"), 1, SensorNoise::kOff);
  const AxisIo io = rot.io(AxisId::kAz);
  rot.set_theta_deg(AxisId::kAz, 370.0);
  EXPECT_TRUE(io.t1->active());
  EXPECT_FALSE(io.t2->active());
  rot.set_theta_deg(AxisId::kAz, -5.0);
  EXPECT_FALSE(io.t1->active());
  EXPECT_TRUE(io.t2->active());
  rot.set_theta_deg(AxisId::kAz, 180.0);
  EXPECT_FALSE(io.t1->active());
  EXPECT_FALSE(io.t2->active());
  EXPECT_FALSE(io.limit_cw->active());
  rot.set_theta_deg(AxisId::kAz, 541.5);
  EXPECT_TRUE(io.limit_cw->active());
  rot.set_theta_deg(AxisId::kAz, -181.5);
  EXPECT_TRUE(io.limit_ccw->active());
  rot.limit_switch_stuck(AxisId::kAz, false, false, kForever_s);
  EXPECT_FALSE(io.limit_ccw->active());
}

TEST(SimRotator, RunsTheAppliedOutputsInVirtualTime) {
  SimRotator rot(profile("g5500"), 1, SensorNoise::kOff, 5000);
  rot.set_theta_deg(AxisId::kAz, 100.0);
  rot.set_theta_deg(AxisId::kEl, 45.0);
  DriveOutputs cw;
  cw.set(OutputChannel::kRelayCw, 1.0f);
  rot.io(AxisId::kAz).drive->apply(cw);
  rot.io(AxisId::kEl).drive->apply(cw);
  rot.advance_to(15000);  // 10 s
  EXPECT_EQ(rot.now_ms(), 15000);
  rot.io(AxisId::kAz).drive->apply(DriveOutputs{});
  rot.io(AxisId::kEl).drive->apply(DriveOutputs{});
  rot.advance_to(18000);
  rot.advance_to(17000);  // going back in time is ignored
  EXPECT_EQ(rot.now_ms(), 18000);
  // Same numbers as the shared step reference.
  EXPECT_NEAR(rot.plant(AxisId::kAz).theta_deg(), 159.2, 1e-3);
  EXPECT_NEAR(rot.plant(AxisId::kEl).theta_deg(), 70.98, 1e-3);
  EXPECT_TRUE(rot.outputs(AxisId::kAz).value == DriveOutputs{}.value);
}

TEST(SimRotator, Ma3FollowsTheAxisThroughTheRefresh) {
  SimRotator rot(profile("spid"), 1, SensorNoise::kOff);
  rot.set_theta_deg(AxisId::kAz, -90.0);
  const hal::PwmPeriod p = rot.io(AxisId::kAz).ma3->read();
  ASSERT_TRUE(p.valid);
  EXPECT_EQ(p.high_us, 3073u);  // 270 deg -> code 3072
}

// A fixed drive schedule and the pot codes read every 10 ms.
std::vector<std::uint16_t> pot_trace(std::uint64_t seed) {
  SimRotator rot(profile("g5500"), seed);
  const AxisIo az = rot.io(AxisId::kAz);
  std::vector<std::uint16_t> trace;
  for (Millis t_ms = 0; t_ms <= 8000; t_ms += 10) {
    rot.advance_to(t_ms);
    DriveOutputs o;
    if (t_ms >= 1000 && t_ms < 4000) o.set(OutputChannel::kRelayCw, 1.0f);
    if (t_ms >= 5000 && t_ms < 6000) o.set(OutputChannel::kRelayCcw, 1.0f);
    az.drive->apply(o);
    if (t_ms == 2000) rot.sensor_noise_burst(AxisId::kAz, 5.0, 0.5);
    trace.push_back(az.pot->read_counts());
  }
  return trace;
}

TEST(SimRotator, SameSeedSameTrace) {
  const auto a = pot_trace(42);
  const auto b = pot_trace(42);
  const auto c = pot_trace(43);
  ASSERT_EQ(a.size(), 801u);
  EXPECT_EQ(a, b);
  EXPECT_NE(a, c);
  // The axis moved: 3 s CW at 6 deg/s is ~16 deg, ~134 counts.
  EXPECT_GT(a[400] - a[0], 120);
}

TEST(SimRotator, SensorLossAndRecovery) {
  SimRotator g5500(profile("g5500"), 1, SensorNoise::kOff);
  g5500.advance_to(1000);
  g5500.sensor_loss(AxisId::kAz, 2.0);
  EXPECT_EQ(g5500.io(AxisId::kAz).pot->read_counts(), 0);
  EXPECT_EQ(g5500.io(AxisId::kEl).pot->read_counts(), 62);  // other axis unaffected: el 0 deg
  g5500.advance_to(3000);
  EXPECT_EQ(g5500.io(AxisId::kAz).pot->read_counts(), 1892);  // parked mid-range, 225 deg

  SimRotator spid(profile("spid"), 1, SensorNoise::kOff);
  spid.sensor_loss(AxisId::kEl, kForever_s);
  EXPECT_FALSE(spid.io(AxisId::kEl).ma3->read().valid);
  EXPECT_TRUE(spid.io(AxisId::kAz).ma3->read().valid);
  spid.clear_faults(AxisId::kEl);
  EXPECT_TRUE(spid.io(AxisId::kEl).ma3->read().valid);
}

TEST(SimRotator, JamHelperStallsThePoweredAxis) {
  SimRotator rot(profile("spid"), 1, SensorNoise::kOff);
  rot.set_theta_deg(AxisId::kAz, 10.0);
  rot.jam(AxisId::kAz, 2.0);
  DriveOutputs cw;
  cw.set(OutputChannel::kPwmCw, 1.0f);
  rot.io(AxisId::kAz).drive->apply(cw);
  rot.advance_to(1500);
  EXPECT_EQ(rot.plant(AxisId::kAz).theta_deg(), 10.0);
  EXPECT_TRUE(rot.plant(AxisId::kAz).stalled());
  rot.advance_to(3000);
  EXPECT_FALSE(rot.plant(AxisId::kAz).stalled());
  EXPECT_GT(rot.plant(AxisId::kAz).theta_deg(), 15.0);
}

}  // namespace
}  // namespace rotord::sim
