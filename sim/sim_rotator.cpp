#include "sim/sim_rotator.hpp"

#include <cmath>

namespace rotord::sim {

namespace {

constexpr double kStep_s = 0.001;

SimPot::Config pot_config(const AxisProfile& a, SensorNoise noise) {
  return {.v0_v = a.pot.v0_v(a.min_deg, a.max_deg),
          .k_v_per_deg = a.pot.k_v_per_deg(a.min_deg, a.max_deg),
          .sigma_v = noise == SensorNoise::kOn ? a.pot.sigma_v : 0.0};
}

// Independent streams per sensor, all from the one user seed.
std::uint64_t part_seed(std::uint64_t seed, std::uint64_t part) {
  return Rng::splitmix64(seed ^ (part * 0xD1B54A32D192ED03ull));
}

}  // namespace

SimRotator::AxisSim::AxisSim(const AxisProfile& p, std::uint64_t seed, SensorNoise noise)
    : profile(p),
      plant(p.plant),
      pot(plant, pot_config(p, noise), part_seed(seed, 1)),
      ma3(plant, noise == SensorNoise::kOn ? p.ma3_sigma_deg : 0.0, part_seed(seed, 2)),
      mag(plant, noise == SensorNoise::kOn ? 2.0 : 0.0, part_seed(seed, 3)),
      limit_cw(plant, SimSwitch::Sense::kAtOrAbove, p.limit_cw_deg),
      limit_ccw(plant, SimSwitch::Sense::kAtOrBelow, p.limit_ccw_deg),
      t1(plant, SimSwitch::Sense::kAtOrAbove, p.t1_above_deg),
      t2(plant, SimSwitch::Sense::kAtOrBelow, p.t2_below_deg) {}

void SimRotator::AxisSim::step_1ms() {
  plant.step(kStep_s, sink.last());
  const double now_s = plant.time_s();
  pot.update(now_s);
  ma3.update(now_s);
  limit_cw.update(now_s);
  limit_ccw.update(now_s);
  t1.update(now_s);
  t2.update(now_s);
}

SimRotator::SimRotator(const Profile& profile, std::uint64_t seed, SensorNoise noise,
                       Millis start_ms)
    : profile_(profile),
      az_(profile.az, Rng::splitmix64(seed), noise),
      el_(profile.el, Rng::splitmix64(seed + 1), noise),
      now_ms_(start_ms) {
  // Start in the middle of the range, the way a rotator usually sits.
  set_theta_deg(AxisId::kAz, 0.5 * (profile.az.min_deg + profile.az.max_deg));
  if (profile.has_el) set_theta_deg(AxisId::kEl, profile.el.min_deg);
}

void SimRotator::advance_to(Millis now_ms) {
  for (; now_ms_ < now_ms; ++now_ms_) {
    az_.step_1ms();
    if (profile_.has_el) el_.step_1ms();
  }
}

AxisIo SimRotator::io(AxisId axis) {
  AxisIo io;
  if (!fitted(axis)) return io;
  AxisSim& s = sim(axis);
  // One model an input, fitted for the input the profile's sensor type
  // reads (its row), never by type: a new type on an input modelled here
  // runs in the simulator as it is. The azimuth's I2C magnetometer is
  // always there, so az.sensor = mag works on any profile.
  switch (sensor_info(s.profile.sensor).input) {
    case SensorInput::kAnalog:
      io.pot = &s.pot;
      break;
    case SensorInput::kPwm:
      io.ma3 = &s.ma3;
      break;
    case SensorInput::kI2c:
      break;
  }
  if (axis == AxisId::kAz) io.i2c = &s.mag;
  if (s.profile.has_limit_switches) {
    io.limit_cw = &s.limit_cw;
    io.limit_ccw = &s.limit_ccw;
  }
  if (s.profile.has_t1) io.t1 = &s.t1;
  if (s.profile.has_t2) io.t2 = &s.t2;
  io.drive = &s.sink;
  return io;
}

const AxisProfile& SimRotator::axis_profile(AxisId axis) const {
  return sim(axis).profile;
}

void SimRotator::set_theta_deg(AxisId axis, double theta_deg) {
  AxisSim& s = sim(axis);
  s.plant.set_theta_deg(theta_deg);
  s.ma3.sample();
}

void SimRotator::set_sensor_mount_deg(AxisId axis, double deg) {
  AxisSim& s = sim(axis);
  s.ma3.set_mount_deg(deg);
  s.mag.set_mount_deg(deg);
  s.ma3.sample();
}

void SimRotator::sensor_loss(AxisId axis, double duration_s) {
  sim(axis).pot.inject_loss(duration_s);
  sim(axis).ma3.inject_loss(duration_s);
}

void SimRotator::sensor_noise_burst(AxisId axis, double sigma_deg, double duration_s) {
  AxisSim& s = sim(axis);
  s.pot.inject_noise_burst(sigma_deg * std::fabs(s.pot.config().k_v_per_deg), duration_s);
  s.ma3.inject_noise_burst(sigma_deg, duration_s);
}

void SimRotator::sensor_stuck(AxisId axis, double duration_s) {
  sim(axis).pot.inject_stuck(duration_s);
  sim(axis).ma3.inject_stuck(duration_s);
}

void SimRotator::limit_switch_stuck(AxisId axis, bool cw, bool state, double duration_s) {
  AxisSim& s = sim(axis);
  (cw ? s.limit_cw : s.limit_ccw).inject_stuck(state, duration_s);
}

void SimRotator::clear_faults(AxisId axis) {
  AxisSim& s = sim(axis);
  s.plant.clear_faults();
  s.pot.clear_faults();
  s.ma3.clear_faults();
  s.limit_cw.clear_faults();
  s.limit_ccw.clear_faults();
}

}  // namespace rotord::sim
