#include "web/care_api.hpp"

#include <cmath>

#include "care/odometer_record.hpp"
#include "command/care_commands.hpp"
#include "util/utc_time.hpp"

namespace rotord::web {
namespace {

using care::AxisWear;
using settings::Id;

constexpr AxisId kAxes[] = {AxisId::kAz, AxisId::kEl};
constexpr const char* kAxisLabels[] = {"az", "el"};

void write_reset_date(JsonWriter& w, const care::Odometer& o) {
  w.key("reset_utc");
  char utc[32];
  const std::size_t n =
      o.reset_unix_s() > 0 ? format_utc_iso8601(o.reset_unix_s() * 1000, utc, sizeof utc) : 0;
  if (n > 0) {
    w.string(std::string_view(utc, n));
  } else {
    w.null();  // never reset, or the clock was unknown then
  }
}

/// The ceiling's part of an axis: its starts in the sliding hour and, while
/// a go-to waits for it, the tolerance it waits at.
void write_ceiling(JsonWriter& w, const Controller& c, AxisId id, const AxisStatus& a) {
  w.member("starts_last_hour", c.start_ceiling(id).starts_in_hour())
      .member("starts_held", c.starts_held(id))
      .member("start_held", a.start_held);
  w.key("widened_tolerance_deg");
  if (a.start_held) {
    w.number(std::fabs(a.target_deg - a.position_deg));
  } else {
    w.null();
  }
}

void write_axis_summary(JsonWriter& w, const AxisWear& wear) {
  w.begin_object()
      .member("starts", wear.starts)
      .member("reversals", wear.reversals)
      .member("run_s", static_cast<long long>(wear.run_ms / 1000))
      .member("turned_deg", wear.turned_deg)
      .member("brake_cycles", wear.brake_cycles)
      .member("relay_switchings", wear.relay_switchings)
      .member("faults_total", wear.faults_total());
  w.key("faults").begin_object();
  for (std::size_t k = 1; k < kAxisFaultKinds; ++k)
    if (wear.faults[k] != 0) w.member(care::fault_key(static_cast<AxisFault>(k)), wear.faults[k]);
  w.end_object();
}

}  // namespace

void write_odometer_status(JsonWriter& w, const Controller& c) {
  const RotatorStatus s = c.status();
  const care::Odometer& o = c.odometer();
  w.key("odometer").begin_object();
  write_reset_date(w, o);
  w.member("max_starts_h", c.settings().i(Id::kCareMaxStartsH));
  for (std::size_t n = 0; n < 2; ++n) {
    const AxisStatus& a = n == 0 ? s.az : s.el;
    w.key(kAxisLabels[n]);
    if (!a.present) {
      w.null();
      continue;
    }
    write_axis_summary(w, o.axis(kAxes[n]).wear());
    write_ceiling(w, c, kAxes[n], a);
    w.end_object();
  }
  w.end_object();
}

Api::Outcome get_odometer(Api& api, const Api::Call& call) {
  const Controller& c = api.controller();
  send_json(call.out, 200, call.options, [&](JsonWriter& w) {
    const RotatorStatus s = c.status();
    w.begin_object();
    write_reset_date(w, c.odometer());
    w.member("max_starts_h", c.settings().i(Id::kCareMaxStartsH));
    for (std::size_t n = 0; n < 2; ++n) {
      w.key(kAxisLabels[n]);
      if (!(n == 0 ? s.az : s.el).present) {
        w.null();
        continue;
      }
      care::write_wear(w, c.odometer().axis(kAxes[n]).wear());
    }
    w.end_object();
  });
  return Api::Outcome::kDone;
}

Api::Outcome post_odometer_reset(Api& api, const Api::Call& call) {
  // The port's saver writes a reset at once (care::OdometerSaver::poll).
  command::reset_odometer(api.controller(), {"rest", call.peer});
  return get_odometer(api, call);
}

namespace {

/// The starts ceiling (care.max_starts_h): starts counted, go-tos held.
void write_starts_ceiling_metrics(metrics::PrometheusWriter& w, const Controller& c,
                                  std::size_t count) {
  w.family("rotord_starts_last_hour", "gauge",
           "Motor starts in the sliding hour the starts ceiling counts (care.max_starts_h).");
  for (std::size_t n = 0; n < count; ++n)
    w.integer({{"axis", kAxisLabels[n]}}, c.start_ceiling(kAxes[n]).starts_in_hour());
  w.family("rotord_starts_ceiling_held_total", "counter",
           "Go-tos held at rest because another start would pass care.max_starts_h (the "
           "tolerance widened meanwhile).");
  for (std::size_t n = 0; n < count; ++n)
    w.integer({{"axis", kAxisLabels[n]}}, c.starts_held(kAxes[n]));
  w.family("rotord_starts_ceiling_holding", "gauge", "1 while a go-to waits for the ceiling.");
  const RotatorStatus s = c.status();
  for (std::size_t n = 0; n < count; ++n)
    w.integer({{"axis", kAxisLabels[n]}}, (n == 0 ? s.az : s.el).start_held ? 1 : 0);
}

}  // namespace

void write_care_metrics(metrics::PrometheusWriter& w, const Controller& c,
                        const metrics::Registry* registry) {
  const std::size_t count = c.has_el() ? 2 : 1;
  struct Family {
    const char* name;
    const char* help;
    std::uint32_t AxisWear::*count;
  };
  static constexpr Family kFamilies[] = {
      {"rotord_odometer_starts_total",
       "Motor starts since the odometer's reset (kept across restarts).", &AxisWear::starts},
      {"rotord_odometer_reversals_total", "Starts in the other direction than the one before.",
       &AxisWear::reversals},
      {"rotord_odometer_turned_degrees_total", "Whole degrees turned under power and coasting.",
       &AxisWear::turned_deg},
      {"rotord_odometer_brake_cycles_total", "Brake releases.", &AxisWear::brake_cycles},
      {"rotord_odometer_relay_switchings_total", "Relay closures, every relay of the axis.",
       &AxisWear::relay_switchings},
  };
  for (const Family& f : kFamilies) {
    w.family(f.name, "counter", f.help);
    for (std::size_t n = 0; n < count; ++n)
      w.integer({{"axis", kAxisLabels[n]}}, c.odometer().axis(kAxes[n]).wear().*f.count);
  }
  w.family("rotord_odometer_run_seconds_total", "counter", "Time the motor was driven.");
  for (std::size_t n = 0; n < count; ++n)
    w.value({{"axis", kAxisLabels[n]}},
            static_cast<double>(c.odometer().axis(kAxes[n]).wear().run_ms) / 1000.0);
  w.family("rotord_odometer_faults_total", "counter",
           "Faults latched since the odometer's reset (kept across restarts), by kind.");
  for (std::size_t n = 0; n < count; ++n) {
    const AxisWear& wear = c.odometer().axis(kAxes[n]).wear();
    for (std::size_t k = 1; k < kAxisFaultKinds; ++k)
      w.integer({{"axis", kAxisLabels[n]}, {"kind", care::fault_key(static_cast<AxisFault>(k))}},
                wear.faults[k]);
  }
  w.family("rotord_odometer_reset_timestamp_seconds", "gauge",
           "Unix time of the odometer's last reset; 0: never reset, or the clock was unknown.");
  w.integer({}, static_cast<std::uint64_t>(c.odometer().reset_unix_s()));
  write_starts_ceiling_metrics(w, c, count);
  if (registry != nullptr && registry->odometer_writes != nullptr &&
      registry->odometer_failures != nullptr) {
    w.family("rotord_odometer_saves_total", "counter",
             "Odometer records written (a file on Linux; a flash sector erased on the Pico W).");
    w.integer({}, *registry->odometer_writes);
    w.family("rotord_odometer_save_failures_total", "counter", "Odometer writes that failed.");
    w.integer({}, *registry->odometer_failures);
  }
}

}  // namespace rotord::web
