#include "care.hpp"

#include <algorithm>
#include <cmath>
#include <memory>

#include "rotator/controller.hpp"
#include "sim/anemometer.hpp"
#include "sim/profiles.hpp"
#include "sim/rng.hpp"
#include "sim/sim_rotator.hpp"

namespace rotord::bench {
namespace {

constexpr Millis kTickMs = 10;
constexpr Millis kDayMs = 24LL * 3600 * 1000;
constexpr Millis kGotoEveryMs = 10 * 60 * 1000;
constexpr Millis kGustEveryMs = 90 * 1000;
constexpr double kPulsesPerMps = 1.5;  // wind.pulses_per_mps's default

bool sensor_fault(AxisFault f) {
  return f == AxisFault::kSensorLost || f == AxisFault::kSensorRange ||
         f == AxisFault::kSensorJump || f == AxisFault::kSensorStuck || f == AxisFault::kNoSensor;
}

/// The profile's settings; with `wind_stow`, the wind stow on an anemometer,
/// stowing at 90 deg (wind.stow_mps 20 for wind.hold_s 10, the defaults).
settings::Settings profile_settings(const sim::Profile& profile, bool wind_stow) {
  settings::Settings settings;
  for (const auto& o : profile.overrides) settings.set(*settings::find(o.key), o.value);
  if (wind_stow) {
    settings.set(settings::Id::kWindSource, 2);
    settings.set(settings::Id::kWindStowAzDeg, 90);
  }
  return settings;
}

/// A profile's simulated rotator at `az_deg` with its settings: built before
/// the controller (Stand), which reads the sensors as it starts.
struct Plant {
  Plant(const char* name, double az_deg, bool wind_stow)
      : profile(*sim::find_profile(name)),
        settings(profile_settings(profile, wind_stow)),
        rotator(profile, 27) {
    rotator.set_theta_deg(AxisId::kAz, az_deg);
  }
  const sim::Profile& profile;
  settings::Settings settings;
  sim::Anemometer anemometer{kPulsesPerMps};
  sim::SimRotator rotator;
};

/// The plant and its controller, begun at 0 ms; with `wind_stow` the
/// anemometer feeds the controller's wind input. Each run ticks it its way.
struct Stand : Plant {
  Stand(const char* name, double az_deg, bool wind_stow)
      : Plant(name, az_deg, wind_stow),
        c(settings, rotator.io(AxisId::kAz), rotator.io(AxisId::kEl)) {
    if (wind_stow) c.attach_wind_pulses(&anemometer);
    c.begin(0);
  }
  Controller c;
};

Result run_day(const char* name) {
  // The day's wind stays below the stow's threshold.
  Stand stand(name, 180.0, true);
  const sim::Profile& profile = stand.profile;
  sim::Anemometer& anemometer = stand.anemometer;
  sim::SimRotator& rotator = stand.rotator;
  Controller& c = stand.c;
  double wind_peak_mps = 0.0;
  Millis gust_ends_at = 0;
  Millis now = 0;
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
    // A breeze of 4..12 m/s changing every 20 s; each gust 14..19.5 m/s for
    // 3..15 s (wind.hold_s is 10: long gusts pass the hold, never the speed).
    if (now % 20000 == 0 && now >= gust_ends_at) anemometer.set_wind_mps(4.0 + 8.0 * rng.uniform());
    if (now % kGustEveryMs == 0) {
      anemometer.set_wind_mps(14.0 + 5.5 * rng.uniform());
      gust_ends_at = now + 3000 + static_cast<Millis>(12000 * rng.uniform());
    }
    if (now == gust_ends_at) anemometer.set_wind_mps(4.0 + 8.0 * rng.uniform());
    wind_peak_mps = std::max(wind_peak_mps, anemometer.wind_mps());
    anemometer.advance_to(now);
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
          {{"hours", 24.0},
           {"gotos", gotos},
           {"gusts_at_rest", gusts},
           {"wind_peak_mps", wind_peak_mps},
           {"wind_stow_mps", 20.0}},
          {{"false_slips", slips},
           {"false_stows", static_cast<double>(s.wind_stows)},
           {"false_sensor_faults", sensor_faults},
           {"faults", faults},
           {"readings_rejected",
            static_cast<double>(s.az.readings_rejected + s.el.readings_rejected)}}};
}

/// A storm on the anemometer: 8 m/s, then 25 m/s against the motor (its
/// torque costs 30 % of the speed). How long after the wind held 20 m/s for
/// wind.hold_s the stow began (the motor started), and reached the heading.
Result run_storm(const char* name) {
  Stand stand(name, 250.0, true);
  sim::Anemometer& anemometer = stand.anemometer;
  sim::SimRotator& rotator = stand.rotator;
  Controller& c = stand.c;
  Millis now = 0;
  constexpr Millis kStormAtMs = 60000;
  constexpr Millis kHeldAtMs = kStormAtMs + 10000;  // wind.hold_s after the storm began
  anemometer.set_wind_mps(8.0);
  Millis began_ms = -1, arrived_ms = -1;
  for (now = kTickMs; now <= kStormAtMs + 180000 && arrived_ms < 0; now += kTickMs) {
    if (now == kStormAtMs) {
      anemometer.set_wind_mps(25.0);
      rotator.slip(AxisId::kAz, 0.7, 180.0);
    }
    anemometer.advance_to(now);
    rotator.advance_to(now);
    c.tick(now);
    const AxisStatus& az = c.status().az;
    if (began_ms < 0 && (az.state == AxisState::kStarting || az.state == AxisState::kMoving))
      began_ms = now;
    if (began_ms > 0 && az.state == AxisState::kIdle && std::fabs(az.position_deg - 90.0f) < 1.5f)
      arrived_ms = now;
  }
  return {std::string("care/wind_stow/") + name,
          {{"wind_mps", 25.0}, {"wind_stow_mps", 20.0}, {"hold_s", 10.0}, {"turn_deg", 160.0}},
          {{"stow_began_after_hold_ms", static_cast<double>(began_ms - kHeldAtMs)},
           {"stowed_after_hold_s", static_cast<double>(arrived_ms - kHeldAtMs) / 1000.0}}};
}

/// A slip of 2 deg in 0.5 s against the brake (a Ham IV at rest): how long
/// after it began the slip was flagged.
Result run_slip() {
  Stand stand("ham4", 200.0, false);
  sim::SimRotator& rotator = stand.rotator;
  Controller& c = stand.c;
  Millis now = 0;
  constexpr Millis kSlipAtMs = 5000;
  Millis flagged_ms = -1;
  for (now = kTickMs; now <= kSlipAtMs + 5000 && flagged_ms < 0; now += kTickMs) {
    if (now == kSlipAtMs) rotator.wind_slip(AxisId::kAz, 4.0, 0.5);
    rotator.advance_to(now);
    c.tick(now);
    if (c.status().az.slips > 0) flagged_ms = now - kSlipAtMs;
  }
  return {"care/slip_flagged/ham4",
          {{"slip_deg", 2.0}, {"slip_s", 0.5}},
          {{"flagged_after_ms", static_cast<double>(flagged_ms)}}};
}

}  // namespace

std::vector<Result> run_care_day() {
  std::vector<Result> rows;
  for (const char* name : {"g5500", "spid", "ham4"}) rows.push_back(run_day(name));
  for (const char* name : {"g5500", "spid", "ham4"}) rows.push_back(run_storm(name));
  rows.push_back(run_slip());
  return rows;
}

}  // namespace rotord::bench
