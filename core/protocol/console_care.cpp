// The console's wear odometer (issue 27, docs/care.md): the counts of each
// axis, and their reset (dated, written to storage at once by the port's
// saver), as GET /api/odometer and POST /api/odometer/reset.
#include <cstdio>

#include "care/odometer_record.hpp"
#include "command/care_commands.hpp"
#include "protocol/console_reply.hpp"
#include "protocol/console_session.hpp"
#include "rotator/controller.hpp"
#include "util/slice.hpp"
#include "util/text.hpp"
#include "util/utc_time.hpp"

namespace rotord::protocol {
using console::send;

void ConsoleSession::odometer(std::string_view args, ByteSink& out) {
  args = text::trim(args);
  if (!args.empty() && !text::iequals(args, "reset"))
    return send(out, "error: odometer takes nothing or 'reset'");
  care::Odometer& o = controller_.odometer();
  if (!args.empty()) {
    if (!may_control(controller_, "odometer reset"))
      return send(out, "error: read-only: this client may not reset the odometer");
    command::reset_odometer(controller_, origin());
  }
  char date[40] = "never (or the clock was unknown)";
  if (o.reset_unix_s() > 0) {
    const std::size_t n = format_utc_iso8601(o.reset_unix_s() * 1000, date, sizeof date);
    date[n < sizeof date ? n : sizeof date - 1] = '\0';
  }
  send(out, "odometer reset %s", date);
  const RotatorStatus s = controller_.status();
  for (const AxisId id : {AxisId::kAz, AxisId::kEl}) {
    if (!(id == AxisId::kAz ? s.az : s.el).present) continue;
    const care::AxisWear& w = o.axis(id).wear();
    send(out,
         "%s starts=%lu reversals=%lu run_s=%lu turned_deg=%lu brake_cycles=%lu "
         "relay_switchings=%lu faults=%lu",
         id == AxisId::kAz ? "az" : "el", static_cast<unsigned long>(w.starts),
         static_cast<unsigned long>(w.reversals), static_cast<unsigned long>(w.run_ms / 1000),
         static_cast<unsigned long>(w.turned_deg), static_cast<unsigned long>(w.brake_cycles),
         static_cast<unsigned long>(w.relay_switchings),
         static_cast<unsigned long>(w.faults_total()));
    for (std::size_t k = 1; k < kAxisFaultKinds; ++k)
      if (w.faults[k] != 0)
        send(out, "%s faults.%s=%lu", id == AxisId::kAz ? "az" : "el",
             care::fault_key(static_cast<AxisFault>(k)), static_cast<unsigned long>(w.faults[k]));
  }
  send(out, "ok");
}

void ConsoleSession::wind(std::string_view args, ByteSink& out) {
  args = text::trim(args);
  const care::WindStow& w = controller_.wind();
  if (!args.empty()) {
    const std::size_t space = args.find(' ');
    const std::string_view verb = text::slice(args, 0, space);
    const std::string_view rest =
        space == std::string_view::npos ? std::string_view{} : text::trim(text::slice(args, space));
    if (!text::iequals(verb, "override") && !(text::iequals(verb, "stow") && rest.empty()))
      return send(out, "error: wind takes nothing, 'override [minutes]' or 'stow'");
    if (!may_control(controller_, "wind"))
      return send(out, "error: read-only: this client may not override the wind stow");
    if (text::iequals(verb, "stow")) {
      if (command::end_wind_override(controller_, origin()) != Error::kOk)
        return send(out, "error: no override of a wind stow is running");
    } else {
      long minutes = 0;
      if (!rest.empty() && (!text::parse_int(rest, minutes) || minutes < 1 || minutes > 1440))
        return send(out, "error: minutes must be a whole number 1..1440");
      if (command::wind_override(controller_, origin(), static_cast<int>(minutes)) != Error::kOk)
        return send(out, "error: nothing to override: the antenna is not stowed for the wind");
    }
  }
  static constexpr const char* kSources[] = {"off", "mqtt", "pulses"};
  char speed[24] = "none";
  if (w.has_speed()) std::snprintf(speed, sizeof speed, "%.1f", static_cast<double>(w.speed_mps()));
  const Millis now = controller_.now();
  send(out, "wind source=%s state=%s speed_mps=%s stow_mps=%.1f calm_mps=%.1f stow_az_deg=%.1f",
       kSources[static_cast<std::size_t>(w.config().source)], care::wind_state_name(w.state()),
       speed, static_cast<double>(w.config().stow_mps), static_cast<double>(w.config().calm_mps),
       static_cast<double>(controller_.wind_stow_az_deg()));
  send(out, "wind calm_left_s=%lld override_left_s=%lld stows=%lu overrides=%lu readings=%lu",
       static_cast<long long>(w.calm_left_ms(now) / 1000),
       static_cast<long long>(w.override_left_ms(now) / 1000),
       static_cast<unsigned long>(w.stows()), static_cast<unsigned long>(w.overrides()),
       static_cast<unsigned long>(w.readings()));
  for (std::size_t n = 0; n < care::kWindRejectKinds; ++n) {
    const auto why = static_cast<care::WindReject>(n);
    send(out, "wind rejected.%s=%lu", care::wind_reject_name(why),
         static_cast<unsigned long>(w.rejected(why)));
  }
  send(out, "ok");
}

}  // namespace rotord::protocol
