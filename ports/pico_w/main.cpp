// The composition root of the Pico W firmware (the counterpart of
// ports/linux/daemon.cpp): outputs off, watchdog, the HAL over the SDK, the
// controller, Wi-Fi and the protocol servers, all run from one poll loop.
//
// One loop, no interrupts into the core: pico_cyw43_arch_lwip_poll runs lwIP
// only inside cyw43_arch_poll(), so network callbacks, sessions and the
// control tick never run concurrently and the core needs no locks. The tick
// is scheduled by absolute deadline (TickScheduler) and the loop sleeps only
// until the next deadline, so network traffic delays a tick by at most one
// poll.
#include <algorithm>
#include <cstdio>
#include <optional>
#include <string_view>

#include "hardware/address_mapped.h"
#include "hardware/watchdog.h"
#include "json/settings_json.hpp"
#include "log_port.hpp"
#include "loop/tick_scheduler.hpp"
#include "lwip_transport.hpp"
#include "ma3_pio.hpp"
#include "metrics/registry.hpp"
#include "pico/binary_info.h"
#include "pico/cyw43_arch.h"
#include "pico/stdio/driver.h"
#include "pico/stdio_usb.h"
#include "pico/stdlib.h"
#include "pico_crypto.hpp"
#include "pico_flash.hpp"
#include "pico_hal.hpp"
#include "protocol/protocol_registry.hpp"
#include "rotator/controller.hpp"
#include "settings/pin_rules.hpp"
#include "settings/settings.hpp"
#include "sntp_clock.hpp"
#include "storage/flash_slots.hpp"
#include "storage/settings_saver.hpp"
#include "tracking/tle_catalog.hpp"
#include "usb_cdc_port.hpp"
#include "usb_personality.hpp"
#include "web/http_session.hpp"
#include "web/web_api.hpp"
#include "wifi.hpp"
#include "wifi_secrets.h"

namespace rotord::pico_w {
namespace {

/// The USB log port as a ByteSink for output that only matters as it
/// happens (WRC MONITOR lines): never kept for a later reader.
class LogPortSink final : public protocol::ByteSink {
 public:
  explicit LogPortSink(usb_port::LogPort& log) : log_(log) {}
  void write(std::string_view bytes) override { log_.write_live(bytes); }

