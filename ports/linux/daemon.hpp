#pragma once
#include <asio.hpp>
#include <memory>
#include <vector>

#include "avahi_publisher.hpp"
#include "care/odometer_saver.hpp"
#include "clock_control.hpp"
#include "command/buttons.hpp"
#include "command/command_log.hpp"
#include "file_storage.hpp"
#include "gpiod_io.hpp"
#include "loop/tick_scheduler.hpp"
#include "mbed_crypto.hpp"
#include "metrics/registry.hpp"
#include "mqtt_client.hpp"
#include "ntp_state.hpp"
#include "options.hpp"
#include "protocol/console_session.hpp"
#include "protocol/datagram_registry.hpp"
#include "rotator/axis_events.hpp"
#include "rotator/controller.hpp"
#include "rotator/recognition_events.hpp"
#include "serial_transport.hpp"
#include "service_notify.hpp"
#include "settings/settings.hpp"
#include "simulator.hpp"
#include "storage/settings_saver.hpp"
#include "system_wall_clock.hpp"
#include "tcp_server.hpp"
#include "tle_fetcher.hpp"
#include "tracking/tle_catalog.hpp"
#include "udp_server.hpp"
#include "web/web_api.hpp"

namespace rotord::linux_port {

/// The composition root of the Linux daemon: settings, the simulated (or
/// real) hardware, the controller, the protocol servers and the one asio loop
/// that runs the 100 Hz control tick and every socket.
class Daemon final {
 public:
  static constexpr Millis kTickMs = 10;
  /// The most of a 10 ms pass a web login's password hash may take.
  static constexpr std::chrono::milliseconds kHashBudget{3};

  explicit Daemon(const Options& options);
  ~Daemon();
  /// Returns the process exit code.
  int run();

 private:
  bool setup();
  /// --hw gpiod: opens the GPIO chip, its lines and the ADCs from the
  /// settings, or says what is missing.
  bool open_gpiod();
  AxisIo axis_io(AxisId axis);
  /// False: the settings file cannot be used at all (not a regular file).
  bool load_settings(const sim::Profile* profile);
  /// Creates the controller, the REST API and the protocol servers.
  bool start_controller();
  /// POST /api/reboot and the console's `reboot` (through System): the
  /// controller is re-created with the current settings (restart-only
  /// settings take effect), every client reconnects.
  void request_reboot();
  void reboot();
  void add_service(ServiceConfig config);
  /// Opens every --pty and --serial line the first time; after a controller
  /// restart only gives them sessions on the new controller (paths stay).
  bool attach_serial_lines(const std::vector<ServiceConfig>& services);
  /// Listens for every enabled UDP rotor protocol (docs/protocols/udp.md).
  bool start_udp(const asio::ip::address& bind);
  /// Sleeps until the scheduler's next deadline (start + n x kTickMs).
  void schedule_tick();
  void on_tick();
  /// Logs what the last poll of the tick schedule skipped (debug) or restarted (warning).
  void report_late_tick(const TickScheduler::Stats& before) const;
  /// The steady clock in microseconds, the scheduler's time base.
  static std::int64_t steady_us();
  /// The same clock for the core (GET /healthz: the age of the last tick).
  class SteadyClock final : public hal::MonotonicClock {
   public:
    std::int64_t now_us() const override { return steady_us(); }
  };
  void advance_simulation(Millis wall_ms);
  /// One control tick of the simulator at now_ms_ + kTickMs.
  void tick_simulation();
  /// --clock manual: runs `ms` of controller time at once, with the sessions
  /// and the settings saver served after every tick; returns the new time.
  Millis advance_manual_clock(Millis ms);
  /// Work every wake-up does whatever the clock: sessions, saving, reboot.
  void serve(Millis wall_ms);
  Millis wall_ms() const;
  /// The network's clock (sessions' timeouts, admission, logins): the wall
  /// clock, plus under --clock manual every ms the manual clock was advanced,
  /// so a test can run a timeout out without waiting for it.
  Millis network_ms() const { return wall_ms() + network_skip_ms_; }
  /// Stops the motors (safe_stop.hpp), saves a pending change and ends the loop.
  void stop();
  /// The outputs the simulator or the GPIO lines were last given, for the exit log.
  std::string driver_outputs() const;
  /// Saves what the protocols changed (after the saver's quiet time, or at
  /// once when `now`), and says so.
  void save_changed_settings(bool now);
  /// Announces the ports through avahi-daemon (--avahi on), unless rotord
  /// listens on a loopback address nobody else can reach.
  void announce();

