// Issue 22: the modelled clients beside on-board tracking of the same pass.
// Each row follows one real ISS pass (SGP4) on the simulator in virtual
// time and reports the pointing error of the antenna (the angle on the sky
// between where its axes point, over the top when el > 90, and the
// satellite: bench/sky_angle.hpp) every 0.1 s from AOS to LOS, the
// seconds off by more than 5 deg, the unwinds (one azimuth run of more than
// 200 deg; the tracking mode counts its own), the motor starts of both axes
// in the pass and the commands the client had refused; on a pass whose
// 0..360 azimuth crosses north, the largest error within 30 s of that moment
// beside issue 22's goal for it (the client's threshold + 2 deg; on-board
// and SatDump have none). Beside it, the client's own pointing (where it
// asks the antenna to be, against the satellite: the SatNOGS client's
// mirrored flip is off the satellite by itself) and the antenna against
// what the client asks (what rotord adds), and the same client obeyed by
// an ideal follower of its go-tos (ObeyingFloor). Each client runs
// three times: the lead rule off (`_before`), on (the default), and on with
// the ISS in the TLE store (`_recognised`: rotord may recognise the pass and
// follow it between the client's go-tos; how long it took from AOS, how
// long it lasted and the error once recognised are reported too).
#include "client_passes.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>

#include "protocol/rotctld_session.hpp"
#include "rotator/controller.hpp"
#include "sim/profiles.hpp"
#include "sim/sim_rotator.hpp"
#include "sky_pass.hpp"
#include "tracker_clients.hpp"
#include "tracking/julian.hpp"
#include "tracking/pass_finder.hpp"
#include "tracking/tle_catalog.hpp"

namespace rotord::bench {
namespace {

using settings::Id;

constexpr Millis kTickMs = 10;
constexpr Millis kSampleMs = 100;
/// The north crossing's window: either side of the moment the satellite's
/// 0..360 azimuth wraps, where a client's 359 -> 0.5 is resolved or not.
constexpr std::int64_t kNorthWindowMs = 30000;

struct PassCase {
  std::string name;
  tracking::Geodetic station;
  std::int64_t from_ms = 0;  ///< the run starts here (before AOS)
  tracking::Pass pass;
  bool crosses_north = false;
  std::int64_t north_ms = 0;  ///< when the 0..360 azimuth wraps (crosses_north)
  double north_el_deg = 0;    ///< the elevation then
};

tracking::SkyTarget iss() {
  tracking::Tle tle;
  tracking::parse_tle(kIss1, kIss2, tle);
  tracking::SkyTarget t;
  t.set_satellite(tle);
  return t;
}

/// The first pass after `from_ms` over `where`, and whether its 0..360
/// azimuth crosses north.
bool first_pass(const tracking::Geodetic& where, std::int64_t from_ms, PassCase& out) {
  tracking::SkyTarget sat = iss();
  const tracking::Observer obs(where);
  tracking::PassFinder finder;
  finder.start(sat, obs, from_ms, from_ms + 40 * 60 * 1000, 0.0);
  for (;;) {
    const auto st = finder.step(1000);
    if (st == tracking::PassFinder::Status::kSearching) continue;
    if (st != tracking::PassFinder::Status::kFound) return false;
    break;
  }
  out.station = where;
  out.from_ms = from_ms;
  out.pass = finder.pass();
  out.crosses_north = false;
  double last = out.pass.aos_az_deg;
  for (std::int64_t t = out.pass.aos_ms; t <= out.pass.los_ms; t += 2000) {
    tracking::LookAngles look;
    sat.look(t, obs, look);
    if (std::fabs(look.az_deg - last) > 180.0 && !out.crosses_north) {
      out.crosses_north = true;
      out.north_ms = t - 1000;  // within a second
      out.north_el_deg = look.el_deg;
    }
    last = look.az_deg;
  }
  return true;
}

/// A station west or east of the 2019-12-09 19:2x pass's ground track
/// whose pass culminates nearest `max_el_deg` (and, if asked, crosses north).
PassCase find_case(const char* name, double max_el_deg, bool north) {
  std::int64_t from = 0;
  tracking::parse_utc("2019-12-09T19:10:00Z", from);
  PassCase best;
  double best_gap = 1e9;
  for (double dlon = -12.0; dlon <= 12.0; dlon += 0.05) {
    PassCase c;
    if (!first_pass({39.86366, -119.17875 + dlon, 0.0}, from, c)) continue;
    if (north && !c.crosses_north) continue;
    const double gap = std::fabs(c.pass.max_el_deg - max_el_deg);
    if (gap < best_gap) {
      best_gap = gap;
      best = c;
    }
  }
  best.name = name;
  return best;
}

/// Unwinds as the antenna makes them: an azimuth run of more than 200 deg.
class UnwindCounter {
 public:
  void add(double az_deg) {
    if (!have_) {
      have_ = true;
      start_ = last_ = az_deg;
      return;
    }
    const double d = az_deg - last_;
    const int sign = d > 0.05 ? 1 : (d < -0.05 ? -1 : 0);
    if (sign != 0 && sign != dir_) {
      dir_ = sign;
      start_ = last_;
      counted_ = false;
    }
    if (!counted_ && std::fabs(az_deg - start_) > 200.0) {
      ++unwinds_;
      counted_ = true;
    }
    last_ = az_deg;
  }
  int unwinds() const { return unwinds_; }