 private:
  usb_port::LogPort& log_;
};

constexpr Millis kTickMs = 10;  // 100 Hz, as on Linux
// Long enough for the slowest blocking SDK call in the loop (enabling the
// access point: a few Wi-Fi chip ioctls), short enough that a hung loop stops
// a turning motor within 2 s (12 deg on a 6 deg/s G-5500; the reset puts
// every pin back to an input with its pull-down, i.e. relays off).
constexpr std::uint32_t kWatchdogMs = 2000;
// Every line protocol of the registry (core/protocol/protocol_registry.hpp)
// on its TCP port, with a static pool of connection slots each;
// net.max_clients is clamped to the pool. lwIP's pools (config/lwipopts.h)
// are sized for these 17 slots plus the web's 4 and 6 listeners.
using protocol::Personality;
template <Personality P>
constexpr std::size_t kTcpSlots = 0;
template <>
constexpr std::size_t kTcpSlots<Personality::kWrc> = 4;
// ~2.6 KB each (a whole reply, the arguments, input held by \pause): Gpredict
// or SatNOGS, a logger and a rotctl at once.
template <>
constexpr std::size_t kTcpSlots<Personality::kRotctld> = 3;
template <>
constexpr std::size_t kTcpSlots<Personality::kGs232> =
    2;  // under 1 KB each; PstRotator or N1MM plus one
template <>
constexpr std::size_t kTcpSlots<Personality::kEasycomm> = 2;  // a tracker plus one
// A jog panel or script plus one; about 100 B each.
template <>
constexpr std::size_t kTcpSlots<Personality::kSeed> = 2;
// A new personality in the registry fails to build here until it is served
// (or this says why not).
static_assert(protocol::kPersonalityCount == 5, "serve every personality on TCP");

/// Builds a session of personality P for a static pool (returned by value:
/// guaranteed copy elision builds it in its slot).
template <Personality P>
struct MakeSession {
  const protocol::SessionDeps* deps;
  typename protocol::SessionOf<P>::type operator()() const {
    return protocol::SessionOf<P>::make(*deps);
  }
};
template <Personality P>
using LineService =
    lwip_port::StaticService<typename protocol::SessionOf<P>::type, kTcpSlots<P>, MakeSession<P>>;
constexpr std::uint16_t kHttpPort = 80;
// A browser holds a page connection and the event stream, plus short API
// requests; each HTTP session is ~6 KB of RAM (request head and body buffers).
constexpr std::size_t kHttpSlots = 4;
// Open pages' event streams share those slots; at most this many, so two
// always remain for requests (web.max_event_streams is clamped to it), and a
// newcomer finding all four taken closes the oldest stream (net/admission.hpp).
constexpr std::size_t kHttpEventStreams = 2;
// POST /api/reboot answers first, then the watchdog resets the chip.
constexpr Millis kRebootDelayMs = 300;
// The web password's PBKDF2-HMAC-SHA256 (web_auth.hpp). One iteration is
// about 29 300 instructions with the SDK's mbedtls 3.6 and this port's
// mbedtls_config.h (counted under qemu -icount: tests/embedded, target
// m0_pico_crypto), some 35 000-44 000 cycles on the Cortex-M0+ (1.2-1.5
// cycles per instruction), 0.28-0.35 ms at 125 MHz. 5000 iterations: about
// 1.5-1.8 s of CPU per login or new password (not measured on a chip), run
// in slices of 3 iterations (about 1 ms) in the loop's idle time, so a tick
// is never late by more than one slice. A hash made on Linux (100 000
// iterations) also verifies here, 20 times slower: set the password on the
// Pico itself.
constexpr std::uint32_t kPbkdf2Iterations = 5'000;
constexpr std::uint32_t kPbkdf2SliceIterations = 3;
// A slice is started only when at least this much time is left before the tick.
constexpr std::int64_t kSliceHeadroomUs = 2000;

using settings::Id;
using settings::kNoPin;

/// The drive type's second output shares one pin: the fast/slow relay of a
/// two-speed drive, or the voltage-select relay. Which one the axis writes
/// depends on az.drive / el.drive (0 relay, 1 two-speed, 2 voltage-select, 3
/// H-bridge), so only that channel is mapped.
DrivePins drive_pins(int drive, int relay_cw, int relay_ccw, int speed, int brake, int pwm_cw,
                     int pwm_ccw) {
  DrivePins pins;
  pins.set(OutputChannel::kRelayCw, relay_cw).set(OutputChannel::kRelayCcw, relay_ccw);
  pins.set(OutputChannel::kBrake, brake);
  pins.set(OutputChannel::kPwmCw, pwm_cw).set(OutputChannel::kPwmCcw, pwm_ccw);
  pins.set(drive == 2 ? OutputChannel::kVoltageFast : OutputChannel::kSpeedFast, speed);
  return pins;
}

Millis now_ms() {
  return static_cast<Millis>(to_us_since_boot(get_absolute_time()) / 1000);
}

/// The program's flash (XIP) never changes while it runs: the web UI's
/// gzipped files there are sent by reference, without a copy in RAM.
bool in_program_flash(const void* data, std::size_t size) {
  const auto begin = reinterpret_cast<std::uintptr_t>(data);
  return begin >= XIP_BASE && begin + size <= XIP_BASE + PICO_FLASH_SIZE_BYTES;
}

/// The loop's clock for GET /healthz (the age of the last tick): the same
/// microsecond timer the tick schedule runs on.
class PicoMonotonicClock final : public hal::MonotonicClock {
 public:
  std::int64_t now_us() const override { return static_cast<std::int64_t>(time_us_64()); }
};

/// POST /api/reboot: remembered here, done by the loop once the response is
/// out (the hook runs inside the request).
class Reboot final : public web::RebootHook {
 public:
  bool request_reboot() override {
    requested_ = true;
    return true;
  }
  bool requested() const { return requested_; }

