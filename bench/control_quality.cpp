#include "control_quality.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>
#include <string>

#include "bounds.hpp"
#include "peer_strategies.hpp"
#include "rotator/controller.hpp"
#include "sim/profiles.hpp"
#include "sim/sim_rotator.hpp"

namespace rotord::bench {
namespace {

constexpr Millis kTickMs = 10;
constexpr std::uint64_t kSeed = 7;
constexpr double kToleranceDeg =
    1.0;  // rotord's az.tolerance_deg default, used for every controller
constexpr double kRestSpeedFraction = 0.01;  // "speed = 0": below 1 % of v_max
constexpr Millis kQuietMs = 3000;            // no drive for this long = the move is over
constexpr double kMoveSetDeg[] = {2, 5, 10, 30, 90, 180, 350};

enum class Controller_ : int { kRotord = 0, kWrc = 1, kPicoRotor = 2 };
constexpr const char* kControllerNames[] = {"rotord", "wrc", "picorotor"};

enum class Kind : int { kMove = 0, kOverlap = 1, kReversal = 2 };
constexpr const char* kKindNames[] = {"move", "overlap", "reversal"};

struct Scenario {
  Kind kind;
  double start_deg;
  double target_deg;
  /// Reversal: once the axis has passed this angle the target becomes `second_target_deg`.
  double reverse_at_deg = 0.0;
  double second_target_deg = 0.0;
};

settings::Settings settings_for(const sim::Profile& p) {
  settings::Settings s;
  for (const auto& o : p.overrides) s.set(*settings::find(o.key), o.value);
  return s;
}

BoundPlant bound_plant(const sim::AxisProfile& a) {
  return {a.plant.v_max_deg_s, a.plant.tau_m_s, a.plant.tau_c_s,
          a.plant.has_brake ? a.plant.brake_decel_deg_s2 : 0.0};
}

bool pwm_drive(const sim::AxisProfile& a) {
  return a.plant.drive == sim::DriveKind::kHBridge;
}

double bound_s(const sim::AxisProfile& a, double distance_deg) {
  const BoundPlant p = bound_plant(a);
  if (pwm_drive(a)) return trapezoid_bound_s(p, distance_deg);
  return p.brake_decel_deg_s2 > 0 ? relay_brake_bound_s(p, distance_deg)
                                  : relay_coast_bound_s(p, distance_deg);
}

// Shortest stop from full speed: coasting out (relay) or braking at a (PWM).
double stop_time_s(const sim::AxisProfile& a) {
  const BoundPlant p = bound_plant(a);
  if (pwm_drive(a)) return p.tau_m_s;
  if (p.brake_decel_deg_s2 > 0) return p.v_max_deg_s / p.brake_decel_deg_s2;
  return p.tau_c_s * std::log(1.0 / kRestSpeedFraction);
}
double stop_distance_deg(const sim::AxisProfile& a) {
  const BoundPlant p = bound_plant(a);
  if (pwm_drive(a)) return 0.5 * p.v_max_deg_s * p.tau_m_s;
  if (p.brake_decel_deg_s2 > 0) return p.v_max_deg_s * p.v_max_deg_s / (2 * p.brake_decel_deg_s2);
  return p.v_max_deg_s * p.tau_c_s;
}

bool driving(const DriveOutputs& o) {
  return o.on(OutputChannel::kRelayCw) || o.on(OutputChannel::kRelayCcw) ||
         o.on(OutputChannel::kPwmCw) || o.on(OutputChannel::kPwmCcw);
}
int direction(const DriveOutputs& o) {
  if (o.on(OutputChannel::kRelayCw) || o.on(OutputChannel::kPwmCw)) return 1;
  if (o.on(OutputChannel::kRelayCcw) || o.on(OutputChannel::kPwmCcw)) return -1;
  return 0;
}
int relay_changes(const DriveOutputs& a, const DriveOutputs& b) {
  int n = 0;
  for (OutputChannel ch :
       {OutputChannel::kRelayCw, OutputChannel::kRelayCcw, OutputChannel::kSpeedFast,
        OutputChannel::kBrake, OutputChannel::kVoltageFast}) {
    if (a.on(ch) != b.on(ch)) ++n;
  }
  return n;
}

struct Run {
  double settle_s = NAN;  // from the (last) command
  double final_error_deg = 0;
  double overshoot_deg = 0;
  int starts = 0;
  int reversals = 0;
  int relay_switchings = 0;
  double reversal_command_theta_deg = 0;
};

// `use`: rotord's settings (default: the profile's own, as `--sim` runs it).
Run run_one(const sim::Profile& profile, Controller_ who, const Scenario& sc,
            const settings::Settings* use = nullptr) {
  const sim::AxisProfile& ax = profile.az;
  settings::Settings settings = use != nullptr ? *use : settings_for(profile);
  sim::SimRotator sim(profile, kSeed);
  sim.set_theta_deg(AxisId::kAz, sc.start_deg);
  std::unique_ptr<Controller> controller;
  std::unique_ptr<PeerStrategy> peer;
  AxisIo az_io = sim.io(AxisId::kAz);
  if (who == Controller_::kRotord) {
    controller = std::make_unique<Controller>(settings, az_io, sim.io(AxisId::kEl));
    controller->begin(0);
    controller->go_to(static_cast<float>(sc.target_deg), std::nullopt, AzTarget::kUnwrapped);
  } else if (who == Controller_::kWrc) {
    peer = std::make_unique<WrcTwoSpeed>(ax.plant.drive, ax.plant.has_brake, kToleranceDeg);
  } else {
    peer = std::make_unique<PicoRotorSlowZone>(ax.plant.drive, ax.plant.has_brake);
  }

  Run r;
  double target = sc.target_deg;
  double move_sign = target >= sc.start_deg ? 1.0 : -1.0;
  bool reversed = sc.kind != Kind::kReversal;
  Millis command_ms = 0;
  Millis last_unsettled_ms = 0;
  Millis last_drive_ms = 0;
  DriveOutputs prev{};
  int prev_dir = 0;
  const double rest_deg_s = kRestSpeedFraction * ax.plant.v_max_deg_s;
  const Millis limit_ms =
      static_cast<Millis>(1000.0 * (3.0 * bound_s(ax, std::fabs(target - sc.start_deg)) + 60.0));
  for (Millis now = kTickMs; now <= limit_ms; now += kTickMs) {
    sim.advance_to(now);
    const double theta = sim.plant(AxisId::kAz).theta_deg();
    if (!reversed && (theta - sc.reverse_at_deg) * move_sign >= 0) {
      reversed = true;
      r.reversal_command_theta_deg = theta;
      target = sc.second_target_deg;
      move_sign = -move_sign;
      command_ms = now;
      r.overshoot_deg = 0;
      if (controller)
        controller->go_to(static_cast<float>(target), std::nullopt, AzTarget::kUnwrapped);
    }
    if (controller) {
      controller->tick(now);
    } else if (now % peer->loop_ms() == 0) {
      az_io.drive->apply(peer->step(target - theta));
    }
    const DriveOutputs& out = sim.outputs(AxisId::kAz);
    r.relay_switchings += relay_changes(prev, out);
    const int dir = direction(out);
    if (dir != 0 && direction(prev) == 0) {
      ++r.starts;
      if (prev_dir != 0 && dir != prev_dir) ++r.reversals;
    } else if (dir != 0 && direction(prev) != 0 && dir != direction(prev)) {
      ++r.reversals;
    }
    if (dir != 0) prev_dir = dir;
    prev = out;
    if (driving(out)) last_drive_ms = now;
    const double err = theta - target;
    if (reversed) r.overshoot_deg = std::max(r.overshoot_deg, err * move_sign);
    if (std::fabs(err) > kToleranceDeg ||
        std::fabs(sim.plant(AxisId::kAz).w_deg_s()) > rest_deg_s || !reversed) {
      last_unsettled_ms = now;
    }
    const bool idle = controller ? (!controller->status().az.has_target &&
                                    controller->status().az.state == AxisState::kIdle)
                                 : true;
    if (reversed && idle && now - last_drive_ms >= kQuietMs && now - last_unsettled_ms >= kQuietMs)
      break;
  }
  r.final_error_deg = std::fabs(sim.plant(AxisId::kAz).theta_deg() - target);
  if (r.final_error_deg <= kToleranceDeg)
    r.settle_s = static_cast<double>(last_unsettled_ms + kTickMs - command_ms) / 1000.0;
  return r;
}

std::vector<Scenario> scenarios_for(const sim::Profile& p) {
  std::vector<Scenario> list;
  const double start = std::max(p.az.min_deg, 0.0) + 5.0;
  for (double d : kMoveSetDeg) list.push_back({Kind::kMove, start, start + d});
  // Through the overlap threshold (360) into the CW overlap, where there is one.
  if (p.az.max_deg > 360.0 + 60.0) list.push_back({Kind::kOverlap, 300.0, 420.0});
  // 180 deg commanded, turned back to start + 20 once 45 deg have been covered.
  list.push_back({Kind::kReversal, start, start + 180.0, start + 45.0, start + 20.0});
  return list;
}

struct Scored {
  double bound_s = 0;
  double efficiency = 0;
  int corrections = 0;
};

Scored score(const sim::Profile& p, const Scenario& sc, const Run& r) {
  double distance = std::fabs(sc.target_deg - sc.start_deg);
  Scored q;
  q.bound_s = bound_s(p.az, distance);
  if (sc.kind == Kind::kReversal) {
    // Stop from full speed, then the shortest move back (approximate:
    // the two phases are not merged into one optimal profile).
    distance =
        std::fabs(r.reversal_command_theta_deg + stop_distance_deg(p.az) - sc.second_target_deg);
    q.bound_s = stop_time_s(p.az) + bound_s(p.az, distance);
  }
  q.efficiency = std::isfinite(r.settle_s) ? q.bound_s / r.settle_s : 0.0;
  // A reversal needs a second start by design.
  const int expected_starts = sc.kind == Kind::kReversal ? 2 : 1;
  q.corrections = std::max(0, r.starts - expected_starts);
  return q;
}

std::string label(const Scenario& sc) {
  return std::string(kKindNames[static_cast<int>(sc.kind)]) + "_" +
         std::to_string(static_cast<int>(std::fabs(sc.target_deg - sc.start_deg)));
}

}  // namespace

std::vector<MoveQuality> rotord_move_quality(const sim::Profile& p,
                                             const settings::Settings& settings) {
  std::vector<MoveQuality> out;
  for (const Scenario& sc : scenarios_for(p)) {
    const Run r = run_one(p, Controller_::kRotord, sc, &settings);
    const Scored q = score(p, sc, r);
    out.push_back(
        {label(sc), q.bound_s, r.settle_s, q.efficiency, r.final_error_deg, q.corrections});
  }
  return out;
}

std::vector<Result> run_control_quality() {
  std::vector<Result> results;
  for (const sim::Profile* p : sim::all_profiles()) {
    for (const Scenario& sc : scenarios_for(*p)) {
      for (int c = 0; c < 3; ++c) {
        const Run r = run_one(*p, static_cast<Controller_>(c), sc);
        const Scored q = score(*p, sc, r);
        Result res;
        res.name = std::string("control/") + kControllerNames[c] + "/" + p->name + "/" + label(sc);
        res.inputs = {
            {"start_deg", sc.start_deg},
            {"target_deg", sc.kind == Kind::kReversal ? sc.second_target_deg : sc.target_deg},
            {"distance_deg", std::fabs(sc.target_deg - sc.start_deg)},
            {"tolerance_deg", kToleranceDeg},
            {"seed", static_cast<double>(kSeed)}};
        res.metrics = {{"settle_s", r.settle_s},
                       {"bound_s", q.bound_s},
                       {"efficiency", q.efficiency},
                       {"final_error_deg", r.final_error_deg},
                       {"overshoot_deg", r.overshoot_deg},
                       {"corrections", static_cast<double>(q.corrections)},
                       {"reversals", static_cast<double>(r.reversals)},
                       {"relay_switchings", static_cast<double>(r.relay_switchings)}};
        results.push_back(std::move(res));
      }
    }
  }
  return results;
}

}  // namespace rotord::bench