 private:
  bool have_ = false, counted_ = false;
  int dir_ = 0, unwinds_ = 0;
  double start_ = 0, last_ = 0;
};

/// The floor of obeying a client: each axis turned at the profile's top
/// speed with no acceleration, delay or backlash, straight to where the
/// client last asked (its azimuth continued to the nearest turn, as the
/// continuity rule does), the client deciding on its own cycle against
/// this follower's position (read back 0..360, as rotord reports to it).
/// What a controller that goes where it is told, without predicting the
/// satellite, cannot beat by much; rotord's lead rule is such a controller
/// with a lead of at most the client's threshold.
class ObeyingFloor {
 public:
  ObeyingFloor(double vaz_deg_s, double vel_deg_s) : vaz_(vaz_deg_s), vel_(vel_deg_s) {}
  void start(SkyAzEl at) {
    az_ = cmd_az_ = at.az_deg;
    el_ = cmd_el_ = at.el_deg;
  }
  void step(Millis now, double dt_s, SkyAzEl wish, const TrackerClient& client) {
    if (now >= next_ms_) {
      next_ms_ = now + client.cycle_ms();
      const double read_az = std::fmod(std::fmod(az_, 360.0) + 360.0, 360.0);
      const double w_el = wish.el_deg < 0.0 ? 0.0 : wish.el_deg;
      if (client.would_send(wish.az_deg - read_az, w_el - el_)) {
        cmd_az_ = az_ + std::remainder(wish.az_deg - az_, 360.0);
        cmd_el_ = w_el;
      }
    }
    az_ += std::clamp(cmd_az_ - az_, -vaz_ * dt_s, vaz_ * dt_s);
    el_ += std::clamp(cmd_el_ - el_, -vel_ * dt_s, vel_ * dt_s);
  }
  double az_deg() const { return az_; }
  double el_deg() const { return el_; }