  Options options_;
  asio::io_context io_;
  asio::steady_timer timer_;
  /// The loop's wake-ups for the control tick, on an absolute schedule.
  TickScheduler ticks_{kTickMs * 1000};
  SteadyClock steady_clock_;
  /// READY=1, WATCHDOG=1 and STOPPING=1 to systemd (nothing outside it).
  ServiceNotifier notifier_;
  /// Connections, error replies, ticks and saves for GET /metrics; outlives
  /// controller restarts, so counters only reset with the process.
  metrics::Registry metrics_;
  asio::signal_set signals_;
  settings::Settings settings_;
  SystemWallClock wall_clock_;  ///< GET /api/status time_utc
  NtpState ntp_state_;          ///< GET /api/setup "clock": the host's NTP in words
  /// Tracking's UTC: wall_clock_, or start UTC + controller time under
  /// --speedup / --clock manual.
  std::unique_ptr<SimulatedUtcClock> sim_utc_;
  /// The stored TLEs (tles.txt beside the settings file).
  std::unique_ptr<tracking::TleCatalog> tles_;
  std::unique_ptr<FileStorage> tle_storage_;
  /// track.tle_url: a refresh at start, when the URL changes, and every
  /// track.tle_refresh_h hours.
  void refresh_tles();
  std::unique_ptr<TleFetcher> tle_fetcher_;
  std::string tle_url_fetched_;
  std::chrono::steady_clock::time_point next_tle_refresh_{};
  std::string host_name_;  ///< gethostname(): a name the web answers to
  MbedCrypto crypto_;      ///< access control: web password, sessions, tokens
  /// Access control's log lines (logins, failed logins, tokens, the lock).
  class StdoutLog final : public protocol::ByteSink {
   public:
    void write(std::string_view bytes) override;
  } access_log_;
  /// The command layer's lines (one per command that changes something),
  /// as info lines of the journal, within the process's log budget.
  class InfoLog final : public protocol::ByteSink {
   public:
    void write(std::string_view bytes) override;
  } info_log_;
  command::CommandLog command_log_{info_log_};
  settings::Settings defaults_;  ///< table defaults + the profile: what a reset restores
  std::unique_ptr<FileStorage> storage_;
  /// What reading the settings file dropped (the log, GET /api/status).
  web::LoadReport load_report_;
  std::vector<char> saver_buf_;
  /// Between the REST API and storage_; saves settings changed by protocols.
  std::unique_ptr<SettingsSaver> saver_;
  /// The wear odometer's record, odometer.json beside the settings file
  /// (docs/care.md), and its saver (a new one with each controller).
  std::unique_ptr<FileStorage> odometer_storage_;
  std::vector<char> odometer_buf_;
  std::unique_ptr<care::OdometerSaver> odometer_saver_;
  /// Reads the odometer back into a new controller; says why a damaged
  /// record starts again from zero.
  void load_odometer();
  /// Writes the odometer when due (or at once when `now`), and says so.
  void save_odometer(bool now);
  std::unique_ptr<sim::SimRotator> sim_;
  std::unique_ptr<GpiodRotator> gpio_;           ///< --hw gpiod, instead of sim_
  std::unique_ptr<ClockControl> clock_control_;  ///< --clock manual
  int exit_code_ = 0;
  Millis network_skip_ms_ = 0;  ///< see network_ms()
  std::unique_ptr<Controller> controller_;
  /// The manual buttons (gpiod.btn_*), a front end of the command layer:
  /// polled just before each controller tick (tick_controller).
  std::unique_ptr<command::Buttons> buttons_;
  /// One control tick: the buttons, then the controller.
  void tick_controller();
  AxisEvents axis_events_;                // faults and slips, for the log
  RecognitionEvents recognition_events_;  // recognised passes, for the log
  std::unique_ptr<web::Api> api_;
  std::unique_ptr<MqttClient> mqtt_;  ///< mqtt.enabled: on the station's broker
  bool reboot_pending_ = false;
  std::chrono::steady_clock::time_point reboot_at_;
  /// The restart of POST /api/reboot and the console's (`--pty console`)
  /// `reboot`; bootsel is refused: there is no USB bootloader here.
  class System final : public command::SystemHooks {
   public:
    explicit System(Daemon& daemon) : daemon_(daemon) {}
    const char* reboot() override;
    const char* reboot_to_bootloader() override;

   private:
    Daemon& daemon_;
  } system_{*this};
  settings::Settings console_scratch_;  ///< the console's import working copy
  protocol::ConsolePort console_port_{&defaults_, &console_scratch_, &system_, "Linux"};
  std::vector<std::unique_ptr<TcpServer>> servers_;
  std::vector<std::unique_ptr<SerialTransport>> serial_lines_;
  /// The UDP rotor protocols that are enabled (n1mm.*, pst.*), on the
  /// controller of the moment; the servers go before their handlers.
  std::unique_ptr<protocol::DatagramHandlers> datagram_handlers_;
  std::vector<std::unique_ptr<UdpServer>> udp_servers_;
  std::unique_ptr<AvahiPublisher> avahi_;  ///< --avahi on, not bound to loopback
  std::chrono::steady_clock::time_point wall_start_;
  Millis now_ms_ = 0;
};

}  // namespace rotord::linux_port
