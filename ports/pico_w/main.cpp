// The composition root of the Pico W and plain Pico firmware (the
// counterpart of ports/linux/daemon.cpp): outputs off, watchdog, the HAL over
// the SDK, the controller, the USB ports and, on the Pico W, Wi-Fi and the
// network servers (network_services.hpp), all run from one poll loop.
//
// One loop, no interrupts into the core: pico_cyw43_arch_lwip_poll runs lwIP
// only inside cyw43_arch_poll(), so network callbacks, sessions and the
// control tick never run concurrently and the core needs no locks. The tick
// is scheduled by absolute deadline (TickScheduler) and the loop sleeps only
// until the next deadline, so network traffic delays a tick by at most one
// poll.
#include <cstdio>
#include <optional>
#include <string_view>

#include "axis/sensor_registry.hpp"
#include "care/odometer_saver.hpp"
#include "command/buttons.hpp"
#include "command/command_log.hpp"
#include "hardware/address_mapped.h"
#include "hardware/watchdog.h"
#include "json/settings_json.hpp"
#include "log_port.hpp"
#include "loop/tick_scheduler.hpp"
#include "ma3_pio.hpp"
#include "metrics/registry.hpp"
#include "pico/binary_info.h"
#include "pico/bootrom.h"
#include "pico/stdio/driver.h"
#include "pico/stdio_usb.h"
#include "pico/stdlib.h"
#include "pico_flash.hpp"
#include "pico_hal.hpp"
#include "protocol/console_session.hpp"
#include "protocol/protocol_registry.hpp"
#include "rotator/axis_events.hpp"
#include "rotator/controller.hpp"
#include "rotator/recognition_events.hpp"
#include "sensors/magnetometer.hpp"
#include "settings/pin_rules.hpp"
#include "settings/settings.hpp"
#include "storage/flash_slots.hpp"
#include "storage/settings_saver.hpp"
#include "usb_cdc_port.hpp"
#include "usb_personality.hpp"
#if ROTORD_PICO_NETWORK
#include "network_services.hpp"
#include "wifi_secrets.h"
#endif

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
// POST /api/reboot (and the console's reboot) answers first, then the
// watchdog resets the chip.
constexpr Millis kRebootDelayMs = 300;
/// The wear odometer's save interval on the flash (docs/care.md, the endurance).
constexpr Millis kOdometerSaveMs = 600000;
using protocol::Personality;
using settings::Id;
using settings::kNoPin;

/// A line of the command layer's log on the USB log port (stdout there).
class StdoutLine final : public ByteSink {
 public:
  void write(std::string_view bytes) override {
    std::printf("rotord: %.*s\n", static_cast<int>(bytes.size()), bytes.data());
  }
};

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

/// The loop's clock for GET /healthz (the age of the last tick): the same
/// microsecond timer the tick schedule runs on.
class PicoMonotonicClock final : public hal::MonotonicClock {
 public:
  std::int64_t now_us() const override { return static_cast<std::int64_t>(time_us_64()); }
};

/// A reboot asked for (POST /api/reboot on the Pico W, the console's
/// `reboot` and `bootsel`): remembered here, done by the loop once the
/// answer is out (the request runs inside it).
class Reboot final : public command::SystemHooks {
 public:
  void request() { requested_ = true; }
  bool requested() const { return requested_; }
  /// Into the ROM's USB bootloader (the RPI-RP2 drive and picotool) rather
  /// than into rotord again.
  bool to_bootloader() const { return bootloader_; }

  const char* reboot() override {
    request();
    return nullptr;
  }
  const char* reboot_to_bootloader() override {
    bootloader_ = true;
    request();
    return nullptr;
  }