 private:
  double vaz_, vel_;
  double az_ = 0, el_ = 0, cmd_az_ = 0, cmd_el_ = 0;
  Millis next_ms_ = 0;
};

struct Who {
  const char* name;
  bool onboard;
  ClientKind kind;
  bool lead;
  bool recognise;  ///< the ISS in the TLE store: rotord may recognise the pass
};

Result run_one(const char* profile_name, const PassCase& pc, const Who& who, bool flip_pass) {
  const sim::Profile& p = *sim::find_profile(profile_name);
  settings::Settings settings;
  for (const auto& o : p.overrides) settings.set(*settings::find(o.key), o.value);
  settings.set(Id::kStationLatDeg, pc.station.lat_deg);
  settings.set(Id::kStationLonDeg, pc.station.lon_deg);
  settings.set(Id::kStationAltM, pc.station.alt_m);
  settings.set(Id::kTrackStreamLead, who.lead ? 1.0 : 0.0);
  sim::SimRotator sim(p, 7);
  // Parked at the pass's AOS azimuth on the travel's first turn, el 0.
  // Parked where the pass begins, as the client will ask for it (a
  // tracker's pre-positioning is not what these rows measure).
  ClientPass cp;
  cp.flip = flip_pass && who.kind != ClientKind::kSatdump &&
            (who.kind == ClientKind::kGpredict ? pc.crosses_north : pc.pass.max_el_deg >= 75.0);
  cp.culmination = {pc.pass.max_el_az_deg, pc.pass.max_el_deg};
  cp.culmination_s = static_cast<double>(pc.pass.max_el_ms - pc.from_ms) / 1000.0;
  TrackerClient client(who.kind, cp);
  const SkyAzEl start = who.onboard ? SkyAzEl{pc.pass.aos_az_deg, 0.0}
                                    : client.wanted({pc.pass.aos_az_deg, 0.0}, 0.0);
  sim.set_theta_deg(AxisId::kAz, start.az_deg);
  sim.set_theta_deg(AxisId::kEl, start.el_deg);
  ObeyingFloor floor(p.az.plant.v_max_deg_s, p.el.plant.v_max_deg_s);
  floor.start(start);
  Millis now = 0;
  VirtualUtc utc(pc.from_ms, &now);
  Controller c(settings, sim.io(AxisId::kAz), sim.io(AxisId::kEl));
  c.attach_utc_clock(&utc);
  tracking::TleCatalog catalog;
  if (who.recognise) {
    const std::string text = std::string("ISS (ZARYA)\n") + kIss1 + "\n" + kIss2 + "\n";
    if (!catalog.put(text, pc.from_ms).ok())
      std::fprintf(stderr, "bench: the ISS TLE not stored\n");
    c.attach_catalog(&catalog);
  }
  settings.set(Id::kTrackRecognise, who.recognise ? 1.0 : 0.0);
  c.begin(now);
  protocol::RotctldSession session(c, "bench");
  tracking::SkyTarget sat = iss();
  const tracking::Observer obs(pc.station);
  if (who.onboard) {
    TrackRequest r;
    r.kind = tracking::TargetKind::kSatellite;
    tracking::parse_tle(kIss1, kIss2, r.tle);
    c.track(r);
  }
  double sum = 0, max_err = 0, s_over_5 = 0, s_recognised = 0, s_to_recognise = -1;
  double sum_recognised = 0, max_recognised = 0;
  // The continuity goal: the error within kNorthWindowMs of the moment the
  // 0..360 azimuth wraps, and when the pass's largest error came.
  double max_north = 0, s_max_error = 0;
  // The client's own pointing (where it asks the antenna to be, against the
  // satellite: what obeying it exactly would give) and the antenna against
  // it (what rotord adds), to tell the client's geometry from rotord's.
  double own_sum = 0, own_max = 0, own_north = 0, from_client_max = 0, from_client_north = 0;
  double floor_max = 0, floor_north = 0;
  long n_recognised = 0;
  long n = 0;
  std::uint32_t starts_at_aos = 0;
  bool in_pass = false;
  UnwindCounter unwinds;
  SkyAzEl sky;
  const Millis end = static_cast<Millis>(pc.pass.los_ms - pc.from_ms);
  for (now = kTickMs; now <= end; now += kTickMs) {
    sim.advance_to(now);
    if (now % kSampleMs == 0) {
      tracking::LookAngles look;
      sat.look(pc.from_ms + now, obs, look);
      sky = {look.az_deg, look.el_deg};
    }
    const bool up = pc.from_ms + now >= pc.pass.aos_ms;
    if (up && !who.onboard) {
      client.step(now, sky, session);
      const double t_s = static_cast<double>(now) / 1000.0;
      floor.step(now, static_cast<double>(kTickMs) / 1000.0, client.wanted(sky, t_s), client);
    }
    c.tick(now);
    if (!up) continue;
    const RotatorStatus s = c.status();
    if (!in_pass) starts_at_aos = s.az.moves + s.el.moves;
    in_pass = true;
    if (now % kSampleMs != 0) continue;
    const double az = sim.plant(AxisId::kAz).theta_deg();
    unwinds.add(az);
    const double el = sim.plant(AxisId::kEl).theta_deg();
    const double sky_el = sky.el_deg < 0 ? 0 : sky.el_deg;
    const double e = pointing_error(az, el, sky.az_deg, sky_el);
    SkyAzEl w = who.onboard ? SkyAzEl{sky.az_deg, sky_el}
                            : client.wanted(sky, static_cast<double>(now) / 1000.0);
    if (w.el_deg < 0) w.el_deg = 0;
    const double own = pointing_error(w.az_deg, w.el_deg, sky.az_deg, sky_el);
    const double from_client = pointing_error(az, el, w.az_deg, w.el_deg);
    own_sum += own * own;
    own_max = std::fmax(own_max, own);
    from_client_max = std::fmax(from_client_max, from_client);
    const double floor_e =
        who.onboard ? 0.0 : pointing_error(floor.az_deg(), floor.el_deg(), sky.az_deg, sky_el);
    floor_max = std::fmax(floor_max, floor_e);
    sum += e * e;
    ++n;
    const std::int64_t t_ms = pc.from_ms + now;
    if (e > max_err) s_max_error = static_cast<double>(t_ms - pc.pass.aos_ms) / 1000.0;
    max_err = std::fmax(max_err, e);
    if (pc.crosses_north && t_ms >= pc.north_ms - kNorthWindowMs &&
        t_ms <= pc.north_ms + kNorthWindowMs) {
      max_north = std::fmax(max_north, e);
      own_north = std::fmax(own_north, own);
      floor_north = std::fmax(floor_north, floor_e);
      from_client_north = std::fmax(from_client_north, from_client);
    }
    if (e > 5.0) s_over_5 += kSampleMs / 1000.0;
    if (c.recognition().active) {
      if (s_to_recognise < 0)
        s_to_recognise = static_cast<double>(pc.from_ms + now - pc.pass.aos_ms) / 1000.0;
      s_recognised += kSampleMs / 1000.0;
      sum_recognised += e * e;
      max_recognised = std::fmax(max_recognised, e);
      ++n_recognised;
    }
  }
  const RotatorStatus s = c.status();
  const double starts = s.az.moves + s.el.moves - starts_at_aos;
  const double unwound = who.onboard ? c.track_status().unwinds : unwinds.unwinds();
  Result row{
      std::string("clients/") + profile_name + "/" + pc.name + "/" + who.name,
      {{"max_el_deg", pc.pass.max_el_deg},
       {"lat_deg", pc.station.lat_deg},
       {"lon_deg", pc.station.lon_deg},
       {"crosses_north", pc.crosses_north ? 1.0 : 0.0},
       {"client_flips", cp.flip ? 1.0 : 0.0},
       {"s_north_after_aos",
        pc.crosses_north ? static_cast<double>(pc.north_ms - pc.pass.aos_ms) / 1000.0 : -1.0},
       {"north_el_deg", pc.crosses_north ? pc.north_el_deg : -1.0},
       {"client_threshold_deg", who.onboard ? 0.0 : client.threshold_deg()}},
      {{"rms_error_deg", n > 0 ? std::sqrt(sum / static_cast<double>(n)) : 0.0},
       {"max_error_deg", max_err},
       {"s_max_error_after_aos", s_max_error},
       {"s_error_over_5deg", s_over_5},
       {"unwinds", unwound},
       {"motor_starts", starts},
       {"refused", static_cast<double>(client.refused())},
       // How long after AOS the pass was recognised (-1: never), how long
       // it was followed so, the error meanwhile, and how often a
       // recognition ended (LOS, or a mirrored or departing go-to).
       {"s_recognised", s_recognised},
       {"s_to_recognise", s_to_recognise},
       {"rms_recognised_deg",
        n_recognised > 0 ? std::sqrt(sum_recognised / static_cast<double>(n_recognised)) : 0.0},
       {"max_recognised_deg", max_recognised},
       {"recognition_endings", static_cast<double>(c.recognition().endings)},
       {"client_own_rms_deg", n > 0 ? std::sqrt(own_sum / static_cast<double>(n)) : 0.0},
       {"client_own_max_deg", own_max},
       {"max_from_client_deg", from_client_max},
       {"obeying_floor_max_deg", floor_max}}};
  // Issue 22's continuity goal, read directly: the largest error within 30 s
  // of the north crossing, against the client's threshold + 2 deg.
  if (pc.crosses_north) {
    row.metrics.push_back({"north_max_error_deg", max_north});
    row.metrics.push_back({"north_goal_deg", row.inputs.back().second + 2.0});
    row.metrics.push_back({"north_client_own_deg", own_north});
    row.metrics.push_back({"north_from_client_deg", from_client_north});
    row.metrics.push_back({"north_obeying_floor_deg", floor_north});
  }
  return row;
}

}  // namespace

std::vector<Result> run_client_passes() {
  std::vector<PassCase> cases;
  for (const double el : {30.0, 60.0, 75.0, 85.0})
    cases.push_back(
        find_case(("max_el_" + std::to_string(static_cast<int>(el))).c_str(), el, false));
  cases.push_back(find_case("north", 45.0, true));
  cases.push_back(find_case("flip", 82.0, true));
  const Who whos[] = {
      {"onboard", true, ClientKind::kSatdump, true, false},
      {"gpredict_before", false, ClientKind::kGpredict, false, false},
      {"gpredict", false, ClientKind::kGpredict, true, false},
      {"gpredict_recognised", false, ClientKind::kGpredict, true, true},
      {"satnogs_before", false, ClientKind::kSatnogs, false, false},
      {"satnogs", false, ClientKind::kSatnogs, true, false},
      {"satnogs_recognised", false, ClientKind::kSatnogs, true, true},
      {"satdump_before", false, ClientKind::kSatdump, false, false},
      {"satdump", false, ClientKind::kSatdump, true, false},
      {"satdump_recognised", false, ClientKind::kSatdump, true, true},
  };
  std::vector<Result> rows;
  for (const char* profile : {"g5500", "spid"}) {
    for (const PassCase& pc : cases) {
      for (const Who& who : whos) rows.push_back(run_one(profile, pc, who, pc.name == "flip"));
    }
  }
  return rows;
}

}  // namespace rotord::bench