 private:
  bool requested_ = false;
};

// The USB log port (CDC 0), printf's only output (log_port.hpp): what is
// printed while no terminal has the port open waits in its ring.
TinyUsbCdcPort g_log_cdc(ROTORD_USB_LOG_CDC);
usb_port::LogPort g_log(g_log_cdc);

void log_out_chars(const char* buf, int length) {
  g_log.write(std::string_view(buf, static_cast<std::size_t>(length)));
}

stdio_driver_t g_log_driver = {
    .out_chars = log_out_chars,
    .out_flush = nullptr,
    .in_chars = nullptr,
    .set_chars_available_callback = nullptr,
    .next = nullptr,
#if PICO_STDIO_ENABLE_CRLF_SUPPORT
    .last_ended_with_cr = false,
    .crlf_enabled = PICO_STDIO_DEFAULT_CRLF,
#endif
};

// Hardware objects: static storage, built once the settings (and so the
// pins) are known; an unwired pin (-1) leaves its object empty and the core
// sees nullptr ("not fitted").
settings::Settings g_settings;
settings::Settings g_scratch;  // load_settings' working copy
// The table's defaults plus wifi_secrets.h, for the web's reset (which then
// keeps a build's Wi-Fi credentials).
settings::Settings g_defaults;
char g_boot_document[web::Api::kMaxDocumentBytes];
Reboot g_reboot;
PicoFlash g_flash;
FlashSlots g_storage(g_flash);
// The stored TLEs: their own two slots right below the settings.
PicoFlash g_tle_flash(PicoFlash::kRegionBytes, PicoFlash::kTleRegionBytes);
FlashSlots g_tle_storage(g_tle_flash);
tracking::TleCatalog g_tles;
// Between the web API and the flash, and the one that saves what the
// protocols change (GS-232 calibration, WRC AZOFFSET, rotctld C). Its
// document buffer is the start-up one, free once the settings are loaded.
// Only the user's changes over g_defaults go to flash (settings_layers.hpp).
SettingsSaver g_saver(g_settings, g_defaults, g_storage, g_boot_document, sizeof g_boot_document);
/// The pins.* settings of one axis's wiring: the Pico's counterpart of the
/// Linux port's gpiod.* key table (ports/linux/gpiod_io.cpp). "fwd" is CW on
/// the azimuth and up on the elevation.
struct AxisPins {
  const char* name;
  Id drive, sensor;
  Id relay_fwd, relay_rev, speed;
  std::optional<Id> brake;
  Id pwm_fwd, pwm_rev;
  Id pot;
  Id limit_cw, limit_ccw;  ///< L2 / L1 on the azimuth
  std::optional<Id> t1, t2;
  Id ma3, button_fwd, button_rev;
  bool may_use_magnetometer;  ///< the I2C magnetometer is an azimuth sensor only
};

constexpr AxisPins kAxisPins[] = {
    {"az", Id::kAzDrive, Id::kAzSensor, Id::kPinAzCw, Id::kPinAzCcw, Id::kPinAzSpeed,
     Id::kPinAzBrake, Id::kPinAzPwmCw, Id::kPinAzPwmCcw, Id::kPinAzPot, Id::kPinAzL2, Id::kPinAzL1,
     Id::kPinAzT1, Id::kPinAzT2, Id::kPinAzMa3, Id::kPinBtnCw, Id::kPinBtnCcw, true},
    {"el", Id::kElDrive, Id::kElSensor, Id::kPinElUp, Id::kPinElDown, Id::kPinElSpeed, std::nullopt,
     Id::kPinElPwmUp, Id::kPinElPwmDown, Id::kPinElPot, Id::kPinElLimitUp, Id::kPinElLimitDown,
     std::nullopt, std::nullopt, Id::kPinElMa3, Id::kPinBtnUp, Id::kPinBtnDown, false},
};

/// The hardware objects of one axis, in static storage (g_axes).
struct AxisParts {
  std::optional<PicoDriveSink> drive;
  std::optional<PicoAdc> pot;
  std::optional<Ma3PioInput> ma3_pio;
  std::optional<Ma3EdgeInput> ma3_irq;
  std::optional<PicoSwitch> t1, t2, limit_cw, limit_ccw, button_fwd, button_rev;
};
AxisParts g_axes[2];  // az, el: the order of kAxisPins
std::optional<PicoSwitch> g_estop;
std::optional<PicoI2c> g_i2c;

/// Builds the object for a wired pin and returns it, or nullptr.
template <class T, class... Args>
T* fit(std::optional<T>& slot, int gpio, Args&&... args) {
  if (gpio == kNoPin) return nullptr;
  slot.emplace(gpio, args...);
  return &*slot;
}

PicoSwitch* fit_switch(std::optional<PicoSwitch>& slot, int gpio) {
  PicoSwitch* s = fit(slot, gpio);
  if (s != nullptr) s->begin();
  return s;
}

/// The MA3 input of one axis: a PIO state machine, or the GPIO edge
/// interrupt when none is free. Only for an axis that uses the MA3, so an
/// unwired pin can never load the CPU.
hal::PwmIn* fit_ma3(std::optional<Ma3PioInput>& pio, std::optional<Ma3EdgeInput>& irq, int gpio,
                    const char* axis) {
  if (gpio == kNoPin) return nullptr;
  if (fit(pio, gpio)->begin()) {
    std::printf("rotord: %s MA3 on GPIO %d (PIO)\n", axis, gpio);
    return &*pio;
  }
  fit(irq, gpio)->begin();
  std::printf("rotord: %s MA3 on GPIO %d (edge interrupt: no free PIO state machine)\n", axis,
              gpio);
  return &*irq;
}

/// The build's ROTORD_WIFI_SSID, ROTORD_WIFI_PASSWORD and ROTORD_AP_PASSWORD
/// (wifi_secrets.h) as first-boot defaults of the Network settings: settings
/// saved from the web page win. A value the table refuses is ignored.
void apply_wifi_secrets(settings::Settings& s) {
  const struct {
    Id id;
    const char* value;
  } secrets[] = {{Id::kWifiSsid, ROTORD_WIFI_SSID},
                 {Id::kWifiPassword, ROTORD_WIFI_PASSWORD},
                 {Id::kWifiApPassword, ROTORD_AP_PASSWORD}};
  for (const auto& secret : secrets) {
    if (secret.value[0] == '\0') continue;
    const settings::Rejection r = s.set_text(secret.id, secret.value);
    if (r.error != Error::kOk)
      std::printf("rotord: build-time %s ignored: %s\n", settings::def(secret.id).key, r.reason);
  }
}

/// The user's changes from the flash slots over the board's defaults (the
/// table's plus wifi_secrets.h). Invalid stored settings (a pin conflict, a
/// value a newer firmware refuses) leave the defaults in place; the stored
/// copy stays in flash, and the next save goes to the other slot. A slot
/// written before layering (every setting) keeps every value that differs
/// from the board's defaults.
web::LoadOutcome load_stored_settings() {
  if (!g_flash.region_free()) return {};
  return web::load_settings(g_saver, g_defaults, nullptr, g_settings, g_scratch, g_boot_document,
                            sizeof g_boot_document);
}

/// What the loop's settings saver did, on the USB console.
void report_save(SettingsSaver::Result r) {
  if (r == SettingsSaver::Result::kSaved) std::printf("rotord: settings saved to flash\n");
  if (r == SettingsSaver::Result::kFailed)
    std::printf("rotord: saving the settings to flash failed; next try in %ld s\n",
                static_cast<long>(g_saver.retry_delay_ms() / 1000));
}

void report_settings(const web::LoadOutcome& r) {
  if (!g_flash.region_free()) {
    std::printf("rotord: the program overlaps the settings flash; settings are not saved\n");
    return;
  }
  switch (r.status) {
    case web::LoadOutcome::kNothingStored:
      std::printf("rotord: no settings in flash yet, using the defaults\n");
      break;
    case web::LoadOutcome::kLoaded:
      std::printf(
          "rotord: settings loaded from flash (slot %d, save #%lu)%s\n", g_storage.newest()->slot,
          static_cast<unsigned long>(g_storage.newest()->sequence),
          r.migrated ? "; every setting stored: the next save keeps only your changes" : "");
      break;
    case web::LoadOutcome::kCorrupt:
      std::printf("rotord: the settings in flash are invalid (%s%s%s); running on the defaults\n",
                  r.key, r.key[0] != '\0' ? ": " : "", r.reason);
      break;
  }
}

/// The pin of `id`, or kNoPin for a role the axis does not have.
int pin(const settings::Settings& s, std::optional<Id> id) {
  return id ? s.i(*id) : kNoPin;
}

/// Step 1 for one axis: its outputs, built and written off.
void fit_drive(const settings::Settings& s, const AxisPins& k, AxisParts& parts) {
  parts.drive.emplace(drive_pins(s.i(k.drive), s.i(k.relay_fwd), s.i(k.relay_rev), s.i(k.speed),
                                 pin(s, k.brake), s.i(k.pwm_fwd), s.i(k.pwm_rev)));
}

/// Step 2 for one axis: its inputs, from the pins.* settings.
AxisIo fit_inputs(const settings::Settings& s, const AxisPins& k, AxisParts& parts) {
  AxisIo io;
  io.drive = &*parts.drive;
  if (PicoAdc* adc = fit(parts.pot, s.i(k.pot))) {
    adc->begin();
    io.pot = adc;
  }
  io.t1 = fit_switch(parts.t1, pin(s, k.t1));
  io.t2 = fit_switch(parts.t2, pin(s, k.t2));
  io.limit_ccw = fit_switch(parts.limit_ccw, s.i(k.limit_ccw));
  io.limit_cw = fit_switch(parts.limit_cw, s.i(k.limit_cw));
  if (s.i(k.sensor) == static_cast<int>(SensorType::kMa3))
    io.ma3 = fit_ma3(parts.ma3_pio, parts.ma3_irq, s.i(k.ma3), k.name);
  if (k.may_use_magnetometer && s.i(k.sensor) == static_cast<int>(SensorType::kMag)) {
    if (PicoI2c* bus = fit(g_i2c, s.i(Id::kPinI2cSda), s.i(Id::kPinI2cScl))) {
      bus->begin();
      io.i2c = bus;
    }
  }
  if (s.b(Id::kButtonsEnabled)) {
    io.button_fwd = fit_switch(parts.button_fwd, s.i(k.button_fwd));
    io.button_rev = fit_switch(parts.button_rev, s.i(k.button_rev));
  }
  return io;
}

/// Starts the Wi-Fi chip and says why the network is down if it cannot.
/// cyw43_arch_init() only sets up the driver: the chip is powered and its
/// firmware loaded by the first call that needs it, and a chip that does
/// not answer would then be retried (20 + 50 ms of power-up delays, then a
/// failed bus init) by every later Wi-Fi call, several times a second from
/// the loop, stalling the control tick. So one call here brings it up, and
/// a chip that does not answer is left alone: USB and the controller run
/// without network. Found by running the image on an emulated RP2040 with
/// no Wi-Fi chip (make hil).
bool wifi_chip_up() {
  if (cyw43_arch_init() != 0) {
    std::printf("rotord: Wi-Fi driver init failed; running without network (USB only)\n");
    return false;
  }
  std::uint32_t power_mode = 0;
  const int err = cyw43_wifi_get_pm(&cyw43_state, &power_mode);
  if (err != 0) {
    std::printf(
        "rotord: the Wi-Fi chip does not answer (CYW43 bus init error %d); running without "
        "network: USB and the controller keep working\n",
        err);
    return false;
  }
  return true;
}

[[noreturn]] void run() {
  // 1. Outputs off. Until the pins are known every GPIO is still an input
  // with its reset pull-down (relays off); the settings come first because
  // they say which pins are outputs, and reading them takes milliseconds.
  settings::Settings& settings = g_settings;
  apply_wifi_secrets(g_defaults);
  apply_wifi_secrets(g_settings);
  const web::LoadOutcome loaded = load_stored_settings();
  const auto p = [&settings](Id id) { return settings.i(id); };
  AxisParts& az = g_axes[0];
  AxisParts& el = g_axes[1];
  fit_drive(settings, kAxisPins[0], az);
  fit_drive(settings, kAxisPins[1], el);
  az.drive->begin();
  const bool has_el = settings.b(Id::kElEnabled);
  if (has_el) el.drive->begin();

  // USB before stdio: pico_stdio_usb logs on CDC 0 of our TinyUSB device,
  // CDC 1 carries usb.personality (usb_device.c says why two ports).
  const std::optional<Personality> usb_personality =
      usb_port::personality_from_setting(settings.i(Id::kUsbPersonality));
  rotord_usb_init(usb_personality ? usb_port::personality_name(usb_personality) : nullptr);
  stdio_init_all();
  // printf into the log port's ring rather than through pico_stdio_usb's
  // driver, which drops whatever is printed while no terminal listens: the
  // banner, the settings report and the Wi-Fi lines below all come before a
  // terminal can open the port, and are sent when one does.
  stdio_set_driver_enabled(&stdio_usb, false);
  stdio_set_driver_enabled(&g_log_driver, true);
  std::printf("rotord %s (Pico W)%s\n", ROTORD_VERSION,
              watchdog_caused_reboot() ? ": restarted by the watchdog" : "");
  report_settings(loaded);

  // 2. Inputs, from the pins.* settings (kAxisPins).
  const AxisIo az_io = fit_inputs(settings, kAxisPins[0], az);
  const AxisIo el_io = has_el ? fit_inputs(settings, kAxisPins[1], el) : AxisIo{};
  static Controller controller(settings, az_io, el_io);
  if (PicoSwitch* estop = fit_switch(g_estop, p(Id::kPinEstop))) {
    controller.attach_estop(estop);
    std::printf("rotord: emergency stop on GPIO %d (%s contact)\n", p(Id::kPinEstop),
                settings.b(Id::kEstopNormallyClosed) ? "normally-closed" : "normally-open");
  }
  controller.begin(now_ms());

  // 3. The USB protocol port: one session, fresh whenever a program opens
  // the port (usb_cdc_link.hpp).
  static usb_port::PersonalitySessions usb_sessions(usb_personality, controller, ROTORD_VERSION);
  static TinyUsbCdcPort usb_cdc(ROTORD_USB_PROTOCOL_CDC);
  static std::optional<usb_port::UsbCdcLink> usb_link;
  if (usb_personality) {
    usb_link.emplace(usb_cdc, usb_sessions);
    std::printf("rotord: %s on USB (the second USB serial port)\n",
                usb_port::personality_name(usb_personality));
  }

  // GET /metrics and /healthz: what the loop and the transports count.
  static metrics::Registry registry;
  static PicoMonotonicClock monotonic_clock;
  // The n-th tick at start + n x kTickMs (loop/tick_scheduler.hpp): network
  // traffic delays a tick but never shifts the ones after it.
  static TickScheduler ticks(kTickMs * 1000);
  registry.ticks = &ticks;
  registry.clock = &monotonic_clock;
  // Without the HELP lines the page is about 7 KB: it must pass through
  // lwIP's send buffer (TCP_SND_BUF, 11.7 KB) and the 1 KiB output buffer.
  registry.help_text = false;

  // 4. Network. Without the Wi-Fi chip the controller still runs (USB logs,
  // safety rules), it just takes no commands.
  const bool network = wifi_chip_up();

  // wifi.*, net.*, time.* as loaded at boot (they all need a restart).
  Wifi::Config wifi_config =
      Wifi::config_from(settings, ROTORD_WIFI_CONNECT_TIMEOUT_S * Millis{1000});
  // Announced by mDNS, as rotord on Linux announces them through Avahi.
  // The TCP ports are the registry's (every line protocol is served below).
  const auto tcp_port = [](Personality personality) {
    return protocol::protocol_info(personality).tcp_port;
  };
  wifi_config.ports = net::ServicePorts{kHttpPort,
                                        tcp_port(Personality::kRotctld),
                                        tcp_port(Personality::kWrc),
                                        tcp_port(Personality::kGs232),
                                        tcp_port(Personality::kEasycomm),
                                        tcp_port(Personality::kSeed)};
  static Wifi wifi(wifi_config);
  // WRC MONITOR lines also go to the USB log port as they happen, where the
  // WRC firmware prints them, but only while a terminal listens (log_port.hpp).
  static LogPortSink log_port(g_log);
  static protocol::MonitorTap monitor_tap(log_port);
  static const protocol::SessionDeps deps{controller, ROTORD_VERSION, &monitor_tap};
  // Every server admits by net/admission.hpp with the live settings (idle
  // eviction, per-address cap, allow-list), as on Linux.
  auto line_config = [&settings](Personality personality) {
    const protocol::ProtocolInfo& info = protocol::protocol_info(personality);
    lwip_port::ServerConfig config;
    config.name = info.name.data();  // a string literal
    config.port = info.tcp_port;
    config.max_clients = static_cast<std::size_t>(settings.i(Id::kNetMaxClients));
    config.reject_message = info.refusal;
    config.settings = &settings;
    config.metrics = &registry;
    config.protocol = info.metric;
    return config;
  };
  static LineService<Personality::kWrc> wrc(line_config(Personality::kWrc),
                                            MakeSession<Personality::kWrc>{&deps});
  static LineService<Personality::kRotctld> rotctld(line_config(Personality::kRotctld),
                                                    MakeSession<Personality::kRotctld>{&deps});
  static LineService<Personality::kGs232> gs232(line_config(Personality::kGs232),
                                                MakeSession<Personality::kGs232>{&deps});
  static LineService<Personality::kEasycomm> easycomm(line_config(Personality::kEasycomm),
                                                      MakeSession<Personality::kEasycomm>{&deps});
  // The seed protocol: on the Pico's TCP too since issue 11 (port 4603).
  static LineService<Personality::kSeed> seed(line_config(Personality::kSeed),
                                              MakeSession<Personality::kSeed>{&deps});
  // POST /api/settings persists to the flash slots (RAM only when the
  // program image would overlap them).
  hal::Storage* const storage = g_flash.region_free() ? &g_saver : nullptr;
  g_saver.begin();  // what was loaded (or deliberately not overwritten) counts as saved
  if (storage != nullptr) registry.saver = &g_saver;
  static SntpWallClock wall_clock(&now_ms);  // time_utc once SNTP has answered
  // Access control's crypto: seeded once here (its only heap allocation).
  static PicoCrypto crypto;
  if (!crypto.begin()) std::printf("rotord: mbedtls could not seed: web logins refused\n");
  web::ApiContext api_context{controller,     storage,     &g_defaults, &g_reboot,
                              ROTORD_VERSION, &wall_clock, nullptr,     &registry};
  api_context.crypto = crypto.ready() ? &crypto : nullptr;
  api_context.pbkdf2_iterations = kPbkdf2Iterations;
  api_context.pbkdf2_slice = kPbkdf2SliceIterations;
  api_context.log = &log_port;
  // Tracking: UTC from SNTP (refused until it has answered), one target
  // evaluation (about 3 ms) per tick for the pass search and the plan, and
  // GET /api/passes a slice per loop. The TLEs in their flash slots; a PUT
  // while the rotator moves is refused (a flash write pauses this loop).
  controller.attach_utc_clock(&wall_clock);
  controller.set_track_budget(1);
  api_context.passes_request_budget = 10;
  api_context.passes_poll_budget = 1;
  api_context.tle_save_while_moving = false;
  if (g_tle_flash.region_free()) {
    static char tle_text[tracking::TleCatalog::kMaxTextBytes];
    g_tles.load(g_tle_storage, tle_text, sizeof tle_text);
    api_context.tle_storage = &g_tle_storage;
    std::printf("rotord: %u TLEs in flash\n", static_cast<unsigned>(g_tles.size()));
  }
  api_context.tles = &g_tles;
  static web::Api api(api_context);
  auto make_http = [] { return web::HttpSession(api); };
  lwip_port::ServerConfig http_config;
  http_config.name = "web UI and REST API";
  http_config.port = kHttpPort;
  http_config.max_clients = kHttpSlots;
  http_config.reject_message = web::HttpSession::kTooManyConnections;
  http_config.is_immutable = &in_program_flash;
  http_config.settings = &settings;
  http_config.max_event_streams =
      std::min(kHttpEventStreams, static_cast<std::size_t>(settings.i(Id::kWebMaxEventStreams)));
  http_config.metrics = &registry;
  http_config.protocol = metrics::Protocol::kHttp;
  static lwip_port::StaticService<web::HttpSession, kHttpSlots, decltype(make_http)> http(
      http_config, make_http);
  lwip_port::TcpServer* const servers[] = {&wrc.server(),      &rotctld.server(), &gs232.server(),
                                           &easycomm.server(), &seed.server(),    &http.server()};
  if (network) {
    wifi.begin(now_ms());
    // lwIP listens on every address, so the servers work on the station and
    // on the setup access point alike.
    for (lwip_port::TcpServer* server : servers) {
      if (server->start())
        std::printf("rotord: %s on port %u\n", server->name(), server->port());
      else
        std::printf("rotord: %s: cannot listen\n", server->name());
    }
  }

  // 5. The loop. Started after the blocking Wi-Fi chip init (firmware load).
  watchdog_enable(kWatchdogMs, true /* pause while a debugger halts the core */);
  ticks.start(static_cast<std::int64_t>(time_us_64()));
  registry.start_us = ticks.deadline_us() - kTickMs * 1000;
  std::uint64_t reported_overruns = 0;
  std::uint32_t reported_usb_drops = 0;
  Millis next_report = now_ms() + 10'000;
  Millis reboot_at = 0;
  for (;;) {
    watchdog_update();
    // USB every pass: neither TinyUSB's task nor the link waits for the host.
    rotord_usb_task();
    g_log.service();
    if (usb_link) usb_link->service();
    if (network) cyw43_arch_poll();
    if (ticks.poll(static_cast<std::int64_t>(time_us_64()))) {
      const Millis now = now_ms();
      controller.tick(now);
      api.poll(now);  // hold-to-move's dead-man, with or without a connection
      if (usb_link) usb_link->poll(now);
      if (network) {
        for (lwip_port::TcpServer* server : servers) server->poll(now);
        wifi.step(now);
      }
      // Settings changed by a protocol: saved after a quiet time, while the
      // rotator stands (a flash erase stalls this loop for tens of ms).
      if (storage != nullptr) report_save(g_saver.poll(now, controller.status().moving()));
      if (g_reboot.requested()) {
        if (reboot_at == 0) reboot_at = now + kRebootDelayMs;
        if (now >= reboot_at) {
          std::printf("rotord: rebooting\n");
          controller.shutdown();
          if (storage != nullptr) report_save(g_saver.flush(now));  // motors off first
          // watchdog_update() would postpone a delayed reboot forever, so
          // reboot now and wait for it here.
          watchdog_reboot(0, 0, 0);
          for (;;) tight_loop_contents();
        }
      }
      if (now >= next_report) {
        // Ticks skipped because the loop fell a whole period behind (the
        // scheduler never runs a burst of catch-up ticks).
        if (ticks.stats().overruns != reported_overruns)
          std::printf("rotord: %lu control ticks skipped so far (loop overruns)\n",
                      static_cast<unsigned long>(ticks.stats().overruns));
        reported_overruns = ticks.stats().overruns;
        if (usb_link && usb_link->stats().dropped_replies != reported_usb_drops) {
          reported_usb_drops = usb_link->stats().dropped_replies;
          std::printf("rotord: USB: %lu replies dropped so far (the program stopped reading)\n",
                      static_cast<unsigned long>(reported_usb_drops));
        }
        next_report = now + 10'000;
      }
    }
    const absolute_time_t next_tick =
        from_us_since_boot(static_cast<std::uint64_t>(ticks.deadline_us()));
    // A login or a new password being hashed: its slices fill the time up to
    // the next tick instead of sleeping (the tick is never late by more
    // than one slice, and the watchdog is fed on every pass).
    while (api.auth_busy() &&
           absolute_time_diff_us(get_absolute_time(), next_tick) > kSliceHeadroomUs)
      api.work();
    if (network)
      cyw43_arch_wait_for_work_until(next_tick);
    else
      sleep_until(next_tick);
  }
}

}  // namespace
}  // namespace rotord::pico_w

int main() {
  rotord::pico_w::run();
}
