#include "daemon.hpp"

#include <unistd.h>

#include <csignal>
#include <cstdio>

#include "legacy_profile_guess.hpp"
#include "services.hpp"
#include "sysfs_pwm.hpp"

namespace rotord::linux_port {

Daemon::Daemon(const Options& options)
    : options_(options), timer_(io_), signals_(io_, SIGINT, SIGTERM) {}

Daemon::~Daemon() {
  if (controller_) controller_->shutdown();
}

bool Daemon::setup() {
  // The web answers to the host's own name (host_check.hpp).
  char name[256] = "";
  if (::gethostname(name, sizeof(name) - 1) == 0) host_name_ = name;
  if (options_.hw == "gpiod") {
    if (options_.speedup != 1.0 || options_.clock != "wall") {
      std::fprintf(
          stderr, "rotord: --speedup and --clock apply to the simulator only, not to --hw gpiod\n");
      return false;
    }
    defaults_ = settings_;  // no profile layer under real hardware
    if (!load_settings(nullptr)) return false;
    if (!open_gpiod()) return false;
    std::printf("rotord %s: %s\n", ROTORD_VERSION, gpio_->summary().c_str());
    if (!start_controller()) return false;
    gpio_->watch(io_);
    std::printf("rotord: ready\n");
    std::fflush(stdout);
    return true;
  }
  if (options_.hw != "sim") {
    std::fprintf(stderr, "rotord: unknown --hw '%s' (sim or gpiod)\n", options_.hw.c_str());
    return false;
  }
  const sim::Profile* profile = sim::find_profile(options_.sim_profile);
  if (profile == nullptr) {
    std::fprintf(stderr, "rotord: unknown simulator profile '%s' (try g5500, ham4, spid)\n",
                 options_.sim_profile.c_str());
    return false;
  }
  for (const auto& o : profile->overrides) {
    const auto id = settings::find(o.key);
    if (!id || settings_.set(*id, o.value).error != Error::kOk) {
      std::fprintf(stderr, "rotord: profile %s sets an invalid %s\n", profile->name, o.key);
      return false;
    }
  }
  defaults_ = settings_;
  if (!load_settings(profile)) return false;
  sim_ = std::make_unique<sim::SimRotator>(*profile, options_.sim_seed);
  if (options_.clock == "manual") {
    std::printf("rotord %s: simulated rotator '%s' (%s), manual clock (advance <ms> on stdin)\n",
                ROTORD_VERSION, profile->name, profile->description);
    clock_control_ =
        std::make_unique<ClockControl>(io_, [this](Millis ms) { return advance_manual_clock(ms); });
  } else {
    std::printf("rotord %s: simulated rotator '%s' (%s), speedup %g\n", ROTORD_VERSION,
                profile->name, profile->description, options_.speedup);
  }
  if (!start_controller()) return false;
  std::printf("rotord: ready\n");
  std::fflush(stdout);
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
    std::fprintf(stderr, "rotord: --hw gpiod: %s\n", error.c_str());
    return false;
  }
  return true;
}

AxisIo Daemon::axis_io(AxisId axis) {
  return gpio_ ? gpio_->io(axis) : sim_->io(axis);
}

