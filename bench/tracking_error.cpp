#include "tracking_error.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>

#include "protocol/rotctld_session.hpp"
#include "rotator/controller.hpp"
#include "sim/profiles.hpp"
#include "sim/sim_rotator.hpp"
#include "sky_angle.hpp"

namespace rotord::bench {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDeg = kPi / 180.0;
constexpr double kEarthRadiusKm = 6371.0;
constexpr double kMuKm3S2 = 398600.4418;
constexpr double kAltitudeKm = 420.0;
constexpr double kMaxElevationsDeg[] = {30, 60, 75, 85};
constexpr Millis kTickMs = 10;

struct AzEl {
  double az_deg;
  double el_deg;
};

// A pass over a non-rotating spherical Earth: the satellite's unit vector
// runs along a great circle whose closest approach to the observer (at +z,
// east +x, north +y) is the central angle beta, at t = 0.
class Pass {
 public:
  explicit Pass(double max_el_deg) : r_km_(kEarthRadiusKm + kAltitudeKm) {
    omega_rad_s_ = std::sqrt(kMuKm3S2 / (r_km_ * r_km_ * r_km_));
    const double e = max_el_deg * kDeg;
    // Earth-central angle from the observer to the ground track, for a pass
    // culminating at max_el_deg.
    beta_rad_ = std::acos(kEarthRadiusKm * std::cos(e) / r_km_) - e;
    half_s_ = std::acos(kEarthRadiusKm / r_km_ / std::cos(beta_rad_)) / omega_rad_s_;
  }
  double duration_s() const { return 2.0 * half_s_; }
  /// t from AOS (0) to LOS (duration_s()).
  AzEl at(double t_s) const {
    const double a = omega_rad_s_ * (t_s - half_s_);
    // Ground track heading north-east so the azimuth sweeps through north.
    const double sx = std::sin(a), sy = std::cos(a) * std::sin(beta_rad_),
                 sz = std::cos(a) * std::cos(beta_rad_);
    const double dx = r_km_ * sx, dy = r_km_ * sy, dz = r_km_ * sz - kEarthRadiusKm;
    const double range = std::sqrt(dx * dx + dy * dy + dz * dz);
    double az = std::atan2(dx, dy) / kDeg;
    if (az < 0) az += 360.0;
    return {az, std::asin(dz / range) / kDeg};
  }

 private:
  double r_km_;
  double omega_rad_s_;
  double beta_rad_;
  double half_s_;
};

double great_circle_deg(AzEl a, AzEl b) {
  return sky_angle_deg(a.az_deg, a.el_deg, b.az_deg, b.el_deg);
}

double wrap180(double d) {
  d = std::fmod(d + 540.0, 360.0) - 180.0;
  return d;
}

struct ErrorStats {
  double sum_sq = 0, max = 0;
  long n = 0;
  double s_over_5 = 0;
  void add(double e) {
    sum_sq += e * e;
    max = std::max(max, e);
    ++n;
    if (e > 5.0) s_over_5 += kTickMs / 1000.0;
  }
  double rms() const { return n ? std::sqrt(sum_sq / static_cast<double>(n)) : 0.0; }
};

// The limit: each axis moves straight toward the satellite at up to its top
// speed, no lag, no overshoot (the reference's "rate-limited follower").
ErrorStats ideal_follower(const Pass& pass, double vaz_deg_s, double vel_deg_s) {
  ErrorStats st;
  AzEl p = pass.at(0);
  const double dt = kTickMs / 1000.0;
  for (double t = dt; t <= pass.duration_s(); t += dt) {
    const AzEl s = pass.at(t);
    const double daz = wrap180(s.az_deg - p.az_deg);
    p.az_deg += std::clamp(daz, -vaz_deg_s * dt, vaz_deg_s * dt);
    p.el_deg += std::clamp(s.el_deg - p.el_deg, -vel_deg_s * dt, vel_deg_s * dt);
    st.add(great_circle_deg(p, s));
  }
  return st;
}

class NullSink final : public protocol::ByteSink {
 public:
  void write(std::string_view bytes) override { last.assign(bytes); }
  std::string last;
};

/// A tracking client in the loop with rotord. Gpredict-style today; on-board
/// tracking (being built in core/rotator) gets its own client here: one that
/// hands the pass to the controller's tracking mode and only watches.
class TrackingClient {
 public:
  virtual ~TrackingClient() = default;
  virtual void step(Millis now, AzEl sat, protocol::RotctldSession& session) = 0;
};

// Gpredict's rotator controller: one cycle per 0.8 s reads the position
// (`p`) and sends a new `P` only when the rotator is off by more than 5 deg
// on an axis (its default threshold). Azimuths go out as 0..360, as Gpredict
// sends them; rotctld took them as positions (Hamlib's rule), so a pass
// crossing north made a 450 deg rotator run the long way round at 360 -> 0,
// until the continuity rule (issue 22) continued such a stream.
class GpredictClient final : public TrackingClient {
 public:
  void step(Millis now, AzEl sat, protocol::RotctldSession& session) override {
    if (now < next_ms_) return;
    next_ms_ = now + kCycleMs;
    NullSink sink;
    session.receive("p\n", sink);
    double az = 0, el = 0;
    if (std::sscanf(sink.last.c_str(), "%lf %lf", &az, &el) != 2) return;
    const double target_el = std::max(0.0, sat.el_deg);
    if (std::fabs(wrap180(sat.az_deg - az)) > kThresholdDeg ||
        std::fabs(target_el - el) > kThresholdDeg) {
      char cmd[64];
      std::snprintf(cmd, sizeof cmd, "P %.2f %.2f\n", sat.az_deg, target_el);
      session.receive(cmd, sink);
    }
  }
  static constexpr Millis kCycleMs = 800;
  static constexpr double kThresholdDeg = 5.0;

