// The console's wear odometer (issue 27, docs/care.md): the counts of each
// axis, and their reset (dated, written to storage at once by the port's
// saver), as GET /api/odometer and POST /api/odometer/reset.
#include <cstdio>

#include "care/odometer_record.hpp"
#include "protocol/console_reply.hpp"
#include "protocol/console_session.hpp"
#include "rotator/controller.hpp"
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
    if (!may_control(controller_))
      return send(out, "error: read-only: this client may not reset the odometer");
    const std::optional<std::int64_t> utc_ms = controller_.utc_ms();
    o.reset(utc_ms ? *utc_ms / 1000 : 0);
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

}  // namespace rotord::protocol