bool Daemon::load_settings(const sim::Profile* profile) {
  storage_ = std::make_unique<FileStorage>(
      options_.config_path.empty() ? FileStorage::default_path() : options_.config_path);
  if (const std::string why = storage_->unusable_reason(); !why.empty()) {
    // A FIFO would block the first read forever, before any port listens.
    std::fprintf(stderr, "rotord: settings file %s %s\n", storage_->path().c_str(), why.c_str());
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
                                                *scratch, buf.data(), buf.size());
  saver_->begin();  // only later changes are saved; a damaged file stays as it is
  switch (r.status) {
    case web::LoadOutcome::kNothingStored:
      std::printf("rotord: no settings file at %s yet, using the defaults\n",
                  storage_->path().c_str());
      break;
    case web::LoadOutcome::kLoaded:
      std::printf("rotord: settings loaded from %s\n", storage_->path().c_str());
      if (r.migrated) {
        const sim::Profile* from = guess ? guess->recognised() : nullptr;
        std::printf(
            "rotord: %s holds every setting (written before rotord kept only your changes); "
            "read as your changes over %s%s; the next save keeps only those\n",
            storage_->path().c_str(), from != nullptr ? "the simulator profile " : "the defaults",
            from != nullptr ? from->name : "");
      }
      break;
    case web::LoadOutcome::kCorrupt:
      // Keep running on the defaults, and keep the file: it may hold hours of
      // calibration that one wrong character made unreadable.
      std::fprintf(stderr,
                   "rotord: settings file %s is invalid (%s%s%s%s%s); running on the defaults. "
                   "The file is left as it is; the next save keeps it as %s.bad\n",
                   storage_->path().c_str(), r.key, r.key[0] != '\0' ? ": " : "", r.reason,
                   storage_->last_error().empty() ? "" : ": ", storage_->last_error().c_str(),
                   storage_->path().c_str());
      storage_->keep_backup_before_next_save();
      break;
  }
  return true;
}

bool Daemon::start_controller() {
  controller_ = std::make_unique<Controller>(settings_, axis_io(AxisId::kAz), axis_io(AxisId::kEl));
  if (gpio_ && gpio_->estop() != nullptr) controller_->attach_estop(gpio_->estop());
  web::ApiContext api_context{*controller_,   saver_.get(), &defaults_,        this,
                              ROTORD_VERSION, &wall_clock_, host_name_.c_str()};
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
  api_ = std::make_unique<web::Api>(api_context);

  std::error_code ec;
  const auto bind = asio::ip::make_address(options_.bind, ec);
  if (ec) {
    std::fprintf(stderr, "rotord: invalid bind address '%s'\n", options_.bind.c_str());
    return false;
  }
  const auto max_clients = static_cast<std::size_t>(settings_.i(settings::Id::kNetMaxClients));
  std::vector<ServiceConfig> services = make_services(options_, *controller_, *api_, max_clients);
  if (!attach_serial_lines(services)) return false;
  for (auto& service : services) {
    if (service.port == 0) continue;
    try {
      servers_.push_back(std::make_unique<TcpServer>(io_, bind, std::move(service)));
    } catch (const std::system_error& e) {
      std::fprintf(stderr, "rotord: cannot listen on %s:%u: %s\n", options_.bind.c_str(),
                   static_cast<unsigned>(service.port), e.what());
      return false;
    }
    std::printf("rotord: %s listening on %s:%u\n", servers_.back()->name().c_str(),
                options_.bind.c_str(), static_cast<unsigned>(servers_.back()->port()));
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
        std::fprintf(stderr, "rotord: %s %s\n", pty ? "--pty" : "--serial", error.c_str());
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
      std::fprintf(stderr, "rotord: unknown personality '%s' (known: %s)\n",
                   spec.personality.c_str(), known.c_str());
      return false;
    }
    auto line = std::make_unique<SerialTransport>(io_, service->name, spec, service->serial_baud,
                                                  service->make_session);
    if (!line->open(error)) {
      std::fprintf(stderr, "rotord: %s: %s\n", service->name.c_str(), error.c_str());
      return false;
    }
    if (spec.pty) {
      std::printf("rotord: %s on pty %s%s%s\n", service->name.c_str(), line->path().c_str(),
                  spec.path.empty() ? "" : " linked from ", spec.path.c_str());
    } else {
      std::printf("rotord: %s on serial %s at %d baud\n", service->name.c_str(),
                  line->path().c_str(), line->baud());
    }
    serial_lines_.push_back(std::move(line));
  }
  return true;
}

