#include "daemon.hpp"

#include <unistd.h>

#include <csignal>
#include <cstdio>

#include <cstring>

#include "legacy_profile_guess.hpp"
#include "log.hpp"
#include "print_config.hpp"
#include "safe_stop.hpp"
#include "services.hpp"
#include "sysfs_pwm.hpp"
#include "tracking/julian.hpp"

namespace rotord::linux_port {
namespace {

/// Every signal that ends a process by default and that it may catch: each
/// one stops the motors before rotord exits. Left out are the ones the CPU
/// raises for a fault in rotord itself (SIGSEGV, SIGBUS, SIGFPE, SIGILL,
/// SIGTRAP, SIGSYS, SIGABRT): running on after those is undefined, so they
/// end the process like `kill -9` (docs/running.md, "Signals"). SIGPIPE is ignored.
std::vector<int> terminating_signals() {
  std::vector<int> signals = {SIGHUP,  SIGINT,  SIGQUIT,   SIGTERM, SIGUSR1, SIGUSR2,
                              SIGALRM, SIGPOLL, SIGVTALRM, SIGPROF, SIGXCPU, SIGXFSZ};
#ifdef SIGPWR
  signals.push_back(SIGPWR);
#endif
#ifdef SIGSTKFLT
  signals.push_back(SIGSTKFLT);
#endif
  for (int n = SIGRTMIN; n <= SIGRTMAX; ++n) signals.push_back(n);
  return signals;
}

std::string signal_name(int signal) {
  if (signal >= SIGRTMIN && signal <= SIGRTMAX)
    return "SIGRTMIN+" + std::to_string(signal - SIGRTMIN);
  const char* abbrev = ::sigabbrev_np(signal);
  return abbrev != nullptr ? std::string("SIG") + abbrev : "signal " + std::to_string(signal);
}

}  // namespace

Daemon::Daemon(const Options& options) : options_(options), timer_(io_), signals_(io_) {
  // A write to a closed pipe or pty (a dropped SSH session's terminal, a
  // pty's reader gone) fails with EPIPE instead of killing rotord mid-move;
  // a SIGPIPE sent with kill is ignored too.
  std::signal(SIGPIPE, SIG_IGN);
  // Caught from now on: one arriving during start-up is handled as soon as
  // the loop runs, and the outputs are off until then anyway.
  for (const int signal : terminating_signals()) signals_.add(signal);
}

Daemon::~Daemon() {
  stop_motors(controller_.get(), gpio_.get());
}

bool Daemon::setup() {
  // The web answers to the host's own name (host_check.hpp).
  char name[256] = "";
  if (::gethostname(name, sizeof(name) - 1) == 0) host_name_ = name;
  if (options_.hw == "gpiod") {
    if (options_.speedup != 1.0 || options_.clock != "wall" || !options_.utc_start.empty()) {
      log::error(
          "--speedup, --clock and --utc-start apply to the simulator only, not to --hw gpiod");
      return false;
    }
    defaults_ = settings_;  // no profile layer under real hardware
    if (!load_settings(nullptr)) return false;
    if (!open_gpiod()) return false;
    log::info("rotord %s, %s", ROTORD_VERSION, gpio_->summary().c_str());
    if (!start_controller()) return false;
    gpio_->watch(io_);
    log::info("ready");
    return true;
  }
  if (options_.hw != "sim") {
    log::error("unknown --hw '%s' (sim or gpiod)", options_.hw.c_str());
    return false;
  }
  const sim::Profile* profile = sim::find_profile(options_.sim_profile);
  if (profile == nullptr) {
    log::error("unknown simulator profile '%s' (try g5500, ham4, spid)",
               options_.sim_profile.c_str());
    return false;
  }
  if (std::string error; !apply_profile(*profile, settings_, error)) {
    log::error("%s", error.c_str());
    return false;
  }
  defaults_ = settings_;
  if (!load_settings(profile)) return false;
  sim_ = std::make_unique<sim::SimRotator>(*profile, options_.sim_seed);
  sim_->set_sensor_mount_deg(AxisId::kAz, options_.sim_sensor_mount_deg);
  if (options_.clock == "manual" || options_.speedup != 1.0 || !options_.utc_start.empty()) {
    // Simulated time: UTC moves with it (tracking follows the simulated sky).
    std::int64_t start = 0;
    if (options_.utc_start.empty()) {
      start = *wall_clock_.unix_ms();
    } else if (!tracking::parse_utc(options_.utc_start, start)) {
      log::error("--utc-start '%s' is not a UTC time like 2019-12-09T16:00:00Z",
                 options_.utc_start.c_str());
      return false;
    }
    sim_utc_ = std::make_unique<SimulatedUtcClock>(start, &now_ms_);
  }
  if (options_.clock == "manual") {
    log::info("rotord %s, simulated rotator '%s' (%s), manual clock (advance <ms> on stdin)",
              ROTORD_VERSION, profile->name, profile->description);
    clock_control_ =
        std::make_unique<ClockControl>(io_, [this](Millis ms) { return advance_manual_clock(ms); });
  } else {
    log::info("rotord %s, simulated rotator '%s' (%s), speedup %g", ROTORD_VERSION, profile->name,
              profile->description, options_.speedup);
  }
  if (!start_controller()) return false;
  log::info("ready");
  return true;
}

bool Daemon::open_gpiod() {
  std::string error;
  auto chip = open_gpiod_chip(settings_.i(settings::Id::kGpiodChip), error);
  if (chip)
    gpio_ = GpiodRotator::open(
        settings_, std::move(chip),
        GpiodHost{iio_root(), pwm_root(), i2c_dev_root(), &linux_i2c_kernel(), monotonic_ns},
        error);
  if (!gpio_) {
    log::error("--hw gpiod: %s", error.c_str());
    return false;
  }
  return true;
}

AxisIo Daemon::axis_io(AxisId axis) {
  return gpio_ ? gpio_->io(axis) : sim_->io(axis);
}

bool Daemon::load_settings(const sim::Profile* profile) {
  storage_ = std::make_unique<FileStorage>(settings_path(options_));
  if (const std::string why = storage_->unusable_reason(); !why.empty()) {
    // A FIFO would block the first read forever, before any port listens.
    log::error("settings file %s %s", storage_->path().c_str(), why.c_str());
    return false;
  }
  // Heap is fine here (start-up, Linux); the Pico keeps this buffer static.
  saver_buf_.resize(web::Api::kMaxDocumentBytes);
  saver_ = std::make_unique<SettingsSaver>(settings_, defaults_, *storage_, saver_buf_.data(),
                                           saver_buf_.size());
  std::vector<char> buf(web::Api::kMaxDocumentBytes);
  auto scratch = std::make_unique<settings::Settings>();
  std::unique_ptr<LegacyProfileGuess> guess;
  if (profile != nullptr) guess = std::make_unique<LegacyProfileGuess>(*profile);
  // Through the saver, so it knows what the file holds.
  const web::LoadOutcome r = web::load_settings(*saver_, defaults_, guess.get(), settings_,
                                                *scratch, buf.data(), buf.size(), &load_report_);
  saver_->begin();  // only later changes are saved; a damaged file stays as it is
  switch (r.status) {
    case web::LoadOutcome::kNothingStored:
      log::info("no settings file at %s yet, using the defaults", storage_->path().c_str());
      break;
    case web::LoadOutcome::kLoaded:
      log::info("settings loaded from %s", storage_->path().c_str());
      if (r.migrated) {
        const sim::Profile* from = guess ? guess->recognised() : nullptr;
        log::info(
            "%s holds every setting (written before rotord kept only your changes); "
            "read as your changes over %s%s; the next save keeps only those",
            storage_->path().c_str(), from != nullptr ? "the simulator profile " : "the defaults",
            from != nullptr ? from->name : "");
      }
      break;
    case web::LoadOutcome::kRepaired:
      // Keep every valid value, and the file as it is: it may hold hours of
      // calibration besides the one wrong character.
      for (std::size_t n = 0; n < load_report_.size(); ++n)
        log::error("settings file %s: %s%s%s: dropped, running on the default",
                   storage_->path().c_str(), load_report_[n].key,
                   load_report_[n].key[0] != '\0' ? ": " : "", load_report_[n].reason);
      if (load_report_.more() > 0)
        log::error("settings file %s: %zu more values dropped", storage_->path().c_str(),
                   load_report_.more());
      log::error(
          "settings file %s: every other value loaded. The file is left as it is; "
          "the next save keeps it as %s.bad",
          storage_->path().c_str(), storage_->path().c_str());
      storage_->keep_backup_before_next_save();
      break;
    case web::LoadOutcome::kCorrupt:
      log::error(
          "settings file %s is invalid (%s%s%s%s%s); running on the defaults. "
          "The file is left as it is; the next save keeps it as %s.bad",
          storage_->path().c_str(), r.key, r.key[0] != '\0' ? ": " : "", r.reason,
          storage_->last_error().empty() ? "" : ": ", storage_->last_error().c_str(),
          storage_->path().c_str());
      storage_->keep_backup_before_next_save();
      break;
  }
  if (r.access_unreadable)
    log::error(
        "settings file %s: the access settings cannot be read, so rotord fails closed: every "
        "port obeys only STOP and answers status until the file is fixed and rotord restarted",
        storage_->path().c_str());
  return true;
}

bool Daemon::start_controller() {
  const AxisIo az_io = axis_io(AxisId::kAz);
  const AxisIo el_io = axis_io(AxisId::kEl);
  controller_ = std::make_unique<Controller>(settings_, az_io, el_io);
  controller_->attach_journal(&command_log_);
  buttons_ = std::make_unique<command::Buttons>(*controller_, az_io, el_io);
  controller_->attach_utc_clock(sim_utc_ ? static_cast<const hal::WallClock*>(sim_utc_.get())
                                         : &wall_clock_);
  // A pass search or plan: 64 evaluations per tick (about 1 ms here).
  controller_->set_track_budget(64);
  if (!tles_) {
    // tles.txt beside the settings file (three-line text, written atomically).
    const std::string& settings_path = storage_->path();
    const std::size_t slash = settings_path.rfind('/');
    tle_storage_ = std::make_unique<FileStorage>(
        (slash == std::string::npos ? std::string() : settings_path.substr(0, slash + 1)) +
        "tles.txt");
    tles_ = std::make_unique<tracking::TleCatalog>();
    std::vector<char> buf(2 * tracking::TleCatalog::kMaxTextBytes);
    tles_->load(*tle_storage_, buf.data(), buf.size());
    if (tles_->size() > 0)
      log::info("%zu TLEs loaded from %s", tles_->size(), tle_storage_->path().c_str());
  }
  // A client's go-to stream is compared with these (track.recognise); on
  // Linux the whole catalogue per go-to (26 evaluations, well under 1 ms).
  controller_->attach_catalog(tles_.get());
  if (gpio_ && gpio_->estop() != nullptr) controller_->attach_estop(gpio_->estop());
  if (gpio_) controller_->attach_wind_pulses(gpio_->wind_pulses());
  load_odometer();
  metrics_.ticks = &ticks_;
  if (saver_) {
    metrics_.settings_writes = &saver_->writes();
    metrics_.settings_failures = &saver_->failures();
  }
  metrics_.clock = &steady_clock_;
  web::ApiContext api_context{*controller_,   saver_.get(), &defaults_,         &system_,
                              ROTORD_VERSION, &wall_clock_, host_name_.c_str(), &metrics_};
  api_context.load_report = &load_report_;
  api_context.platform =
      options_.hw == "gpiod" ? settings::Platform::kGpiod : settings::Platform::kSim;
  api_context.clock_sync = &ntp_state_;
  if (crypto_.ready()) {
    api_context.crypto = &crypto_;
  } else {
    std::fprintf(stderr, "rotord: mbedtls could not seed its generator: web logins refused\n");
  }
  // PBKDF2-HMAC-SHA256 of the web password: 100 000 iterations, about
  // 0.1 s of CPU on an x86-64 core (mbedtls 2.28: 1.1 us per iteration),
  // roughly five times that on a Raspberry Pi 3 or 4. In slices of 500
  // (0.5 ms here), for at most kHashBudget of each 10 ms pass (serve()).
  api_context.pbkdf2_iterations = 100'000;
  api_context.pbkdf2_slice = 500;
  api_context.log = &access_log_;
  api_context.log_gate = &log::gate();
  api_context.tles = tles_.get();
  api_context.tle_storage = tle_storage_.get();
  api_ = std::make_unique<web::Api>(api_context);
  mqtt_ = MqttClient::create(settings_, host_name_,
                             "http://" + host_name_ + ":" + std::to_string(options_.web_port) + "/",
                             *api_);

  std::error_code ec;
  auto bind = asio::ip::make_address(options_.bind, ec);
  if (ec) {
    log::error("invalid bind address '%s'", options_.bind.c_str());
    return false;
  }
  if (bind.is_v6() && bind.is_unspecified()) {
    // A kernel without IPv6 (ipv6.disable=1) cannot open the dual-stack
    // socket: serve IPv4 alone rather than nothing.
    asio::ip::tcp::acceptor probe(io_);
    if (probe.open(asio::ip::tcp::v6(), ec); ec) {
      log::info("no IPv6 on this host (%s): listening on 0.0.0.0", ec.message().c_str());
      bind = asio::ip::address_v4::any();
      options_.bind = "0.0.0.0";
    }
  }
  std::vector<ServiceConfig> services =
      make_services(options_, *controller_, *api_, settings_, metrics_, &console_port_);
  if (!attach_serial_lines(services)) return false;
  for (auto& service : services) {
    if (service.port == 0) continue;
    try {
      servers_.push_back(std::make_unique<TcpServer>(io_, bind, std::move(service)));
    } catch (const std::system_error& e) {
      log::error("cannot listen on %s:%u: %s", options_.bind.c_str(),
                 static_cast<unsigned>(service.port), e.what());
      return false;
    }
    log::info("%s listening on %s:%u", servers_.back()->name().c_str(), options_.bind.c_str(),
              static_cast<unsigned>(servers_.back()->port()));
  }
  return start_udp(bind);
}

bool Daemon::start_udp(const asio::ip::address& bind) {
  datagram_handlers_ = std::make_unique<protocol::DatagramHandlers>(*controller_);
  for (const protocol::DatagramInfo& p : protocol::datagram_protocols()) {
    if (!settings_.b(p.enabled)) continue;
    const auto port = static_cast<std::uint16_t>(settings_.i(p.port));
    try {
      udp_servers_.push_back(std::make_unique<UdpServer>(io_, bind, port, std::string(p.name),
                                                         datagram_handlers_->get(p.personality),
                                                         p.personality, &metrics_));
    } catch (const std::system_error& e) {
      log::error("cannot listen on UDP %s:%u: %s", options_.bind.c_str(),
                 static_cast<unsigned>(port), e.what());
      return false;
    }
    log::info("%s listening on UDP %s:%u", udp_servers_.back()->name().c_str(),
              options_.bind.c_str(), static_cast<unsigned>(udp_servers_.back()->port()));
  }
  return true;
}

bool Daemon::attach_serial_lines(const std::vector<ServiceConfig>& services) {
  auto find = [&](const std::string& key) -> const ServiceConfig* {
    for (const auto& s : services) {
      if (!s.key.empty() && s.key == key) return &s;
    }
    return nullptr;
  };
  if (!serial_lines_.empty()) {
    for (auto& line : serial_lines_) {
      if (const ServiceConfig* service = find(line->spec().personality))
        line->set_session_factory(service->make_session);
    }
    return true;
  }
  std::vector<SerialSpec> specs;
  std::string error;
  for (const auto& [texts, pty] : {std::pair{&options_.ptys, true}, {&options_.serials, false}}) {
    for (const auto& text : *texts) {
      auto spec = parse_serial_spec(text, pty, error);
      if (!spec) {
        log::error("%s %s", pty ? "--pty" : "--serial", error.c_str());
        return false;
      }
      specs.push_back(*spec);
    }
  }
  for (const auto& spec : specs) {
    const ServiceConfig* service = find(spec.personality);
    if (service == nullptr) {
      std::string known;
      for (const auto& s : services) {
        if (!s.key.empty()) known += (known.empty() ? "" : ", ") + s.key;
      }
      log::error("unknown personality '%s' (known: %s)", spec.personality.c_str(), known.c_str());
      return false;
    }
    auto line = std::make_unique<SerialTransport>(io_, service->name, spec, service->serial_baud,
                                                  service->make_session);
    line->count_replies(&metrics_, service->protocol);
    if (!line->open(error)) {
      log::error("%s: %s", service->name.c_str(), error.c_str());
      return false;
    }
    if (spec.pty) {
      log::info("%s on pty %s%s%s", service->name.c_str(), line->path().c_str(),
                spec.path.empty() ? "" : " linked from ", spec.path.c_str());
    } else {
      log::info("%s on serial %s at %d baud", service->name.c_str(), line->path().c_str(),
                line->baud());
    }
    serial_lines_.push_back(std::move(line));
  }
  return true;
}

void Daemon::request_reboot() {
  // Later, from the tick: the request's own connection must first send its
  // response, and the servers cannot be replaced while one of them runs.
  reboot_pending_ = true;
  reboot_at_ = std::chrono::steady_clock::now() + std::chrono::milliseconds(200);
}

const char* Daemon::System::reboot() {
  daemon_.request_reboot();
  return nullptr;
}

const char* Daemon::System::reboot_to_bootloader() {
  return "bootsel is for the Pico: rotord on Linux has no USB bootloader (update the package "
         "instead)";
}

void Daemon::reboot() {
  reboot_pending_ = false;
  log::info("restarting the controller");
  stop_motors(controller_.get(), nullptr);
  save_odometer(true);  // the next controller reads it back
  odometer_saver_.reset();
  servers_.clear();
  udp_servers_.clear();
  datagram_handlers_.reset();
  mqtt_.reset();
  api_.reset();
  buttons_.reset();
  controller_.reset();
  if (gpio_) {
    // Line and ADC settings take effect now: release every line, request anew.
    gpio_.reset();
    if (!open_gpiod()) {
      exit_code_ = 2;
      stop();
      return;
    }
    gpio_->watch(io_);
  }
  if (!start_controller()) {
    stop();
    return;
  }
  controller_->begin(now_ms_);
  log::info("ready");
}

int Daemon::run() {
  if (!setup()) return 2;
  signals_.async_wait([this](std::error_code ec, int signal) {
    if (ec) return;
    log::info("%s (%d), stopping the motors", signal_name(signal).c_str(), signal);
    stop();
  });
  controller_->begin(now_ms_);
  axis_events_.begin(controller_->status());
  recognition_events_.begin(controller_->recognition());
  if (sim_) sim_->advance_to(now_ms_);
  wall_start_ = std::chrono::steady_clock::now();
  ticks_.start(steady_us());
  metrics_.start_us = steady_us();
  if (clock_control_) clock_control_->start();
  schedule_tick();
  // Every port listens (setup() returned true only then): clients may come.
  notifier_.ready("ready");
  announce();
  if (notifier_.watchdog_us() != 0)
    log::debug("systemd watchdog every %llu ms, fed from the control tick",
               static_cast<unsigned long long>(notifier_.watchdog_us() / 1000));
  io_.run();
  stop_motors(controller_.get(), gpio_.get());
  const std::string outputs = driver_outputs();
  if (outputs.find('=') == std::string::npos) {
    log::info("stopped; outputs at the driver: %s", outputs.c_str());
  } else {
    log::error("stopped; outputs at the driver STILL ON: %s", outputs.c_str());
  }
  return exit_code_;
}

std::string Daemon::driver_outputs() const {
  // What the hardware was last given: the simulator's plant inputs, or the
  // values written to the GPIO lines and PWM channels.
  const bool has_el = controller_ && controller_->has_el();
  DriveOutputs az;
  DriveOutputs el;
  if (sim_) {
    az = sim_->outputs(AxisId::kAz);
    el = sim_->outputs(AxisId::kEl);
  } else if (gpio_) {
    az = gpio_->written(AxisId::kAz);
    el = gpio_->written(AxisId::kEl);
  }
  return describe_outputs(az, has_el ? &el : nullptr);
}

void Daemon::StdoutLog::write(std::string_view bytes) {
  std::fwrite(bytes.data(), 1, bytes.size(), stdout);
  std::fflush(stdout);
}

void Daemon::InfoLog::write(std::string_view bytes) {
  log::info("%.*s", static_cast<int>(bytes.size()), bytes.data());
}

void Daemon::stop() {
  stop_motors(controller_.get(), gpio_.get());
  notifier_.stopping();
  avahi_.reset();               // withdrawn from the network at once
  save_changed_settings(true);  // a change still in its quiet time
  save_odometer(true);
  timer_.cancel();
  mqtt_.reset();
  servers_.clear();
  serial_lines_.clear();
  udp_servers_.clear();
  io_.stop();
}

void Daemon::announce() {
  if (options_.avahi != "on") return;
  std::error_code ec;
  if (asio::ip::make_address(options_.bind, ec).is_loopback()) {
    log::info("avahi: bound to %s, not announced on the network", options_.bind.c_str());
    return;
  }
  const auto port = [this](protocol::Personality p) {
    return static_cast<std::uint16_t>(options_.line_ports[static_cast<std::size_t>(p)]);
  };
  avahi_ = std::make_unique<AvahiPublisher>(
      protocol::announced_ports(static_cast<std::uint16_t>(options_.web_port), port),
      ROTORD_VERSION);
}

std::int64_t Daemon::steady_us() {
  return std::chrono::duration_cast<std::chrono::microseconds>(
             std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

void Daemon::schedule_tick() {
  timer_.expires_at(std::chrono::steady_clock::time_point(
      std::chrono::duration_cast<std::chrono::steady_clock::duration>(
          std::chrono::microseconds(ticks_.deadline_us()))));
  timer_.async_wait([this](std::error_code ec) {
    if (ec) return;
    const TickScheduler::Stats before = ticks_.stats();
    if (ticks_.poll(steady_us())) {
      report_late_tick(before);
      on_tick();
      // Only a loop that ticks feeds the watchdog.
      notifier_.tick(steady_us());
    }
    schedule_tick();
  });
}

void Daemon::report_late_tick(const TickScheduler::Stats& before) const {
  const TickScheduler::Stats& now = ticks_.stats();
  if (now.rebases != before.rebases) {
    log::warn("the control loop stalled for %lld ms; tick schedule restarted",
              static_cast<long long>(now.overruns - before.overruns) * kTickMs);
  } else if (now.overruns != before.overruns && log::enabled(log::Level::kDebug)) {
    log::debug("control tick late: %llu tick(s) skipped (%llu so far)",
               static_cast<unsigned long long>(now.overruns - before.overruns),
               static_cast<unsigned long long>(now.overruns));
  }
}

Millis Daemon::wall_ms() const {
  return static_cast<Millis>(std::chrono::duration_cast<std::chrono::milliseconds>(
                                 std::chrono::steady_clock::now() - wall_start_)
                                 .count());
}

void Daemon::on_tick() {
  const Millis wall_ms = this->wall_ms();
  if (clock_control_) {
    // Controller time moves only by advance_manual_clock().
  } else if (gpio_) {
    // Real hardware: one tick per wake-up on the wall clock.
    if (wall_ms > now_ms_) {
      now_ms_ = wall_ms;
      gpio_->sample();
      tick_controller();
    }
  } else {
    advance_simulation(wall_ms);
  }
  serve(network_ms());
}

void Daemon::serve(Millis wall_ms) {
  log::tick(wall_ms);          // the log budget's minutes, and its summaries
  command_log_.poll(wall_ms);  // commands' repeats summed up
  // Faults latched and slips, named, into the journal.
  char event[192];
  while (axis_events_.next(controller_->status(), event, sizeof event)) log::warn("%s", event);
  // Passes recognised in a client's go-tos, and why each ended.
  while (recognition_events_.next(controller_->recognition(), event, sizeof event))
    log::info("%s", event);
  // Sessions time their clients on the wall clock: --speedup speeds up the
  // rotator, not the network's timeouts.
  if (api_) {
    api_->poll(wall_ms);
    // A login or a new password being hashed: more slices, for at most
    // kHashBudget of this pass, so the next tick is never held up by more.
    const auto until = std::chrono::steady_clock::now() + kHashBudget;
    while (api_->auth_busy() && std::chrono::steady_clock::now() < until) api_->work();
  }
  if (mqtt_) mqtt_->poll(wall_ms);
  for (auto& server : servers_) server->poll(wall_ms);
  for (auto& line : serial_lines_) line->poll(wall_ms);
  for (auto& udp : udp_servers_) udp->poll();
  save_changed_settings(false);
  save_odometer(false);
  refresh_tles();
  if (reboot_pending_ && std::chrono::steady_clock::now() >= reboot_at_) reboot();
}

void Daemon::refresh_tles() {
  if (!tles_) return;
  const std::string url(settings_.text(settings::Id::kTrackTleUrl));
  if (url.empty()) {
    tle_url_fetched_.clear();
    return;
  }
  const auto now = std::chrono::steady_clock::now();
  if (url == tle_url_fetched_ && now < next_tle_refresh_) return;
  if (!tle_fetcher_) tle_fetcher_ = std::make_unique<TleFetcher>(io_);
  if (tle_fetcher_->busy()) return;
  tle_url_fetched_ = url;
  next_tle_refresh_ = now + std::chrono::hours(settings_.i(settings::Id::kTrackTleRefreshH));
  tle_fetcher_->fetch(url, [this, url](bool ok, const std::string& text) {
    if (!ok) {
      log::warn("TLE refresh from %s failed: %s", url.c_str(), text.c_str());
      return;
    }
    if (!tles_) return;
    const tracking::TleCatalog::Refresh r = tles_->refresh(text);
    std::vector<char> buf(2 * tracking::TleCatalog::kMaxTextBytes);
    const bool saved = r.updated == 0 || tles_->save(*tle_storage_, buf.data(), buf.size());
    log::info("TLEs refreshed from %s: %zu updated, %zu not stored here, %zu bad%s", url.c_str(),
              r.updated, r.not_stored, r.bad, saved ? "" : " (could not save them)");
  });
}

void Daemon::advance_simulation(Millis wall_ms) {
  // Simulated time runs `speedup` times faster than the wall clock; the
  // control tick stays at 100 Hz of simulated time whatever the speedup.
  const auto target_ms = static_cast<Millis>(static_cast<double>(wall_ms) * options_.speedup);
  // Catch up at most 2 s of simulated time per wake-up, so an overloaded host
  // slows the simulation down instead of stalling the sockets.
  int budget = 200;
  while (now_ms_ + kTickMs <= target_ms && budget-- > 0) tick_simulation();
}

void Daemon::tick_simulation() {
  now_ms_ += kTickMs;
  sim_->advance_to(now_ms_);
  tick_controller();
}

void Daemon::tick_controller() {
  buttons_->poll(now_ms_);
  controller_->tick(now_ms_);
}

Millis Daemon::advance_manual_clock(Millis ms) {
  // The sessions run between the ticks as they would in real time, so a
  // GS-232 timed list or a settings save falls on the tick it belongs to.
  for (Millis done = 0; done < ms && controller_ && !reboot_pending_; done += kTickMs) {
    tick_simulation();
    network_skip_ms_ += kTickMs;
    serve(network_ms());
  }
  return now_ms_;
}

void Daemon::load_odometer() {
  if (!odometer_storage_) {
    const std::string& settings_path = storage_->path();
    const std::size_t slash = settings_path.rfind('/');
    odometer_storage_ = std::make_unique<FileStorage>(
        (slash == std::string::npos ? std::string() : settings_path.substr(0, slash + 1)) +
        "odometer.json");
    odometer_buf_.resize(4096);
  }
  // Linux writes a small file: once a minute (a power cut loses at most that).
  odometer_saver_ =
      std::make_unique<care::OdometerSaver>(controller_->odometer(), *odometer_storage_,
                                            odometer_buf_.data(), odometer_buf_.size(), 60000);
  const std::string& path = odometer_storage_->path();
  switch (odometer_saver_->load(now_ms_)) {
    case care::OdometerSaver::Load::kNothingStored:
      log::info("no odometer at %s yet: counting from zero", path.c_str());
      break;
    case care::OdometerSaver::Load::kLoaded:
      log::info("odometer loaded from %s", path.c_str());
      break;
    case care::OdometerSaver::Load::kDamaged:
      log::error(
          "odometer %s is damaged (%s%s%s): counting again from zero; the file is kept as "
          "%s.bad",
          path.c_str(), odometer_saver_->why(), odometer_storage_->last_error().empty() ? "" : ": ",
          odometer_storage_->last_error().c_str(), path.c_str());
      odometer_storage_->keep_backup_before_next_save();
      break;
  }
  metrics_.odometer_writes = &odometer_saver_->writes();
  metrics_.odometer_failures = &odometer_saver_->failures();
}

void Daemon::save_odometer(bool now) {
  if (!odometer_saver_) return;
  const care::OdometerSaver::Result r =
      now ? odometer_saver_->flush(now_ms_) : odometer_saver_->poll(now_ms_);
  if (r == care::OdometerSaver::Result::kSaved) {
    log::debug("odometer saved to %s", odometer_storage_->path().c_str());
  } else if (r == care::OdometerSaver::Result::kFailed) {
    log::error("saving the odometer to %s failed (%s); next try in %ld s",
               odometer_storage_->path().c_str(), odometer_storage_->last_error().c_str(),
               static_cast<long>(odometer_saver_->interval_ms() / 1000));
  }
}

void Daemon::save_changed_settings(bool now) {
  if (!saver_) return;
  // Linux writes a small file: no need to wait for the rotator to stand.
  const SettingsSaver::Result r = now ? saver_->flush(now_ms_) : saver_->poll(now_ms_);
  if (r == SettingsSaver::Result::kUnchanged) {
    log::debug("settings changed back to what %s holds; nothing written", storage_->path().c_str());
  } else if (r == SettingsSaver::Result::kSaved) {
    log::info("settings saved to %s", storage_->path().c_str());
  } else if (r == SettingsSaver::Result::kFailed) {
    log::error("saving the settings to %s failed (%s); next try in %ld s", storage_->path().c_str(),
               storage_->last_error().c_str(), static_cast<long>(saver_->retry_delay_ms() / 1000));
  }
}

}  // namespace rotord::linux_port
