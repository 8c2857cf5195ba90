// The lead rule for go-to streams (docs/tracking.md, "Fewer motor starts")
// and flip passes as the clients send them, on the physics simulator in
// virtual time: the clients modelled from their sources
// (bench/tracker_clients.hpp: Gpredict, the SatNOGS client, a SatDump-like
// one) follow real ISS passes (SGP4) through a rotctld session.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>

#include "../unit/iss_elements.hpp"
#include "bench/sky_angle.hpp"
#include "bench/tracker_clients.hpp"
#include "protocol/rotctld_session.hpp"
#include "rotator/controller.hpp"
#include "sim/profiles.hpp"
#include "sim/sim_rotator.hpp"
#include "tracking/julian.hpp"
#include "tracking/pass_finder.hpp"
#include "tracking/sky_target.hpp"
#include "tracking/tle.hpp"

namespace rotord {
namespace {

using bench::ClientKind;
using bench::ClientPass;
using bench::SkyAzEl;
using bench::TrackerClient;
using settings::Id;
constexpr double kPi = 3.14159265358979323846;

constexpr const char* kIss1 = testing::kIssLine1;
constexpr const char* kIss2 = testing::kIssLine2;

/// A pass: where, and the first ISS pass after `from_utc`.
struct PassSpec {
  double lat_deg, lon_deg, alt_m;
  const char* from_utc;
};
/// Boulder, 2019-12-09 22:3x: 312 -> 74 through north, max el 14 (the
/// continuity rule's pass).
constexpr PassSpec kThroughNorth{40.015, -105.27, 1655.0, "2019-12-09T22:30:00Z"};
/// West of Reno, 2019-12-09 19:2x: max el 82, through north (bench row
/// clients/.../flip): Gpredict flips it, and the SatNOGS client too (>= 75).
constexpr PassSpec kHighThroughNorth{39.86366, -118.42875, 0.0, "2019-12-09T19:10:00Z"};

/// What one client's pass did.
struct PassRun {
  int starts = 0;                   ///< motor starts of both axes, AOS..LOS
  double rms_deg = 0, max_deg = 0;  ///< pointing error against the satellite
  double max_from_wanted_deg = 0;   ///< against where the client wanted the antenna
  double max_own_deg = 0;           ///< where the client wanted it, against the satellite
  double az_min = 1e9, az_max = -1e9, el_min = 1e9, el_max = -1e9;
  double longest_az_run_deg = 0;  ///< the longest one-way azimuth run (an unwind > 200)
  int limit_ticks = 0;
  int commands = 0, refused = 0;
};

/// The pointing error: the angle on the sky (bench/sky_angle.hpp), the
/// same as the bench rows measure.
double pointing_error(double ant_az, double ant_el, double az, double el) {
  return bench::sky_angle_deg(ant_az, ant_el, az, el);
}

class Utc final : public hal::WallClock {
 public:
  Utc(std::int64_t start, const Millis* now) : start_(start), now_(now) {}
  std::optional<std::int64_t> unix_ms() const override { return start_ + *now_; }

