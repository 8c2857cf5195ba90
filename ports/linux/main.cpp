#include <CLI/CLI.hpp>
#include <set>
#include <string>

#include "daemon.hpp"
#include "log.hpp"
#include "outputs_off.hpp"
#include "predict_cli.hpp"
#include "print_config.hpp"

int main(int argc, char** argv) {
  rotord::linux_port::Options o;
  CLI::App app{"rotord: antenna rotator controller (simulated rotator by default)"};
  app.add_option("--config", o.config_path, "Settings file (JSON)");
  app.add_option("--hw", o.hw,
                 "Hardware: sim (the simulated rotator --sim) or gpiod (Raspberry Pi GPIO lines "
                 "and IIO ADCs from the gpiod.* and iio.* settings, see docs/gpiod.md)")
      ->check(CLI::IsMember({"sim", "gpiod"}))
      ->capture_default_str();
  app.add_option("--sim", o.sim_profile, "Simulated rotator: g5500, ham4 or spid")
      ->capture_default_str();
  app.add_option("--speedup", o.speedup, "Run simulated time N times faster than the wall clock")
      ->check(CLI::Range(0.01, 1000.0))
      ->capture_default_str();
  app.add_option("--clock", o.clock,
                 "wall: controller time follows the wall clock (times --speedup); manual: it "
                 "stands still until 'advance <ms>' arrives on standard input (tests own the "
                 "clock; simulator only)")
      ->check(CLI::IsMember({"wall", "manual"}))
      ->capture_default_str();
  app.add_option("--utc-start", o.utc_start,
                 "Under --clock manual or --speedup: the UTC at controller time 0 "
                 "(e.g. 2019-12-09T16:00:00Z; default the system clock at start), so "
                 "tracking runs on simulated time");
  app.add_option("--sim-seed", o.sim_seed, "Seed of the simulator's noise (same seed, same run)")
      ->capture_default_str();
  app.add_option("--sim-sensor-mount", o.sim_sensor_mount_deg,
                 "Degrees the simulated azimuth's MA3 encoder and magnetometer read ahead of the "
                 "antenna's bearing (a sensor mounted off north; self-commissioning's known "
                 "bearing finds it)")
      ->check(CLI::Range(-360.0, 360.0))
      ->capture_default_str();
  app.add_option("--bind", o.bind,
                 "Address to listen on (:: serves IPv6 and IPv4; 0.0.0.0 IPv4 only)")
      ->capture_default_str();
  const auto port = CLI::Range(0, 65535);
  app.add_option("--web-port", o.web_port, "Web UI and REST API port (0 disables)")
      ->check(port)
      ->capture_default_str();
  // --KEY-port: one per row of the protocol registry; --pty and --serial
  // name the rows' keys (nothing here lists the protocols).
  std::string keys;
  for (const rotord::protocol::ProtocolInfo& p : rotord::protocol::protocols()) {
    keys += (keys.empty() ? "" : ", ") + std::string(p.key);
    std::string help = std::string(p.name) + " port (0 disables)";
    if (p.personality == rotord::protocol::Personality::kConsole)
      help += "; off unless given (the console changes settings: prefer --pty console)";
    else if (!p.tcp_by_default)
      help += "; off unless given (the Pico W uses " + std::to_string(p.tcp_port) + ")";
    app.add_option("--" + std::string(p.key) + "-port",
                   o.line_ports[static_cast<std::size_t>(p.personality)], help)
        ->check(port)
        ->capture_default_str();
  }
  app.add_option("--pty", o.ptys,
                 "Serve a protocol on a new pseudo-terminal, PERSONALITY[:LINK] (" + keys +
                     "); rotord prints its path and makes LINK a symlink to it. Repeatable")
      ->take_all()
      ->allow_extra_args(false);
  app.add_option("--serial", o.serials,
                 "Serve a protocol on a serial device, PERSONALITY:DEVICE[:BAUD], e.g. "
                 "easycomm:/dev/ttyUSB0:19200. Repeatable")
      ->take_all()
      ->allow_extra_args(false);
  app.add_option("--log-level", o.log_level,
                 "Least important messages logged: error, warn, info or debug (connections, "
                 "late ticks)")
      ->check(CLI::IsMember({"error", "warn", "info", "debug"}))
      ->capture_default_str();
  app.add_option("--log-format", o.log_format,
                 "text (\"rotord: ...\" lines) or json (one object per line: time, level, msg)")
      ->check(CLI::IsMember({"text", "json"}))
      ->capture_default_str();
  app.add_option("--avahi", o.avahi,
                 "on: announce the web UI (_http._tcp) and rotctld (_rotctld._tcp, the other "
                 "ports as TXT records) through avahi-daemon when it runs; off: do not")
      ->check(CLI::IsMember({"on", "off"}))
      ->capture_default_str();
  bool print_config = false;
  app.add_flag("--print-config", print_config,
               "Print the settings rotord would run with and where each comes from (default, "
               "profile, file), the options and the settings file, then exit");
  bool outputs_off = false;
  app.add_flag("--outputs-off", outputs_off,
               "Drive every output the settings wire off (GPIO lines inactive and released, PWM "
               "duty 0 and disabled), then exit: the systemd unit's ExecStopPost, after any "
               "exit of rotord, kill -9 included")
      ->excludes("--print-config");
  // Subcommands that use the tracking layer and exit, no daemon started.
  rotord::linux_port::PredictOptions predict;
  const auto commands = rotord::linux_port::add_predict_commands(app, predict);
  app.require_subcommand(0, 1);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int rc = app.exit(e);
    // Bad input to predict/passes exits 2 (help stays 0); the daemon keeps CLI11's codes.
    const bool subcommand =
        argc > 1 && (std::string(argv[1]) == "predict" || std::string(argv[1]) == "passes");
    return subcommand && rc != 0 ? 2 : rc;
  }
  if (commands.predict->parsed()) return rotord::linux_port::run_predict(predict);
  if (commands.passes->parsed()) return rotord::linux_port::run_passes(predict);
  if (print_config) {
    std::set<std::string> given;
    for (const CLI::Option* option : app.get_options()) {
      if (option->count() > 0) given.insert(option->get_name());
    }
    return rotord::linux_port::print_config(o, given, stdout);
  }
  namespace log = rotord::linux_port::log;
  log::Level level = log::Level::kInfo;
  log::parse_level(o.log_level, level);
  log::configure(level, o.log_format == "json" ? log::Format::kJson : log::Format::kText,
                 log::stdio_is_journal());
  if (outputs_off) return rotord::linux_port::run_outputs_off(o);
  rotord::linux_port::Daemon daemon(o);
  return daemon.run();
}
