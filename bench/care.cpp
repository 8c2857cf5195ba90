#include "care.hpp"

#include <memory>

#include "rotator/controller.hpp"
#include "sim/profiles.hpp"
#include "sim/rng.hpp"
#include "sim/sim_rotator.hpp"

namespace rotord::bench {
namespace {

constexpr Millis kTickMs = 10;
constexpr Millis kDayMs = 24LL * 3600 * 1000;
constexpr Millis kGotoEveryMs = 10 * 60 * 1000;
constexpr Millis kGustEveryMs = 90 * 1000;

bool sensor_fault(AxisFault f) {
  return f == AxisFault::kSensorLost || f == AxisFault::kSensorRange ||
         f == AxisFault::kSensorJump || f == AxisFault::kSensorStuck || f == AxisFault::kNoSensor;
}

Result run_day(const char* name) {
  const sim::Profile& profile = *sim::find_profile(name);
  settings::Settings settings;
  for (const auto& o : profile.overrides) settings.set(*settings::find(o.key), o.value);
  sim::SimRotator rotator(profile, 27);
  rotator.set_theta_deg(AxisId::kAz, 180.0);
  Controller c(settings, rotator.io(AxisId::kAz), rotator.io(AxisId::kEl));
  Millis now = 0;
  c.begin(now);
  sim::Rng rng(2027);
  double slips = 0, sensor_faults = 0, faults = 0, gusts = 0, gotos = 0;
  AxisFault seen_az = AxisFault::kNone, seen_el = AxisFault::kNone;
  double gust_from_deg = 0.0;  // the mast springs back after a gust
  std::uint32_t gust_moves = 0;
  Millis spring_back_at = -1;
  for (now = kTickMs; now <= kDayMs; now += kTickMs) {
    if (now % kGotoEveryMs == 0) {
      const auto az = static_cast<float>(profile.az.min_deg +
                                         rng.uniform() * (profile.az.max_deg - profile.az.min_deg));
      std::optional<float> el;
      if (rotator.has_el()) el = static_cast<float>(5.0 + rng.uniform() * 80.0);
      if (c.go_to(az, el, AzTarget::kUnwrapped) == Error::kOk) ++gotos;
    }
    if (now % kGustEveryMs == 0) {
      // Below every threshold. Turning, the wind costs the motor up to 30 %
      // of its speed for 5 s; at rest it twists the mast by at most 1 deg
      // (slip.deg is 2), which springs back 5 s later unless a move came
      // in between.
      rotator.slip(AxisId::kAz, 0.7 + 0.3 * rng.uniform(), 5.0);
      const RotatorStatus s = c.status();
      if (!s.moving() && !s.az.has_target) {
        const double speed_deg_s = (rng.uniform() < 0.5 ? -1.0 : 1.0) * (0.2 + 0.3 * rng.uniform());
        rotator.wind_slip(AxisId::kAz, speed_deg_s, 2.0);
        gust_from_deg = rotator.plant(AxisId::kAz).theta_deg();
        gust_moves = s.az.moves;
        spring_back_at = now + 5000;
        ++gusts;
      }
    }
    if (now == spring_back_at) {
      const double off_deg = rotator.plant(AxisId::kAz).theta_deg() - gust_from_deg;
      if (c.status().az.moves == gust_moves) rotator.wind_slip(AxisId::kAz, -off_deg / 2.0, 2.0);
    }
    rotator.advance_to(now);
    c.tick(now);
    const RotatorStatus s = c.status();
    for (auto [fault, seen] : {std::pair{s.az.fault, &seen_az}, std::pair{s.el.fault, &seen_el}}) {
      if (fault == *seen) continue;
      *seen = fault;
      if (fault == AxisFault::kNone) continue;
      ++faults;
      if (sensor_fault(fault)) ++sensor_faults;
    }
    if (s.any_fault()) (void)c.reset();
  }
  const RotatorStatus s = c.status();
  slips = static_cast<double>(s.az.slips + s.el.slips);
  return {std::string("care/day_unattended/") + name,
          {{"hours", 24.0}, {"gotos", gotos}, {"gusts_at_rest", gusts}},
          {{"false_slips", slips},
           {"false_sensor_faults", sensor_faults},
           {"faults", faults},
           {"readings_rejected",
            static_cast<double>(s.az.readings_rejected + s.el.readings_rejected)}}};
}

}  // namespace

std::vector<Result> run_care_day() {
  std::vector<Result> rows;
  for (const char* name : {"g5500", "spid", "ham4"}) rows.push_back(run_day(name));
  return rows;
}

}  // namespace rotord::bench