 private:
  std::int64_t start_;
  const Millis* now_;
};

/// Follows the pass of `spec` with `kind` on `profile`, the lead rule on or
/// off, the client flipping the pass when `flip` (its own rule decides).
PassRun follow(const char* profile_name, const PassSpec& spec, ClientKind kind, bool lead,
               bool flip, double el_max_deg = 0.0) {
  const sim::Profile& p = *sim::find_profile(profile_name);
  settings::Settings settings;
  for (const auto& o : p.overrides) settings.set(*settings::find(o.key), o.value);
  settings.set(Id::kStationLatDeg, spec.lat_deg);
  settings.set(Id::kStationLonDeg, spec.lon_deg);
  settings.set(Id::kStationAltM, spec.alt_m);
  settings.set(Id::kTrackStreamLead, lead ? 1.0 : 0.0);
  if (el_max_deg > 0.0) settings.set(Id::kElMaxDeg, el_max_deg);
  tracking::Tle tle;
  EXPECT_TRUE(tracking::parse_tle(kIss1, kIss2, tle).ok());
  tracking::SkyTarget sat;
  EXPECT_EQ(sat.set_satellite(tle), tracking::Sgp4Error::kOk);
  std::int64_t from = 0;
  EXPECT_TRUE(tracking::parse_utc(spec.from_utc, from));
  const tracking::Observer obs(tracking::Geodetic{spec.lat_deg, spec.lon_deg, spec.alt_m});
  tracking::PassFinder finder;
  finder.start(sat, obs, from, from + 40 * 60 * 1000, 0.0);
  tracking::PassFinder::Status st;
  while ((st = finder.step(1000)) == tracking::PassFinder::Status::kSearching) {
  }
  EXPECT_EQ(st, tracking::PassFinder::Status::kFound);
  const tracking::Pass pass = finder.pass();
  ClientPass cp;
  cp.flip = flip;
  cp.culmination = {pass.max_el_az_deg, pass.max_el_deg};
  cp.culmination_s = static_cast<double>(pass.max_el_ms - from) / 1000.0;
  TrackerClient client(kind, cp);
  // Parked where the client will first ask for: the pass, not the slew there.
  const SkyAzEl start = client.wanted({pass.aos_az_deg, 0.0}, 0.0);
  sim::SimRotator sim(p, 5);
  sim.set_theta_deg(AxisId::kAz, start.az_deg);
  sim.set_theta_deg(AxisId::kEl, start.el_deg);
  Millis now = 0;
  Utc utc(from, &now);
  Controller c(settings, sim.io(AxisId::kAz), sim.io(AxisId::kEl));
  c.attach_utc_clock(&utc);
  c.begin(now);
  protocol::RotctldSession session(c, "test");
  session.set_peer(access::Peer::from_ipv4(0x7f000001));
  PassRun run;
  double sum = 0;
  long n = 0;
  std::uint32_t starts0 = 0;
  bool in_pass = false;
  SkyAzEl sky;
  double run_from = start.az_deg, last_az = start.az_deg;
  int dir = 0;
  const Millis end = static_cast<Millis>(pass.los_ms - from);
  for (now = 10; now <= end; now += 10) {
    sim.advance_to(now);
    if (now % 100 == 0) {
      tracking::LookAngles look;
      sat.look(from + now, obs, look);
      sky = {look.az_deg, look.el_deg < 0.0 ? 0.0 : look.el_deg};
    }
    const bool up = from + now >= pass.aos_ms;
    if (up) client.step(now, sky, session);
    c.tick(now);
    const RotatorStatus s = c.status();
    if (s.az.switch_cw || s.az.switch_ccw || s.el.switch_cw || s.el.switch_ccw) ++run.limit_ticks;
    if (!up) continue;
    if (!in_pass) starts0 = s.az.moves + s.el.moves;
    in_pass = true;
    run.starts = static_cast<int>(s.az.moves + s.el.moves - starts0);
    if (now % 100 != 0) continue;
    const double az = sim.plant(AxisId::kAz).theta_deg(), el = sim.plant(AxisId::kEl).theta_deg();
    run.az_min = std::fmin(run.az_min, az);
    run.az_max = std::fmax(run.az_max, az);
    run.el_min = std::fmin(run.el_min, el);
    run.el_max = std::fmax(run.el_max, el);
    const int d = az - last_az > 0.05 ? 1 : (az - last_az < -0.05 ? -1 : 0);
    if (d != 0 && d != dir) {
      dir = d;
      run_from = last_az;
    }
    run.longest_az_run_deg = std::fmax(run.longest_az_run_deg, std::fabs(az - run_from));
    last_az = az;
    const double e = pointing_error(az, el, sky.az_deg, sky.el_deg);
    sum += e * e;
    ++n;
    run.max_deg = std::fmax(run.max_deg, e);
    const SkyAzEl w = client.wanted(sky, static_cast<double>(now) / 1000.0);
    run.max_from_wanted_deg =
        std::fmax(run.max_from_wanted_deg, pointing_error(az, el, w.az_deg, w.el_deg));
    run.max_own_deg =
        std::fmax(run.max_own_deg, pointing_error(w.az_deg, w.el_deg, sky.az_deg, sky.el_deg));
  }
  run.rms_deg = n > 0 ? std::sqrt(sum / static_cast<double>(n)) : 0.0;
  run.commands = client.commands();
  run.refused = client.refused();
  return run;
}

void print(const char* what, const PassRun& r) {
  std::printf(
      "[ lead ] %s: %d starts, RMS %.2f max %.1f deg (from the client's wish at most %.1f; its "
      "wish off the satellite by up to %.1f), az %.0f..%.0f el %.0f..%.0f, longest az run %.0f "
      "deg, %d commands, %d refused\n",
      what, r.starts, r.rms_deg, r.max_deg, r.max_from_wanted_deg, r.max_own_deg, r.az_min,
      r.az_max, r.el_min, r.el_max, r.longest_az_run_deg, r.commands, r.refused);
}

/// Both runs stay inside the travel, touch no limit, never unwind.
void expect_clean(const PassRun& r, double az_lo, double az_hi) {
  EXPECT_EQ(r.limit_ticks, 0);
  EXPECT_EQ(r.refused, 0);
  EXPECT_GE(r.az_min, az_lo);
  EXPECT_LE(r.az_max, az_hi);
  EXPECT_LT(r.longest_az_run_deg, 200.0);
}

TEST(StreamLeadScenario, GpredictStartsTheMotorsFarLessOftenAtNoWorseRms) {
  // G-5500 (el 0..90), Gpredict's 5 deg threshold, the pass through north
  // into the 450 deg overlap: continuity and lead together.
  const PassRun off = follow("g5500", kThroughNorth, ClientKind::kGpredict, false, false, 90.0);
  const PassRun on = follow("g5500", kThroughNorth, ClientKind::kGpredict, true, false, 90.0);
  print("gpredict, lead off", off);
  print("gpredict, lead on", on);
  expect_clean(off, 290.0, 450.0);
  expect_clean(on, 290.0, 450.0);
  EXPECT_GT(on.az_max, 400.0);  // through north into the overlap
  EXPECT_LE(on.starts, 0.7 * off.starts);
  EXPECT_LE(on.rms_deg, off.rms_deg + 0.1);
  EXPECT_LT(on.max_deg, 5.0 + 4.0);
}

TEST(StreamLeadScenario, AClientWithoutThresholdStartsTheMotorsAboutHalfAsOften) {
  // SatDump-like: a go-to every second; the axis's 1 deg tolerance was the
  // only band. SPID (H-bridge, -180..540).
  const PassRun off = follow("spid", kThroughNorth, ClientKind::kSatdump, false, false, 90.0);
  const PassRun on = follow("spid", kThroughNorth, ClientKind::kSatdump, true, false, 90.0);
  print("satdump, lead off", off);
  print("satdump, lead on", on);
  expect_clean(off, 290.0, 540.0);
  expect_clean(on, 290.0, 540.0);
  EXPECT_LE(on.starts, 0.65 * off.starts);
  EXPECT_LE(on.rms_deg, off.rms_deg);
}

TEST(FlipScenario, GpredictSendsTheHighPassFlippedAndIsFollowedWithoutALimit) {
  // Gpredict with max el 180: the pass crosses north, so it is sent whole
  // as az +/- 180, 180 - el. G-5500 el 0..180.
  const PassRun r = follow("g5500", kHighThroughNorth, ClientKind::kGpredict, true, true);
  print("gpredict flipped", r);
  expect_clean(r, 0.0, 450.0);
  EXPECT_GT(r.el_max, 170.0);  // over the top, as sent
  EXPECT_GT(r.el_min, 90.0);   // and never back through the zenith
  // Within Gpredict's threshold plus the plant's lag of what it asked for,
  // and so of the satellite (the flip points at the same sky).
  EXPECT_LT(r.max_from_wanted_deg, 5.0 + 4.0);
  EXPECT_LT(r.max_deg, 5.0 + 4.0);
  // Its flip points at the very sky point it flips: measured as a sky angle
  // the wish is on the satellite all pass.
  EXPECT_LT(r.max_own_deg, 0.01);
}

TEST(FlipScenario, SatnogsMirrorsThePassAtCulminationAndIsFollowedWithoutALimit) {
  // The SatNOGS client's flip (culmination >= 75 deg): past culmination it
  // sends az = 2 az_mid - az, el = 2 el_mid - el; the azimuth turns back once
  // (a single reversal: still a stream), the elevation goes on past 90.
  for (const char* profile : {"g5500", "spid"}) {
    const PassRun r = follow(profile, kHighThroughNorth, ClientKind::kSatnogs, true, true);
    print(profile, r);
    expect_clean(r, profile[0] == 'g' ? 0.0 : -180.0, profile[0] == 'g' ? 450.0 : 540.0);
    EXPECT_GT(r.el_max, 140.0);
    // Followed as sent: within the client's 4 deg threshold plus the lag.
    EXPECT_LT(r.max_from_wanted_deg, 4.0 + 4.0);
    // The mirror is a reflection in (az, el), not a flip (az + 180,
    // 180 - el): past culmination it asks for a point up to ~19 deg off
    // the satellite (16 = 180 - 2 x 82.1 at LOS), so the antenna's error
    // against the satellite is the client's, not the rotator's, and no
    // more than the two together.
    EXPECT_GT(r.max_own_deg, 15.0);
    EXPECT_LE(r.max_deg, r.max_own_deg + r.max_from_wanted_deg + 0.01);
  }
}

TEST(SkyAngle, IsTheAngleOnTheSkyOverTheTopAndNearTheZenith) {
  // What every bench row and these scenarios measure (bench/sky_angle.hpp).
  // An antenna over the top at az + 180, 180 - el points at az, el.
  EXPECT_NEAR(bench::sky_angle_deg(30.0 + 180.0, 180.0 - 70.0, 30.0, 70.0), 0.0, 1e-9);
  EXPECT_NEAR(bench::sky_angle_deg(10.0, 0.0, 20.0, 0.0), 10.0, 1e-9);
  // Near the zenith an azimuth error counts as the sky it moves the beam:
  // 90 deg of azimuth at el 85 is 7.07 deg on the sky (not 0, as a figure
  // of the elevation alone above 80 deg made it, nor 90).
  EXPECT_NEAR(bench::sky_angle_deg(0.0, 85.0, 90.0, 85.0), 7.0666, 1e-3);
  EXPECT_NEAR(bench::sky_angle_deg(0.0, 90.0, 123.0, 90.0), 0.0, 1e-9);
  // Small angles keep their digits (atan2, not acos of a dot near 1).
  EXPECT_NEAR(bench::sky_angle_deg(0.0, 45.0, 0.001, 45.0), 0.001 * std::cos(kPi / 4.0), 1e-8);
}

TEST(StreamLeadScenario, NeverPastTheTravelAndASingleGotoIsLiteral) {
  const sim::Profile& p = *sim::find_profile("g5500");
  settings::Settings settings;
  for (const auto& o : p.overrides) settings.set(*settings::find(o.key), o.value);
  settings.set(Id::kElMaxDeg, 90.0);
  sim::SimRotator sim(p, 3);
  sim.set_theta_deg(AxisId::kAz, 400.0);
  sim.set_theta_deg(AxisId::kEl, 80.0);
  Controller c(settings, sim.io(AxisId::kAz), sim.io(AxisId::kEl));
  Millis now = 0;
  c.begin(now);
  protocol::RotctldSession session(c, "test");
  session.set_peer(access::Peer::from_ipv4(0x7f000001));
  int limit_ticks = 0;
  const auto run_ms = [&](Millis ms) {
    for (Millis t = 0; t < ms; t += 10) {
      now += 10;
      sim.advance_to(now);
      c.tick(now);
      const RotatorStatus s = c.status();
      if (s.az.switch_cw || s.az.switch_ccw || s.el.switch_cw || s.el.switch_ccw) ++limit_ticks;
    }
  };
  const auto send = [&](const char* cmd) {
    struct Sink final : protocol::ByteSink {
      void write(std::string_view b) override { data.append(b); }
      std::string data;
    } sink;
    session.receive(cmd, sink);
    EXPECT_EQ(sink.data, "RPRT 0\n") << cmd;
  };
  run_ms(1000);
  // A single go-to: exactly where it was sent (rotctld: 60 is 60).
  send("P 60 80\n");
  EXPECT_FLOAT_EQ(c.status().az.target_deg, 60.0f);
  EXPECT_FLOAT_EQ(c.status().el.target_deg, 80.0f);
  run_ms(80000);
  send("S\n");
  // A steady stream of compass azimuths through north toward the end of
  // the 450 deg travel (continuity: 5 is 365, 89 is 449) while the
  // elevation climbs to its end (90): led, but never past either end.
  const double az_steps[] = {330, 340, 350, 358, 5,  15, 25, 35, 45,
                             55,  65,  72,  78,  83, 86, 88, 89, 89.5};
  float max_az_target = 0.0f, max_el_target = 0.0f;
  int i = 0;
  for (const double az : az_steps) {
    const double el = 72.0 + static_cast<double>(i++);
    char cmd[48];
    std::snprintf(cmd, sizeof cmd, "P %.1f %.1f\n", az, el);
    send(cmd);
    const RotatorStatus s = c.status();
    max_az_target = std::fmax(max_az_target, s.az.target_deg);
    max_el_target = std::fmax(max_el_target, s.el.target_deg);
    run_ms(4000);
  }
  std::printf("[ lead ] toward the ends: az target at most %.2f, el %.2f, antenna %.1f / %.1f\n",
              static_cast<double>(max_az_target), static_cast<double>(max_el_target),
              sim.plant(AxisId::kAz).theta_deg(), sim.plant(AxisId::kEl).theta_deg());
  EXPECT_GT(c.stream_led(), 5u);     // the rule was at work ...
  EXPECT_GT(max_az_target, 449.5f);  // ... and led the last ones to the end
  EXPECT_LE(max_az_target, 450.0f);  // never past it
  EXPECT_LE(max_el_target, 90.0f);
  run_ms(20000);
  EXPECT_EQ(limit_ticks, 0);
  EXPECT_LE(sim.plant(AxisId::kAz).theta_deg(), 450.0);
  EXPECT_LE(sim.plant(AxisId::kEl).theta_deg(), 90.5);
}

}  // namespace
}  // namespace rotord
