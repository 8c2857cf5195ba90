#include "web/metrics_page.hpp"

#include "web/care_api.hpp"
#include "web/wind_api.hpp"

#include <cmath>
#include <cstdio>
#include <utility>

#include "web/recognition_report.hpp"

namespace rotord::web {
namespace {

using metrics::PrometheusWriter;
using metrics::Protocol;

/// The lower-case name the REST status uses too ("sensor_lost").
const char* lower(const char* upper, char* buf, std::size_t cap) {
  std::size_t n = 0;
  for (; upper[n] != '\0' && n + 1 < cap; ++n)
    buf[n] = (upper[n] >= 'A' && upper[n] <= 'Z') ? static_cast<char>(upper[n] + 32) : upper[n];
  buf[n] = '\0';
  return buf;
}

struct AxisView {
  const char* label;
  AxisId id;
  const AxisStatus* status;
};

bool is_sensor_fault(AxisFault f) {
  return f == AxisFault::kSensorLost || f == AxisFault::kSensorRange ||
         f == AxisFault::kSensorJump || f == AxisFault::kNoSensor || f == AxisFault::kSensorStuck;
}

/// One family with a sample per axis and fault kind (no fault excepted).
void write_axis_faults(PrometheusWriter& w, const Controller& c, const AxisView* all,
                       std::size_t count, const char* family, const char* type, const char* help,
                       std::uint64_t (*read)(const Controller&, const AxisView&, AxisFault)) {
  char name[24];
  w.family(family, type, help);
  for (std::size_t n = 0; n < count; ++n) {
    for (std::size_t k = 1; k < kAxisFaultKinds; ++k) {
      const auto kind = static_cast<AxisFault>(k);
      w.integer({{"axis", all[n].label}, {"kind", lower(axis_fault_name(kind), name, sizeof name)}},
                read(c, all[n], kind));
    }
  }
}

void write_axes(PrometheusWriter& w, const Controller& c, const RotatorStatus& s) {
  const AxisView all[] = {{"az", AxisId::kAz, &s.az}, {"el", AxisId::kEl, &s.el}};
  const std::size_t count = s.el.present ? 2 : 1;
  char name[24];

  w.family("rotord_axis_position_degrees", "gauge",
           "Position of the axis (unwrapped, offset applied), degrees.");
  for (std::size_t n = 0; n < count; ++n)
    w.value({{"axis", all[n].label}}, all[n].status->position_deg);
  w.family("rotord_axis_position_valid", "gauge",
           "1 while the position sensor gives a valid reading.");
  for (std::size_t n = 0; n < count; ++n)
    w.integer({{"axis", all[n].label}}, all[n].status->position_valid ? 1 : 0);
  w.family("rotord_axis_target_degrees", "gauge",
           "Target of the current go-to, degrees; NaN without one.");
  for (std::size_t n = 0; n < count; ++n) {
    const AxisStatus& a = *all[n].status;
    w.value({{"axis", all[n].label}}, a.has_target ? static_cast<double>(a.target_deg) : NAN);
  }
  w.family("rotord_axis_speed_degrees_per_second", "gauge",
           "Speed of the axis estimated from its sensor.");
  for (std::size_t n = 0; n < count; ++n)
    w.value({{"axis", all[n].label}}, all[n].status->speed_deg_s);
  w.family("rotord_axis_state", "gauge", "1 for the state the axis is in, 0 for the others.");
  for (std::size_t n = 0; n < count; ++n) {
    for (std::size_t st = 0; st < kAxisStates; ++st) {
      const auto state = static_cast<AxisState>(st);
      w.integer(
          {{"axis", all[n].label}, {"state", lower(axis_state_name(state), name, sizeof name)}},
          all[n].status->state == state ? 1 : 0);
    }
  }
  write_axis_faults(w, c, all, count, "rotord_axis_fault", "gauge",
                    "1 for the fault latched on the axis now (until RESET), 0 for the others.",
                    [](const Controller&, const AxisView& a, AxisFault kind) -> std::uint64_t {
                      return a.status->fault == kind ? 1 : 0;
                    });
  write_axis_faults(w, c, all, count, "rotord_axis_faults_total", "counter",
                    "Faults latched on the axis since the controller started, by kind.",
                    [](const Controller& ctl, const AxisView& a, AxisFault kind) -> std::uint64_t {
                      return ctl.faults_latched(a.id, kind);
                    });
}

// The counters and flags read straight from the controller or the status,
// one integer per axis each.
struct AxisColumn {
  const char* name;
  const char* type;
  const char* help;
  std::uint64_t (*read)(const Controller&, const AxisView&);
};
constexpr AxisColumn kAxisColumns[] = {
    {"rotord_axis_stalls_total", "counter",
     "Stalls (driven, not moving) latched since the controller started; the same as "
     "rotord_axis_faults_total{kind=\"stall\"}.",
     [](const Controller& ctl, const AxisView& a) -> std::uint64_t {
       return ctl.faults_latched(a.id, AxisFault::kStall);
     }},
    {"rotord_axis_moves_total", "counter",
     "Motor starts since the controller started (relay wear, hunting).",
     [](const Controller&, const AxisView& a) -> std::uint64_t { return a.status->moves; }},
    {"rotord_axis_sensor_readings_rejected_total", "counter",
     "Position readings the robust filter turned away since the controller started "
     "(noise bursts, spikes); a sensor going bad shows here before it latches a fault.",
     [](const Controller&, const AxisView& a) -> std::uint64_t {
       return a.status->readings_rejected;
     }},
    {"rotord_axis_slips_total", "counter",
     "Slips since the controller started: the position moved slip.deg at rest with the "
     "outputs off (wind against the brake).",
     [](const Controller&, const AxisView& a) -> std::uint64_t { return a.status->slips; }},
    {"rotord_axis_slipping", "gauge", "1 while a slip goes on.",
     [](const Controller&, const AxisView& a) -> std::uint64_t {
       return a.status->slipping ? 1 : 0;
     }},
    {"rotord_axis_reholds_total", "counter",
     "Go-tos back to the rest heading after a slip (slip.rehold, an axis without a brake) "
     "since the controller started.",
     [](const Controller&, const AxisView& a) -> std::uint64_t { return a.status->reholds; }},
    {"rotord_axis_reholds_refused_total", "counter",
     "Slips not re-held because slip.rehold's limit (3 in 10 min) was reached.",
     [](const Controller&, const AxisView& a) -> std::uint64_t {
       return a.status->reholds_refused;
     }},
};

/// The counters and outputs of each axis (write_axes: its state).
void write_axis_counters(PrometheusWriter& w, const Controller& c, const RotatorStatus& s) {
  const AxisView all[] = {{"az", AxisId::kAz, &s.az}, {"el", AxisId::kEl, &s.el}};
  const std::size_t count = s.el.present ? 2 : 1;
  for (const AxisColumn& col : kAxisColumns) {
    w.family(col.name, col.type, col.help);
    for (std::size_t n = 0; n < count; ++n)
      w.integer({{"axis", all[n].label}}, col.read(c, all[n]));
  }
  w.family("rotord_goto_continuity_total", "counter",
           "Go-tos of a tracker's stream put on the turn continuous with it instead of the "
           "literal one (track.continuity: a pass through north kept in the overlap).");
  w.integer({}, c.continuity_resolved());
  write_recognition_metrics(w, c.recognition());
  w.family("rotord_goto_led_total", "counter",
           "Go-tos of a tracker's stream whose axes the lead rule sent ahead of the target or "
           "left standing within the band (track.stream_lead: fewer motor starts).");
  w.integer({}, c.stream_led());
  w.family("rotord_axis_limit_active", "gauge",
           "1 while that direction is blocked by a limit switch or soft limit.");
  for (std::size_t n = 0; n < count; ++n) {
    w.integer({{"axis", all[n].label}, {"direction", "cw"}}, all[n].status->limit_cw ? 1 : 0);
    w.integer({{"axis", all[n].label}, {"direction", "ccw"}}, all[n].status->limit_ccw ? 1 : 0);
  }
  w.family("rotord_axis_output", "gauge",
           "Output channels as the controller drives them: relays 0 or 1, PWM duty 0..1.");
  for (std::size_t n = 0; n < count; ++n) {
    for (std::size_t ch = 0; ch < kOutputChannelCount; ++ch)
      w.value({{"axis", all[n].label}, {"channel", kOutputChannelNames[ch]}},
              all[n].status->outputs.value[ch]);
  }
}

void write_protocols(PrometheusWriter& w, const metrics::Registry& r) {
  struct Column {
    const char* name;
    const char* type;
    const char* help;
    std::uint64_t metrics::ProtocolCounters::*counter;
  };
  static constexpr Column kColumns[] = {
      {"rotord_connections_accepted_total", "counter", "Connections accepted since start.",
       &metrics::ProtocolCounters::accepted},
      {"rotord_connections_refused_total", "counter",
       "Newcomers refused at the protocol's connection limit.",
       &metrics::ProtocolCounters::refused},
      {"rotord_connections_evicted_total", "counter",
       "Clients dropped to make room for a newcomer.", &metrics::ProtocolCounters::evicted},
      {"rotord_protocol_errors_total", "counter",
       "Error replies sent (WRC ERROR, rotctld RPRT -n, GS-232 ?>, Easycomm AL, seed $ERR, HTTP "
       "4xx/5xx).",
       &metrics::ProtocolCounters::errors},
      {"rotord_auth_failures_total", "counter", "Failed logins and refused credentials.",
       &metrics::ProtocolCounters::auth_failures},
  };
  w.family("rotord_connections", "gauge", "Connections open now, by protocol (TCP).");
  for (std::size_t p = 0; p < metrics::kProtocolCount; ++p) {
    const auto protocol = static_cast<Protocol>(p);
    w.integer({{"protocol", metrics::protocol_label(protocol)}}, r.protocol(protocol).open);
  }
  for (const Column& col : kColumns) {
    w.family(col.name, col.type, col.help);
    for (std::size_t p = 0; p < metrics::kProtocolCount; ++p) {
      const auto protocol = static_cast<Protocol>(p);
      w.integer({{"protocol", metrics::protocol_label(protocol)}},
                r.protocol(protocol).*col.counter);
    }
  }
  w.family("rotord_udp_datagrams_total", "counter",
           "UDP rotor datagrams (N1MM+, PstRotator) by what became of them.");
  for (const protocol::DatagramInfo& info : protocol::datagram_protocols()) {
    for (std::size_t o = 0; o < protocol::kDatagramOutcomeCount; ++o) {
      const auto outcome = static_cast<protocol::DatagramOutcome>(o);
      w.integer({{"protocol", info.key}, {"outcome", protocol::outcome_label(outcome)}},
                r.datagrams(info.personality, outcome));
    }
  }
}

void write_ticks(PrometheusWriter& w, const metrics::TickSource& t) {
  const metrics::TickStats& s = t.stats();
  w.family("rotord_tick_period_seconds", "gauge", "Period the control loop is scheduled at.");
  w.value({}, static_cast<double>(t.period_us()) / 1e6);
  w.family("rotord_ticks_total", "counter", "Control loop ticks run.");
  w.integer({}, s.ticks);
  w.family("rotord_tick_overruns_total", "counter",
           "Ticks skipped because the loop was a whole period or more late.");
  w.integer({}, s.overruns);
  w.family("rotord_tick_rebases_total", "counter",
           "Restarts of the tick schedule after a stall of a second or more.");
  w.integer({}, s.rebases);
  w.histogram_seconds("rotord_tick_lateness_seconds",
                      "How late each tick ran after its deadline (jitter).", s.lateness);
  w.histogram_seconds("rotord_tick_interval_seconds",
                      "Time from one tick to the next (the period as run).", s.interval);
}

}  // namespace

void write_metrics(PrometheusWriter& w, const Controller& controller,
                   const metrics::Registry* registry, const char* version, std::int64_t now_us) {
  const RotatorStatus s = controller.status();
  w.family("rotord_build_info", "gauge", "Always 1; the version is the label.");
  w.integer({{"version", version}}, 1);
  if (registry != nullptr && registry->clock != nullptr) {
    w.family("rotord_uptime_seconds", "gauge", "Time since rotord started.");
    w.value({}, static_cast<double>(now_us - registry->start_us) / 1e6);
  }
  write_axes(w, controller, s);
  write_axis_counters(w, controller, s);
  w.family("rotord_mode", "gauge", "1 for the controller's mode now, 0 for the others.");
  for (const Mode m :
       {Mode::kIdle, Mode::kGoto, Mode::kManual, Mode::kPark, Mode::kTrack, Mode::kStow})
    w.integer({{"mode", mode_name(m)}}, s.mode == m ? 1 : 0);
  w.family("rotord_speed_percent", "gauge", "Commanded speed, 1..100 %.");
  w.integer({}, static_cast<std::uint64_t>(s.speed_pct));
  w.family("rotord_estop_active", "gauge", "1 while the emergency-stop input is active.");
  w.integer({}, controller.estop_active() ? 1 : 0);
  write_care_metrics(w, controller, registry);
  write_wind_metrics(w, controller);
  if (registry == nullptr) return;
  write_protocols(w, *registry);
  if (registry->ticks != nullptr) write_ticks(w, *registry->ticks);
  if (registry->settings_writes != nullptr && registry->settings_failures != nullptr) {
    w.family("rotord_settings_saves_total", "counter",
             "Settings documents written to the file (Linux) or flash (Pico W).");
    w.integer({}, *registry->settings_writes);
    w.family("rotord_settings_save_failures_total", "counter",
             "Settings writes that failed (each retry counts).");
    w.integer({}, *registry->settings_failures);
  }
}

Health check_health(const Controller& controller, const metrics::Registry* registry,
                    std::int64_t now_us) {
  Health h;
  if (registry != nullptr && registry->ticks != nullptr && registry->clock != nullptr) {
    const metrics::TickStats& t = registry->ticks->stats();
    // Before the first tick, the time since the loop started.
    const std::int64_t age_us = now_us - (t.ticks > 0 ? t.last_tick_us : registry->start_us);
    if (age_us > Health::kMaxTickAgeUs) {
      h.ok = false;
      std::snprintf(h.reason, sizeof h.reason, "the control loop has not ticked for %ld ms",
                    static_cast<long>(age_us / 1000));
      return h;
    }
  }
  const RotatorStatus s = controller.status();
  char name[24];
  for (const auto& [label, a] : {std::pair{"az", &s.az}, std::pair{"el", &s.el}}) {
    if (!a->present || !is_sensor_fault(a->fault)) continue;
    h.ok = false;
    std::snprintf(h.reason, sizeof h.reason, "%s position sensor fault: %s", label,
                  lower(axis_fault_name(a->fault), name, sizeof name));
    return h;
  }
  return h;
}

}  // namespace rotord::web
