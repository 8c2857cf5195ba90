#include "protocol/console_session.hpp"

#include <algorithm>
#include <cstdio>
#include <cstring>

#include "command/calibration.hpp"
#include "command/settings_commands.hpp"
#include "command/typed.hpp"
#include "protocol/console_reply.hpp"
#include "rotator/controller.hpp"
#include "util/slice.hpp"
#include "util/text.hpp"

namespace rotord::protocol {
namespace {

using console::Echo;
using console::error;
using console::send;
using console::Value;
using settings::Id;

int length(std::string_view s) {
  return static_cast<int>(s.size());
}

const char* flag(bool on) {
  return on ? "1" : "0";
}

}  // namespace

// The command table, in the order of docs/protocols/console.md.
using C = ConsoleSession;
constexpr ConsoleSession::Command ConsoleSession::kCommands[] = {
    {"help", "help", &C::help, "list the commands", false},
    {"status", "status", &C::status, "position, raw sensor value, state and fault of each axis",
     false},
    {"get", "get <key>", &C::get, "one setting's value", false},
    {"list", "list [prefix]", &C::list, "every setting (whose key starts with prefix), one a line",
     false},
    {"set", "set <key> <value>", &C::set, "change a setting (saved like the web's changes)", true},
    {"export", "export", &C::export_settings,
     "the settings you changed, as one JSON line (no passwords)", false},
    {"import", "import <json>", &C::import_settings, "apply a JSON settings object, all or nothing",
     true},
    {"cal", "cal <az|el> <lo|hi>", &C::calibrate,
     "the axis stands at its low/high stop: the sensor's reading becomes that calibration point",
     true},
    {"bearing", "bearing <place> [short|long]", &C::bearing,
     "bearing and distance to a locator or <lat> <lon> (no move)", false},
    {"turn", "turn <place> [short|long]", &C::turn, "turn the beam to a locator or <lat> <lon>",
     true},
    {"presets", "presets", &C::presets, "the named headings (set them with set preset.N)", false},
    {"preset", "preset <name>", &C::preset, "turn the beam to a named heading", true},
    {"setup", "setup models | setup model <id> | setup station <locator or lat lon>", &C::setup,
     "list the rotator models, fill the settings from one (docs/rotator_models.md), or set the "
     "station's position",
     true},
    {"commission", "commission <az|el> [step] [ccw_deg cw_deg | deg] | status | accept",
     &C::commission,
     "self-commissioning: start a step (all, direction, ends, speeds, bearing), its result, accept "
     "it",
     false},
    {"odometer", "odometer [reset]", &C::odometer,
     "the wear odometer of each axis; reset: every count to zero, dated", false},
    {"wind", "wind [override [minutes] | stow]", &C::wind,
     "the wind stow: state, speed, counts; override: obey moves for a time; stow: end the "
     "override",
     false},
    {"stop", "stop", &C::stop, "stop every motion", false},
    {"reset", "reset", &C::reset, "stop, clear latched faults", true},
    {"reboot", "reboot", &C::reboot, "restart the controller (settings are saved first)", true},
    {"bootsel", "bootsel", &C::bootsel,
     "Pico: reboot into the USB bootloader for a firmware update", true},
};

std::span<const ConsoleSession::Command> ConsoleSession::commands() {
  return kCommands;
}

void ConsoleSession::receive(std::string_view bytes, ByteSink& out) {
  feed(bytes, out);
}

void ConsoleSession::feed(std::string_view bytes, ByteSink& out) {
  while (!bytes.empty()) {
    if (output_pending()) {
      // A listing is going out: what follows waits for it.
      const std::size_t n = std::min(bytes.size(), hold_.size() - held_);
      std::memcpy(hold_.data() + held_, bytes.data(), n);
      held_ += n;
      hold_dropped_ += bytes.size() - n;
      return;
    }
    // One line at a time, so a command after a listing waits for it.
    const std::size_t end = bytes.find_first_of("\r\n");
    const std::size_t n = end == std::string_view::npos ? bytes.size() : end + 1;
    lines_.feed(text::slice(bytes, 0, n), [&](std::string_view line, bool overflowed) {
      if (overflowed) {
        char reason[64];
        std::snprintf(reason, sizeof reason, "line too long (at most %u bytes)",
                      static_cast<unsigned>(kMaxLineLength));
        return error(out, reason);
      }
      handle_line(line, out);
    });
    bytes = text::slice(bytes, n);
  }
}

void ConsoleSession::handle_line(std::string_view line, ByteSink& out) {
  line = text::trim(line);
  if (line.empty()) return;
  std::string_view rest = line;
  const std::string_view word = text::next_token(rest);
  // The arguments as typed after the word and its spaces (set's value keeps
  // inner and trailing spaces: an SSID may have them).
  while (!rest.empty() && (rest.front() == ' ' || rest.front() == '\t')) rest.remove_prefix(1);
  for (const Command& c : kCommands) {
    if (!text::iequals(word, c.name)) continue;
    if (c.changes_state && !may_control(controller_, c.name))
      return error(out, console::kNotInControl);
    return (this->*c.run)(rest, out);
  }
  const Echo echo(word);
  send(out, "error: unknown command '%s' (help lists the commands)", echo.text);
}

void ConsoleSession::help(std::string_view, ByteSink& out) {
  for (const Command& c : kCommands)
    send(out, "%-22.*s %.*s", length(c.usage), c.usage.data(), length(c.help), c.help.data());
  send(out, "ok");
}

void ConsoleSession::status(std::string_view, ByteSink& out) {
  const RotatorStatus s = controller_.status();
  const char* board = port_ != nullptr && port_->board[0] != '\0' ? port_->board : "rotord";
  send(out, "rotord %s (%s)", version_, board);
  send(out, "mode=%s speed_pct=%d estop=%s control=%s", mode_name(s.mode), s.speed_pct,
       flag(controller_.estop_active()), command::in_control(controller_, peer()) ? "yes" : "no");
  const auto axis = [&](const char* name, const AxisStatus& a) {
    char target[16] = "-";
    if (a.has_target)
      std::snprintf(target, sizeof target, "%.1f", static_cast<double>(a.target_deg));
    send(out,
         "%s position_deg=%.1f valid=%s raw=%.0f target_deg=%s state=%s fault=%s "
         "limit_cw=%s limit_ccw=%s",
         name, static_cast<double>(a.position_deg), flag(a.position_valid),
         static_cast<double>(a.raw), target, axis_state_name(a.state), axis_fault_name(a.fault),
         flag(a.limit_cw), flag(a.limit_ccw));
  };
  axis("az", s.az);
  if (s.el.present) axis("el", s.el);
  send(out, "ok");
}

void ConsoleSession::get(std::string_view args, ByteSink& out) {
  const std::string_view key = text::trim(args);
  if (key.empty()) return error(out, "usage: get <key> (list shows every setting)");
  const std::optional<Id> id = settings::find(key);
  if (!id) {
    const Echo echo(key);
    return send(out, "error: unknown setting '%s' (list shows every setting)", echo.text);
  }
  const Value value(controller_.settings(), *id);
  send(out, "ok %s=%s", settings::def(*id).key, value.text);
}

void ConsoleSession::list(std::string_view args, ByteSink& out) {
  start_listing(Listing::kList, text::trim(args), out);
}

void ConsoleSession::set(std::string_view args, ByteSink& out) {
  std::string_view value = args;
  const std::string_view key = text::next_token(value);
  if (!value.empty()) value.remove_prefix(1);  // the one separator after the key
  if (key.empty() || (value.empty() && args.find_first_of(" \t") == std::string_view::npos))
    return error(out, "usage: set <key> <value> (\"\" for an empty text)");
  if (value == "\"\"") value = {};
  const std::optional<Id> id = settings::find(key);
  if (!id) {
    const Echo echo(key);
    return send(out, "error: unknown setting '%s' (list shows every setting)", echo.text);
  }
  // Who may write it (never the access rules; a password only over USB or
  // serial) and the checks are the command layer's (settings_commands.hpp).
  const settings::Def& def = settings::def(*id);
  const command::SetResult r =
      command::set_setting(controller_, origin(), command::line_writer(peer()), *id, value);
  if (r.status == command::SetResult::kRefused)
    return send(out,
                r.refusal == command::Refusal::kPassword
                    ? "error: %s is a password: set it over USB or serial, not the network"
                    : "error: %s is set through the web only",
                def.key);
  if (r.status != command::SetResult::kOk) return send(out, "error: %s: %s", def.key, r.reason);
  const Value now(controller_.settings(), *id);
  send(out, "ok %s=%s%s", def.key, now.text,
       (def.flags & settings::kRestart) != 0 ? " (takes effect after a reboot)" : "");
}

void ConsoleSession::export_settings(std::string_view args, ByteSink& out) {
  if (!text::trim(args).empty()) return error(out, "usage: export");
  if (export_base() == nullptr) return error(out, "export is not available on this port");
  start_listing(Listing::kExport, {}, out);
}

void ConsoleSession::import_settings(std::string_view args, ByteSink& out) {
  const std::string_view json = text::trim(args);
  if (json.empty()) return error(out, "usage: import {\"key\": value, ...}");
  if (port_ == nullptr || port_->scratch == nullptr)
    return error(out, "import is not available on this port");
  // Every key is checked before anything changes: one this client may not
  // write refuses the whole document.
  web::SettingErrors errors;
  const command::SetResult r =
      command::set_settings(controller_, origin(), command::line_writer(peer()), json,
                            {*port_->scratch, errors}, nullptr);
  if (r.status == command::SetResult::kRefused)
    return send(out,
                "error: %s cannot be imported here (web only, or a password over the "
                "network): remove it",
                settings::def(r.key).key);
  if (r.status == command::SetResult::kBadJson)
    return send(out, "error: invalid JSON: %s", r.reason);
  if (r.status != command::SetResult::kOk) {
    for (std::size_t n = 0; n < errors.size(); ++n)
      send(out, "  %s: %s", errors[n].key, errors[n].reason);
    return send(out, "error: nothing changed: %s", r.reason);
  }
  int changed = 0;
  bool restart = false;
  for (std::size_t n = 0; n < settings::kCount; ++n) {
    if (!r.changed[n]) continue;
    ++changed;
    restart = restart || (settings::def(static_cast<Id>(n)).flags & settings::kRestart) != 0;
  }
  send(out, "ok %d settings changed%s", changed,
       restart ? " (some take effect after a reboot)" : "");
}

void ConsoleSession::calibrate(std::string_view args, ByteSink& out) {
  std::string_view rest = args;
  const std::string_view axis_word = text::next_token(rest);
  const std::string_view point_word = text::next_token(rest);
  const bool az = text::iequals(axis_word, "az");
  const bool lo = text::iequals(point_word, "lo");
  if ((!az && !text::iequals(axis_word, "el")) || (!lo && !text::iequals(point_word, "hi")) ||
      !text::trim(rest).empty())
    return error(out, "usage: cal <az|el> <lo|hi>");
  const Error e = command::calibrate(controller_, origin(), az ? AxisId::kAz : AxisId::kEl,
                                     lo ? command::CalPoint::kLo : command::CalPoint::kHi);
  switch (e) {
    case Error::kOk:
      return send(out, "ok %s %s point set from the sensor's present reading", az ? "az" : "el",
                  lo ? "lo" : "hi");
    case Error::kFaulted:
      return error(out, "the sensor's reading is not valid now: nothing changed");
    case Error::kOutOfRange:
      return error(out, "the two calibration points would be the same: nothing changed");
    default:
      return error(out, az || controller_.has_el()
                            ? "this axis's sensor has no such point (pot: lo and hi; MA3: lo only)"
                            : "there is no elevation axis");
  }
}

void ConsoleSession::stop(std::string_view, ByteSink& out) {
  command::stop(controller_, origin());
  send(out, "ok stopped");
}

void ConsoleSession::reset(std::string_view, ByteSink& out) {
  if (command::reset(controller_, origin()) != Error::kOk)
    return error(out, "the emergency stop is active: release it, then reset");
  send(out, "ok stopped, faults cleared");
}

void ConsoleSession::reboot(std::string_view, ByteSink& out) {
  const command::Restart r =
      command::reboot(controller_, origin(), port_ == nullptr ? nullptr : port_->system);
  if (!r.ok()) return error(out, r.why);
  send(out, "ok rebooting");
}

void ConsoleSession::bootsel(std::string_view, ByteSink& out) {
  const command::Restart r = command::reboot_to_bootloader(
      controller_, origin(), port_ == nullptr ? nullptr : port_->system);
  if (!r.ok()) return error(out, r.why);
  send(out, "ok rebooting into the USB bootloader: copy the .uf2 onto the RPI-RP2 drive");
}

}  // namespace rotord::protocol
