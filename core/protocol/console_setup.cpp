// The console's set-up commands (docs/protocols/console.md): the rotator
// model list, the station's position (a locator or lat lon) and
// self-commissioning, so a Pico reached only over USB can be
// put into service from a terminal.
#include <cmath>
#include <cstdio>

#include "command/commission_commands.hpp"
#include "protocol/console_reply.hpp"
#include "protocol/console_session.hpp"
#include "rotator/controller.hpp"
#include "rotator/place.hpp"
#include "settings/rotator_models.hpp"
#include "util/text.hpp"

namespace rotord::protocol {
namespace {

using console::error;
using console::send;

using settings::Id;

using console::kNotInControl;

void report(Controller& controller, ByteSink& out) {
  const Commissioning& c = controller.commissioning();
  const Commissioning::Measured& m = c.measured();
  send(out, "commission %s state=%s step=%s reason=%s", c.axis() == AxisId::kEl ? "el" : "az",
       commissioning_state_name(c.state()), c.phase_name(), c.reason());
  if (m.direction_known) send(out, "direction swapped=%s", m.swapped ? "yes" : "no");
  if (m.ends_known)
    send(out, "ends ccw_reading=%.1f cw_reading=%.1f noise_deg=%.3f",
         static_cast<double>(m.ccw_reading), static_cast<double>(m.cw_reading),
         static_cast<double>(m.noise_deg));
  if (m.speeds_known)
    send(out,
         "speeds creep_deg_s=%.3f fast_deg_s=%.3f coast_s=%.3f backlash_deg=%.2f dead_band=%.3f",
         static_cast<double>(m.creep_deg_s), static_cast<double>(m.fast_deg_s),
         static_cast<double>(m.coast_s), static_cast<double>(m.backlash_deg),
         static_cast<double>(m.dead_band));
  if (c.proposes_swap()) send(out, "propose swap the CW and CCW outputs' pins");
  const settings::Settings& now = controller.settings();
  for (std::size_t n = 0; n < c.proposal_count(); ++n) {
    const Commissioning::Proposal& p = c.proposal(n);
    char proposed[48];
    char current[48];
    settings::Settings::format(p.id, p.value, proposed, sizeof proposed);
    now.format_value(p.id, current, sizeof current);
    send(out, "propose %s=%s (now %s)", settings::def(p.id).key, proposed, current);
  }
}

// The station's position from a Maidenhead locator or a latitude and a
// longitude: wherever a position is asked for, a locator is understood. A
// locator gives its square's centre, kept to 0.0001 deg (about 11 m).
void setup_station(Controller& controller, const command::Origin& from, std::string_view where,
                   ByteSink& out) {
  PlaceQuery q;
  if (const char* why = parse_place(where, q)) return error(out, why);
  const double lat_deg = std::round(q.to.lat_deg * 1e4) / 1e4;
  const double lon_deg = std::round(q.to.lon_deg * 1e4) / 1e4;
  const command::SetResult r = command::set_station(controller, from, lat_deg, lon_deg);
  if (r.status != command::SetResult::kOk) return send(out, "error: nothing changed: %s", r.reason);
  if (q.locator[0] != '\0')
    send(out, "station %s: lat %.4f lon %.4f (the centre of the square)", q.locator, lat_deg,
         lon_deg);
  else
    send(out, "station lat %.4f lon %.4f", lat_deg, lon_deg);
  send(out, "ok");
}

}  // namespace

void ConsoleSession::setup(std::string_view args, ByteSink& out) {
  std::string_view rest = args;
  const std::string_view word = text::next_token(rest);
  const std::string_view id = text::trim(rest);
  if (text::iequals(word, "station") && !id.empty())
    return setup_station(controller_, origin(), id, out);
  if (text::iequals(word, "models") && id.empty()) {
    for (const settings::RotatorModel& m : settings::rotator_models())
      send(out, "%-16s %s", m.id, m.name);
    return send(out, "ok");
  }
  if (!text::iequals(word, "model") || id.empty())
    return error(out,
                 "usage: setup models | setup model <id> | setup station <locator or lat lon>");
  const settings::RotatorModel* model = nullptr;
  for (const settings::RotatorModel& m : settings::rotator_models())
    if (text::iequals(id, m.id)) model = &m;
  if (model == nullptr) return error(out, "unknown model (setup models lists them)");
  const command::SetResult r = command::apply_model(controller_, origin(), *model, nullptr);
  if (r.status != command::SetResult::kOk) return send(out, "error: nothing changed: %s", r.reason);
  settings::ModelSetting rows[settings::kModelSettingCount];
  const std::size_t n = settings::model_settings(*model, rows, settings::kModelSettingCount);
  int filled = 0;
  for (std::size_t k = 0; k < n; ++k) {
    char value[48];
    controller_.settings().format_value(rows[k].id, value, sizeof value);
    const bool known = rows[k].figure->known();
    filled += known ? 1 : 0;
    send(out, "%s=%s %s", settings::def(rows[k].id).key, value,
         known ? rows[k].figure->source : "(not published: kept; commissioning measures it)");
  }
  send(out, "note %s", model->note);
  send(out, "ok %s: %d settings filled (some take effect after a reboot)", model->name, filled);
}

void ConsoleSession::commission(std::string_view args, ByteSink& out) {
  std::string_view rest = args;
  const std::string_view word = text::next_token(rest);
  if (text::iequals(word, "status") && text::trim(rest).empty()) {
    report(controller_, out);
    return send(out, "ok");
  }
  if (!may_control(controller_, "commission")) return error(out, kNotInControl);
  if (text::iequals(word, "accept") && text::trim(rest).empty()) {
    const command::SetResult r = command::accept_commissioning(controller_, origin(), nullptr);
    if (r.status != command::SetResult::kOk)
      return send(out, "error: nothing changed: %s", r.reason);
    return send(out, "ok settings written (pins take effect after a reboot)");
  }
  const bool az = text::iequals(word, "az");
  if (!az && !text::iequals(word, "el"))
    return error(out, "usage: commission <az|el> [step] [ccw_deg cw_deg | deg] | status | accept");
  Commissioning::Request request;
  request.axis = az ? AxisId::kAz : AxisId::kEl;
  const settings::Settings& s = controller_.settings();
  // The ends default to the travel in force (the model's, once chosen).
  request.ccw_stop_deg = s.f(az ? Id::kAzMinDeg : Id::kElMinDeg);
  request.cw_stop_deg = s.f(az ? Id::kAzMaxDeg : Id::kElMaxDeg);
  std::string_view after_step = rest;
  const std::string_view token = text::next_token(after_step);
  double number = 0.0;
  if (!token.empty() && parse_commissioning_step(token.data(), token.size(), request.step)) {
    rest = after_step;
  } else if (!token.empty() && !text::parse_double(token, number)) {
    return error(out, "unknown step (all, direction, ends, speeds or bearing)");
  }
  const std::string_view lo_word = text::next_token(rest);
  const std::string_view hi_word = text::next_token(rest);
  const bool bearing = request.step == Commissioning::Step::kBearing;
  if (bearing) {
    // One number, the bearing the antenna points at now: anything else is
    // refused with the range's reason (NaN is out of it).
    double deg = 0.0;
    const bool one = text::parse_double(lo_word, deg) && hi_word.empty();
    request.bearing_deg = one ? static_cast<float>(deg) : NAN;
  } else if (!lo_word.empty() || !hi_word.empty()) {
    double lo = 0.0;
    double hi = 0.0;
    if (!text::parse_double(lo_word, lo) || !text::parse_double(hi_word, hi) ||
        !text::trim(rest).empty())
      return error(out, "the ends are two numbers in degrees: ccw_deg cw_deg");
    request.ccw_stop_deg = static_cast<float>(lo);
    request.cw_stop_deg = static_cast<float>(hi);
  }
  const char* why = "";
  if (command::commission(controller_, origin(), request, &why) != Error::kOk)
    return send(out, "error: %s", why);
  if (bearing) {
    report(controller_, out);
    return send(out, "ok");
  }
  send(out, "ok commissioning %s started: STOP (stop) aborts it; commission status follows it",
       az ? "az" : "el");
}

}  // namespace rotord::protocol