 private:
  Millis next_ms_ = 0;
};

ErrorStats closed_loop(const Pass& pass, TrackingClient& client) {
  const sim::Profile& profile = *sim::find_profile("g5500");
  settings::Settings settings;
  for (const auto& o : profile.overrides) settings.set(*settings::find(o.key), o.value);
  sim::SimRotator sim(profile, 7);
  const AzEl aos = pass.at(0);
  sim.set_theta_deg(AxisId::kAz, aos.az_deg);  // parked at the AOS azimuth
  sim.set_theta_deg(AxisId::kEl, 0.0);
  Controller controller(settings, sim.io(AxisId::kAz), sim.io(AxisId::kEl));
  controller.begin(0);
  protocol::RotctldSession session(controller, "bench");
  ErrorStats st;
  const Millis end_ms = static_cast<Millis>(pass.duration_s() * 1000.0);
  for (Millis now = kTickMs; now <= end_ms; now += kTickMs) {
    sim.advance_to(now);
    const AzEl sat = pass.at(static_cast<double>(now) / 1000.0);
    client.step(now, sat, session);
    controller.tick(now);
    const AzEl pointing{std::fmod(sim.plant(AxisId::kAz).theta_deg() + 360.0, 360.0),
                        sim.plant(AxisId::kEl).theta_deg()};
    st.add(great_circle_deg(pointing, sat));
  }
  return st;
}

Result row(const char* who, double max_el, const ErrorStats& st) {
  return {
      std::string("tracking/") + who + "/g5500/max_el_" + std::to_string(static_cast<int>(max_el)),
      {{"max_el_deg", max_el}, {"altitude_km", kAltitudeKm}},
      {{"rms_error_deg", st.rms()}, {"max_error_deg", st.max}, {"s_error_over_5deg", st.s_over_5}}};
}

}  // namespace

std::vector<Result> run_tracking_error() {
  std::vector<Result> results;
  const sim::Profile& g5500 = *sim::find_profile("g5500");
  // The geometry checked against rate_limited_follower_error.csv (420 km,
  // max el 85, az 6.2 / el 2.7 deg/s: max error 4.166 deg).
  const ErrorStats check = ideal_follower(Pass(85.0), 6.2, 2.7);
  results.push_back({"tracking/reference_check",
                     {{"max_el_deg", 85.0}, {"vaz_deg_s", 6.2}, {"vel_deg_s", 2.7}},
                     {{"max_error_deg", check.max}, {"reference_max_error_deg", 4.166}}});
  for (double max_el : kMaxElevationsDeg) {
    const Pass pass(max_el);
    results.push_back(
        row("ideal", max_el,
            ideal_follower(pass, g5500.az.plant.v_max_deg_s, g5500.el.plant.v_max_deg_s)));
    GpredictClient gpredict;
    results.push_back(row("gpredict", max_el, closed_loop(pass, gpredict)));
  }
  return results;
}

}  // namespace rotord::bench