 private:
  bool requested_ = false;
  bool bootloader_ = false;
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
char g_boot_document[web::kMaxSettingsDocumentBytes];
// What loading dropped, for the log and the settings page (about 800 bytes).
web::LoadReport g_load_report;
static_assert(sizeof(web::LoadReport) <= 800, "the load report's RAM (docs/security.md)");
Reboot g_reboot;
PicoFlash g_flash;
FlashSlots g_storage(g_flash);
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
std::optional<PicoPulseCounter> g_wind_pulses;
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

#if ROTORD_PICO_NETWORK
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
#endif

/// The user's changes from the flash slots over the board's defaults (the
/// table's plus wifi_secrets.h). Invalid stored settings (a pin conflict, a
/// value a newer firmware refuses) leave the defaults in place; the stored
/// copy stays in flash, and the next save goes to the other slot. A slot
/// written before layering (every setting) keeps every value that differs
/// from the board's defaults.
web::LoadOutcome load_stored_settings() {
  if (!g_flash.region_free()) return {};
  return web::load_settings(g_saver, g_defaults, nullptr, g_settings, g_scratch, g_boot_document,
                            sizeof g_boot_document, &g_load_report);
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
    case web::LoadOutcome::kRepaired:
      for (std::size_t n = 0; n < g_load_report.size(); ++n)
        std::printf("rotord: settings in flash: %s%s%s: dropped, running on the default\n",
                    g_load_report[n].key, g_load_report[n].key[0] != '\0' ? ": " : "",
                    g_load_report[n].reason);
      std::printf("rotord: every other setting loaded from flash\n");
      break;
    case web::LoadOutcome::kCorrupt:
      std::printf("rotord: the settings in flash are invalid (%s%s%s); running on the defaults\n",
                  r.key, r.key[0] != '\0' ? ": " : "", r.reason);
      break;
  }
  if (r.access_unreadable)
    std::printf(
        "rotord: the access settings cannot be read: every port obeys only STOP and answers "
        "status until they are fixed (erase the settings flash: docs/security.md)\n");
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

/// Says in the log whether the magnetometer answers: a board reached only
/// over USB has no other way to tell a wiring fault from a calibration one
/// (the azimuth reads SENSOR_LOST until the chip answers). Linux refuses to
/// start instead (ports/linux/gpiod_io.cpp); a Pico must stay reachable.
/// Seen missing on the emulated RP2040 (make hil, mag-absent).
void log_magnetometer(PicoI2c& bus, const settings::Settings& s) {
  Magnetometer probe(bus);
  const auto chip = static_cast<MagChip>(s.i(Id::kMagChip));
  probe.set_chip(chip);
  const bool qmc = chip == MagChip::kQmc5883l;
  const char* name = qmc ? "QMC5883L" : "HMC5883L";
  const unsigned address = qmc ? Magnetometer::kQmcAddress : Magnetometer::kHmcAddress;
  const int sda = s.i(Id::kPinI2cSda);
  const int scl = s.i(Id::kPinI2cScl);
  switch (probe.begin()) {
    case Magnetometer::Status::kOk:
      std::printf("rotord: az magnetometer %s at 0x%02X (I2C on GPIO %d SDA, %d SCL)\n", name,
                  address, sda, scl);
      break;
    case Magnetometer::Status::kWrongChip:
      std::printf(
          "rotord: az magnetometer: the chip at 0x%02X (GPIO %d SDA, %d SCL) is not a %s "
          "(is mag.chip right?); the azimuth reads SENSOR_LOST\n",
          address, sda, scl, name);
      break;
    default:
      std::printf(
          "rotord: az magnetometer: no %s answers at 0x%02X on GPIO %d SDA, %d SCL "
          "(wiring, power, pull-ups?); the azimuth reads SENSOR_LOST\n",
          name, address, sda, scl);
      break;
  }
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
  // The inputs the sensor type reads (its row), fitted by input, never by
  // type: a new type on one of these needs nothing here. (The ADC above is
  // fitted whenever its pin is wired, whatever the type.)
  const SensorInput input = find_sensor(s.i(k.sensor))->input;  // the table's range: a row
  if (input == SensorInput::kPwm)
    io.ma3 = fit_ma3(parts.ma3_pio, parts.ma3_irq, s.i(k.ma3), k.name);
  if (k.may_use_magnetometer && input == SensorInput::kI2c) {
    if (PicoI2c* bus = fit(g_i2c, s.i(Id::kPinI2cSda), s.i(Id::kPinI2cScl))) {
      bus->begin();
      log_magnetometer(*bus, s);
      io.i2c = bus;
    }
  }
  if (s.b(Id::kButtonsEnabled)) {
    io.button_fwd = fit_switch(parts.button_fwd, s.i(k.button_fwd));
    io.button_rev = fit_switch(parts.button_rev, s.i(k.button_rev));
  }
  return io;
}

/// Why the chip started, for the banner. A reboot that was asked for (web,
/// console, REST) also goes through the watchdog (watchdog_reboot), so
/// watchdog_caused_reboot() alone would call it a watchdog reset: only a
/// timeout of the watchdog armed by watchdog_enable() (a hung loop) leaves
/// the SDK's magic in scratch[4]. Seen on the emulated RP2040 (make hil).
const char* restart_reason() {
  if (watchdog_enable_caused_reboot()) return ": restarted by the watchdog (the loop hung)";
  if (watchdog_caused_reboot()) return ": restarted (reboot requested)";
  return "";
}

[[noreturn]] void run() {
  // 1. Outputs off. Until the pins are known every GPIO is still an input
  // with its reset pull-down (relays off); the settings come first because
  // they say which pins are outputs, and reading them takes milliseconds.
  settings::Settings& settings = g_settings;
#if ROTORD_PICO_NETWORK
  apply_wifi_secrets(g_defaults);
  apply_wifi_secrets(g_settings);
#endif
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
  std::printf("rotord %s (%s)%s\n", ROTORD_VERSION, ROTORD_PICO_BOARD_NAME, restart_reason());
  report_settings(loaded);

  // 2. Inputs, from the pins.* settings (kAxisPins).
  const AxisIo az_io = fit_inputs(settings, kAxisPins[0], az);
  const AxisIo el_io = has_el ? fit_inputs(settings, kAxisPins[1], el) : AxisIo{};
  static Controller controller(settings, az_io, el_io);
  // The manual buttons (pins.btn_*): a front end of the command layer,
  // polled just before each tick.
  static command::Buttons buttons(controller, az_io, el_io);
  // One line per command that changes something, from every front end
  // (command/command_log.hpp), on the USB log port like the events below.
  static StdoutLine command_lines;
  static command::CommandLog command_log(command_lines);
  controller.attach_journal(&command_log);
  if (PicoSwitch* estop = fit_switch(g_estop, p(Id::kPinEstop))) {
    controller.attach_estop(estop);
    std::printf("rotord: emergency stop on GPIO %d (%s contact)\n", p(Id::kPinEstop),
                settings.b(Id::kEstopNormallyClosed) ? "normally-closed" : "normally-open");
  }
  // Wind stow (docs/care.md): the anemometer's pulses on pins.wind.
  if (settings.i(Id::kWindSource) == 2 && p(Id::kPinWind) != kNoPin) {
    g_wind_pulses.emplace(p(Id::kPinWind));
    g_wind_pulses->begin();
    controller.attach_wind_pulses(&*g_wind_pulses);
    std::printf("rotord: anemometer on GPIO %d (%.2f pulses per m/s)\n", p(Id::kPinWind),
                settings.get(Id::kWindPulsesPerMps));
  }
  controller.begin(now_ms());
  // The wear odometer (docs/care.md): back from its flash slots, saved every
  // 10 minutes in turn over eight sectors (the flash's endurance for ten
  // years, computed there). Its document buffer is the start-up one too:
  // the settings saver and this one run one after the other in this loop.
  static PicoFlash odometer_flash(PicoFlash::kRegionBytes + PicoFlash::kTleRegionBytes,
                                  PicoFlash::kOdometerRegionBytes);
  static FlashSlots odometer_slots(odometer_flash, PicoFlash::kOdometerSlots);
  static care::OdometerSaver odometer_saver(controller.odometer(), odometer_slots, g_boot_document,
                                            sizeof g_boot_document, kOdometerSaveMs);
  const bool odometer_kept = odometer_flash.region_free();
  if (odometer_kept) {
    const care::OdometerSaver::Load l = odometer_saver.load(now_ms());
    if (l == care::OdometerSaver::Load::kDamaged)
      std::printf("rotord: the odometer in flash is damaged (%s): counting again from zero\n",
                  odometer_saver.why());
  }
  // Faults latched and slips, named, for the log port (docs/care.md).
  static AxisEvents axis_events;
  axis_events.begin(controller.status());
  static RecognitionEvents recognition_events;
  recognition_events.begin(controller.recognition());

  // 3. The USB protocol port: one session, fresh whenever a program opens
  // the port (usb_cdc_link.hpp).
  // The console (protocol/console_session.hpp) on the log port, CDC 0:
  // settings, calibration, fault reset, reboot and bootsel over USB, for a
  // board with no network (ports/pico_w/README.md, "USB console"). g_scratch
  // is free once the settings are loaded.
  static const protocol::ConsolePort console_port{&g_defaults, &g_scratch, &g_reboot,
                                                  ROTORD_PICO_BOARD_NAME};
  static protocol::ConsoleSession console(controller, ROTORD_VERSION, &console_port);
  g_log.attach_console(console);
  static usb_port::PersonalitySessions usb_sessions(usb_personality, controller, ROTORD_VERSION,
                                                    &console_port);
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

  // POST /api/settings and the protocols' changes persist to the flash
  // slots (RAM only when the program image would overlap them).
  hal::Storage* const storage = g_flash.region_free() ? &g_saver : nullptr;
  g_saver.begin();  // what was loaded (or deliberately not overwritten) counts as saved
  if (storage != nullptr) {
    registry.settings_writes = &g_saver.writes();
    registry.settings_failures = &g_saver.failures();
  }
  if (odometer_kept) {
    registry.odometer_writes = &odometer_saver.writes();
    registry.odometer_failures = &odometer_saver.failures();
  }

#if ROTORD_PICO_NETWORK
  // 4. Network (network_services.hpp). Without the Wi-Fi chip the controller
  // still runs (USB logs, safety rules, the USB protocol port).
  static LogPortSink log_port(g_log);
  network_start(NetworkDeps{controller, settings, &g_defaults, storage, registry, log_port,
                            &g_reboot, &g_load_report},
                now_ms());
#endif

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
#if ROTORD_PICO_NETWORK
    network_service();
#endif
    if (ticks.poll(static_cast<std::int64_t>(time_us_64()))) {
      const Millis now = now_ms();
      buttons.poll(now);
      controller.tick(now);
      command_log.poll(now);  // commands' repeats summed up
      {
        char event[160];
        const RotatorStatus st = controller.status();
        while (axis_events.next(st, event, sizeof event)) std::printf("rotord: %s\n", event);
        while (recognition_events.next(controller.recognition(), event, sizeof event))
          std::printf("rotord: %s\n", event);
      }
      if (usb_link) usb_link->poll(now);
#if ROTORD_PICO_NETWORK
      network_tick(now);
#endif
      // Settings changed by a protocol: saved after a quiet time, while the
      // rotator stands (a flash erase stalls this loop for tens of ms).
      if (storage != nullptr) report_save(g_saver.poll(now, controller.status().moving()));
      if (odometer_kept && odometer_saver.poll(now, controller.status().moving()) ==
                               care::OdometerSaver::Result::kFailed)
        std::printf("rotord: saving the odometer to flash failed\n");
      if (g_reboot.requested()) {
        if (reboot_at == 0) reboot_at = now + kRebootDelayMs;
        if (now >= reboot_at) {
          std::printf("rotord: rebooting\n");
          controller.shutdown();
          if (storage != nullptr) report_save(g_saver.flush(now));  // motors off first
          if (odometer_kept) odometer_saver.flush(now);
          // The ROM's USB bootloader for a firmware update (the console's
          // bootsel): the RPI-RP2 drive and picotool's interface.
          if (g_reboot.to_bootloader()) reset_usb_boot(0, 0);
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
#if ROTORD_PICO_NETWORK
    network_wait_until(next_tick);
#else
    sleep_until(next_tick);
#endif
  }
}

}  // namespace
}  // namespace rotord::pico_w

int main() {
  rotord::pico_w::run();
}