bool Daemon::request_reboot() {
  // Later, from the tick: the request's own connection must first send its
  // response, and the servers cannot be replaced while one of them runs.
  reboot_pending_ = true;
  reboot_at_ = std::chrono::steady_clock::now() + std::chrono::milliseconds(200);
  return true;
}

void Daemon::reboot() {
  reboot_pending_ = false;
  std::printf("rotord: restarting the controller\n");
  controller_->shutdown();
  servers_.clear();
  api_.reset();
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
  std::printf("rotord: ready\n");
  std::fflush(stdout);
}

int Daemon::run() {
  if (!setup()) return 2;
  signals_.async_wait([this](std::error_code ec, int signal) {
    if (ec) return;
    std::printf("rotord: signal %d, stopping the motors\n", signal);
    std::fflush(stdout);
    stop();
  });
  controller_->begin(now_ms_);
  if (sim_) sim_->advance_to(now_ms_);
  wall_start_ = std::chrono::steady_clock::now();
  if (clock_control_) clock_control_->start();
  schedule_tick();
  io_.run();
  if (controller_) controller_->shutdown();
  if (gpio_) gpio_->all_off();
  std::printf("rotord: stopped\n");
  return exit_code_;
}

void Daemon::StdoutLog::write(std::string_view bytes) {
  std::fwrite(bytes.data(), 1, bytes.size(), stdout);
  std::fflush(stdout);
}

void Daemon::stop() {
  if (controller_) controller_->shutdown();
  save_changed_settings(true);  // a change still in its quiet time
  timer_.cancel();
  servers_.clear();
  serial_lines_.clear();
  io_.stop();
}

void Daemon::schedule_tick() {
  timer_.expires_after(std::chrono::milliseconds(kTickMs));
  timer_.async_wait([this](std::error_code ec) {
    if (ec) return;
    on_tick();
    schedule_tick();
  });
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
      controller_->tick(now_ms_);
    }
  } else {
    advance_simulation(wall_ms);
  }
  serve(wall_ms);
}

void Daemon::serve(Millis wall_ms) {
  // Sessions time their clients on the wall clock: --speedup speeds up the
  // rotator, not the network's timeouts.
  if (api_) {
    api_->poll(wall_ms);
    // A login or a new password being hashed: more slices, for at most
    // kHashBudget of this pass, so the next tick is never held up by more.
    const auto until = std::chrono::steady_clock::now() + kHashBudget;
    while (api_->auth_busy() && std::chrono::steady_clock::now() < until) api_->work();
  }
  for (auto& server : servers_) server->poll(wall_ms);
  for (auto& line : serial_lines_) line->poll(wall_ms);
  save_changed_settings(false);
  if (reboot_pending_ && std::chrono::steady_clock::now() >= reboot_at_) reboot();
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
  controller_->tick(now_ms_);
}

Millis Daemon::advance_manual_clock(Millis ms) {
  // The sessions run between the ticks as they would in real time, so a
  // GS-232 timed list or a settings save falls on the tick it belongs to.
  for (Millis done = 0; done < ms && controller_ && !reboot_pending_; done += kTickMs) {
    tick_simulation();
    serve(wall_ms());
  }
  return now_ms_;
}

void Daemon::save_changed_settings(bool now) {
  if (!saver_) return;
  // Linux writes a small file: no need to wait for the rotator to stand.
  const SettingsSaver::Result r = now ? saver_->flush(now_ms_) : saver_->poll(now_ms_);
  if (r == SettingsSaver::Result::kSaved) {
    std::printf("rotord: settings saved to %s\n", storage_->path().c_str());
    std::fflush(stdout);
  } else if (r == SettingsSaver::Result::kFailed) {
    std::fprintf(stderr, "rotord: saving the settings to %s failed (%s); next try in %ld s\n",
                 storage_->path().c_str(), storage_->last_error().c_str(),
                 static_cast<long>(saver_->retry_delay_ms() / 1000));
  }
}

}  // namespace rotord::linux_port
