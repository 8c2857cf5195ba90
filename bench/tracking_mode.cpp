// Tracking quality on the simulator (issue 13): the scenarios of
// tests/sim/scenario_tracking_test.cpp, reporting the pointing error against
// the true target once a second from AOS to LOS (great-circle; only the
// elevation error above 80 deg, where the azimuth is ill-conditioned), the
// motor starts during the pass, and the cost of a tick while tracking. Each
// scenario also runs with the followers' lead off (AxisFollow::lead_bands
// 0: the antenna stops on the target and starts once it is a band away, a
// sawtooth of 0..band) and with both axes' tolerance at 2 deg instead of 1,
// so the starts the lead saves and what halving them again costs stand
// beside each other (docs/tracking.md, "Fewer motor starts").
#include <chrono>
#include <cmath>
#include <memory>

#include "rotator/controller.hpp"
#include "sim/profiles.hpp"
#include "sim/sim_rotator.hpp"
#include "sky_pass.hpp"
#include "tracking/julian.hpp"
#include "tracking_mode.hpp"

namespace rotord::bench {
namespace {

using settings::Id;

struct Scenario {
  const char* profile;
  const char* start_utc;
  double lat, lon, alt, az0, el0;
  bool sun;
  double el_max;  // 0: the profile's
  Millis run_ms;  // 0: until the pass is done
};

struct Measured {
  double rms = 0, max_err = 0, starts = 0, tick_us = 0;
};

/// One run of `sc`; `lead_bands` as AxisFollow::lead_bands, `tolerance_deg`
/// (> 0) for both axes instead of the profile's.
Measured measure(const Scenario& sc, float lead_bands, double tolerance_deg) {
  double rms = 0, max_err = 0, starts = 0, tick_us = 0;
  {
    const sim::Profile& p = *sim::find_profile(sc.profile);
    settings::Settings settings;
    for (const auto& o : p.overrides) settings.set(*settings::find(o.key), o.value);
    settings.set(Id::kStationLatDeg, sc.lat);
    settings.set(Id::kStationLonDeg, sc.lon);
    settings.set(Id::kStationAltM, sc.alt);
    if (sc.el_max > 0) settings.set(Id::kElMaxDeg, sc.el_max);
    if (tolerance_deg > 0) {
      settings.set(Id::kAzToleranceDeg, tolerance_deg);
      settings.set(Id::kElToleranceDeg, tolerance_deg);
    }
    sim::SimRotator sim(p, 7);
    sim.set_theta_deg(AxisId::kAz, sc.az0);
    sim.set_theta_deg(AxisId::kEl, sc.el0);
    Millis now = 0;
    std::int64_t start = 0;
    tracking::parse_utc(sc.start_utc, start);
    VirtualUtc utc(start, &now);
    Controller c(settings, sim.io(AxisId::kAz), sim.io(AxisId::kEl));
    c.attach_utc_clock(&utc);
    c.set_follow_lead(lead_bands);
    c.begin(now);
    TrackRequest r;
    tracking::SkyTarget truth;
    if (sc.sun) {
      r.kind = tracking::TargetKind::kSun;
      r.when = TrackWhen::kNow;
      truth.set_body(tracking::Body::kSun);
    } else {
      r.kind = tracking::TargetKind::kSatellite;
      tracking::parse_tle(kIss1, kIss2, r.tle);
      truth.set_satellite(r.tle);
    }
    c.track(r);
    double sum = 0;
    int n = 0;
    std::uint32_t starts_at_aos = 0;
    bool in_pass = false;
    long tracking_ticks = 0;
    double tracking_s = 0;
    for (Millis t = 0; t < 3 * 3600 * 1000; t += 10) {
      now += 10;
      sim.advance_to(now);
      const auto t0 = std::chrono::steady_clock::now();
      c.tick(now);
      const TrackStatus& ts = c.track_status();
      if (ts.phase == TrackPhase::kTracking) {
        tracking_s += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        ++tracking_ticks;
        const RotatorStatus s = c.status();
        if (!in_pass) starts_at_aos = s.az.moves + s.el.moves;
        in_pass = true;
        starts = s.az.moves + s.el.moves - starts_at_aos;
        if (now % 1000 == 0) {
          tracking::LookAngles look;
          truth.look(start + now, c.observer(), look);
          if (look.el_deg >= 0) {
            const double e =
                pointing_error(sim.plant(AxisId::kAz).theta_deg(),
                               sim.plant(AxisId::kEl).theta_deg(), look.az_deg, look.el_deg);
            sum += e * e;
            ++n;
            max_err = std::fmax(max_err, e);
          }
        }
      }
      if (!ts.armed() || (sc.run_ms > 0 && in_pass && tracking_ticks * 10 >= sc.run_ms)) break;
    }
    rms = n > 0 ? std::sqrt(sum / n) : 0;
    tick_us = tracking_ticks > 0 ? 1e6 * tracking_s / static_cast<double>(tracking_ticks) : 0;
  }
  return {rms, max_err, starts, tick_us};
}

Result run_one(const char* name, const Scenario& sc) {
  const Measured today = measure(sc, 0.8f, 0.0);
  const Measured no_lead = measure(sc, 0.0f, 0.0);
  const Measured tol2 = measure(sc, 0.8f, 2.0);
  return {std::string("tracking_mode/") + name,
          {{"lat_deg", sc.lat}, {"az0_deg", sc.az0}, {"el0_deg", sc.el0}},
          {{"rms_error_deg", today.rms},
           {"max_error_deg", today.max_err},
           {"motor_starts", today.starts},
           {"tick_us_tracking", today.tick_us},
           {"rms_error_deg_no_lead", no_lead.rms},
           {"max_error_deg_no_lead", no_lead.max_err},
           {"motor_starts_no_lead", no_lead.starts},
           {"rms_error_deg_tol2", tol2.rms},
           {"max_error_deg_tol2", tol2.max_err},
           {"motor_starts_tol2", tol2.starts}}};
}

}  // namespace

std::vector<Result> run_tracking_mode() {
  return {
      run_one("g5500_iss_87deg_flipped", Scenario{"g5500", "2019-12-09T19:15:00Z", 39.86366,
                                                  -119.17875, 0, 50, 90, false, 0, 0}),
      run_one("g5500_450_iss_through_north", Scenario{"g5500", "2019-12-09T22:30:00Z", 40.015,
                                                      -105.27, 1655, 30, 0, false, 90, 0}),
      run_one("spid_iss_85deg",
              Scenario{"spid", "2019-12-09T14:45:00Z", 51.5, 0, 0, -100, 10, false, 0, 0}),
      run_one("g5500_sun_1h", Scenario{"g5500", "2019-12-09T17:00:00Z", 40.015, -105.27, 1655, 150,
                                       20, true, 0, 3600 * 1000}),
  };
}

}  // namespace rotord::bench
