// The composition root of the Pico W firmware (the counterpart of
// ports/linux/daemon.cpp): outputs off, watchdog, the HAL over the SDK, the
// controller, Wi-Fi and the protocol servers, all run from one poll loop.
//
// One loop, no interrupts into the core: pico_cyw43_arch_lwip_poll runs lwIP
// only inside cyw43_arch_poll(), so network callbacks, sessions and the
// control tick never run concurrently and the core needs no locks. The tick
// is scheduled by absolute deadline and the loop sleeps only until the next
// deadline, so network traffic delays a tick by at most one poll.
#include <cstdio>

#include "hardware/address_mapped.h"
#include "hardware/watchdog.h"
#include "lwip_transport.hpp"
#include "pico/binary_info.h"
#include "pico/cyw43_arch.h"
#include "pico/stdlib.h"
#include "pico_hal.hpp"
#include "protocol/wrc_session.hpp"
#include "rotator/controller.hpp"
#include "settings/settings.hpp"
#include "web/http_session.hpp"
#include "web/web_api.hpp"
#include "wifi.hpp"
#include "wifi_secrets.h"

namespace rotord::pico_w {
namespace {

constexpr Millis kTickMs = 10;  // 100 Hz, as on Linux
// Long enough for the slowest blocking SDK call in the loop (enabling the
// access point: a few Wi-Fi chip ioctls), short enough that a hung loop stops
// a turning motor within 2 s (12 deg on a 6 deg/s G-5500; the reset puts
// every pin back to an input with its pull-down, i.e. relays off).
constexpr std::uint32_t kWatchdogMs = 2000;
constexpr std::uint16_t kWrcPort = 1234;
constexpr std::size_t kWrcSlots = 4;  // net.max_clients is clamped to this
constexpr std::uint16_t kHttpPort = 80;
// A browser holds a page connection and the event stream, plus short API
// requests; each HTTP session is ~6 KB of RAM (request head and body buffers).
constexpr std::size_t kHttpSlots = 4;
// POST /api/reboot answers first, then the watchdog resets the chip.
constexpr Millis kRebootDelayMs = 300;

// Pin map. Azimuth: the defaults of issue 6 (relays CW/CCW 5/6, speed 7,
// T1/T2 9/10, L1/L2 11/12, pot on GPIO 26, MA3 on GPIO 2). The elevation
// and H-bridge pins are chosen not to collide with them. GPIO 23..25 and 29
// belong to the Wi-Fi chip on the Pico W.
// TODO(pin settings): read these from the settings table once it has pin rows.
namespace pin {
constexpr int kAzPot = 26, kElPot = 27;
constexpr int kAzMa3 = 2, kElMa3 = 3;
constexpr int kAzRelayCw = 5, kAzRelayCcw = 6, kAzSpeed = 7, kAzBrake = 8;
constexpr int kAzT1 = 9, kAzT2 = 10, kAzLimitCcw = 11 /* L1 */, kAzLimitCw = 12 /* L2 */;
constexpr int kAzPwmCw = 14, kAzPwmCcw = 15;
constexpr int kElRelayUp = 16, kElRelayDown = 17, kElSpeed = 18;
constexpr int kElLimitUp = 19, kElLimitDown = 22;
constexpr int kElPwmUp = 20, kElPwmDown = 21;
}  // namespace pin

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

// Hardware objects: static storage, constructors touch nothing.
settings::Settings g_settings;
const settings::Settings g_defaults;  // the table's defaults, for the web's reset
Reboot g_reboot;
PicoAdc g_az_pot(pin::kAzPot), g_el_pot(pin::kElPot);
Ma3EdgeInput g_az_ma3(pin::kAzMa3), g_el_ma3(pin::kElMa3);
PicoSwitch g_az_t1(pin::kAzT1), g_az_t2(pin::kAzT2);
PicoSwitch g_az_limit_cw(pin::kAzLimitCw), g_az_limit_ccw(pin::kAzLimitCcw);
PicoSwitch g_el_limit_up(pin::kElLimitUp), g_el_limit_down(pin::kElLimitDown);
PicoDriveSink g_az_drive(drive_pins(0, pin::kAzRelayCw, pin::kAzRelayCcw, pin::kAzSpeed,
                                    pin::kAzBrake, pin::kAzPwmCw, pin::kAzPwmCcw));
PicoDriveSink g_el_drive(drive_pins(0, pin::kElRelayUp, pin::kElRelayDown, pin::kElSpeed, kNoPin,
                                    pin::kElPwmUp, pin::kElPwmDown));

// The wiring, readable from the .uf2 or the board with `picotool info -a`.
void declare_pins() {
  // clang-format off
  bi_decl(bi_1pin_with_name(pin::kAzRelayCw, "az relay CW"));
  bi_decl(bi_1pin_with_name(pin::kAzRelayCcw, "az relay CCW"));
  bi_decl(bi_1pin_with_name(pin::kAzSpeed, "az speed / voltage select"));
  bi_decl(bi_1pin_with_name(pin::kAzBrake, "az brake"));
  bi_decl(bi_1pin_with_name(pin::kAzT1, "az T1 (pull-up, active low)"));
  bi_decl(bi_1pin_with_name(pin::kAzT2, "az T2 (pull-up, active low)"));
  bi_decl(bi_1pin_with_name(pin::kAzLimitCcw, "az L1 CCW limit (pull-up, active low)"));
  bi_decl(bi_1pin_with_name(pin::kAzLimitCw, "az L2 CW limit (pull-up, active low)"));
  bi_decl(bi_1pin_with_name(pin::kAzPot, "az pot (ADC0)"));
  bi_decl(bi_1pin_with_name(pin::kAzMa3, "az MA3 PWM (az.sensor=ma3)"));
  bi_decl(bi_2pins_with_names(pin::kAzPwmCw, "az H-bridge CW", pin::kAzPwmCcw, "az H-bridge CCW"));
  bi_decl(bi_1pin_with_name(pin::kElPot, "el pot (ADC1)"));
  bi_decl(bi_1pin_with_name(pin::kElMa3, "el MA3 PWM (el.sensor=ma3)"));
  bi_decl(bi_2pins_with_names(pin::kElRelayUp, "el relay UP", pin::kElRelayDown, "el relay DOWN"));
  bi_decl(bi_1pin_with_name(pin::kElSpeed, "el speed / voltage select"));
  bi_decl(bi_2pins_with_names(pin::kElLimitUp, "el UP limit", pin::kElLimitDown, "el DOWN limit"));
  bi_decl(bi_2pins_with_names(pin::kElPwmUp, "el H-bridge UP", pin::kElPwmDown, "el H-bridge DOWN"));
  // clang-format on
}

[[noreturn]] void run() {
  // 1. Outputs off before anything that can take time or fail.
  g_az_drive.begin();
  g_el_drive.begin();
  declare_pins();

  stdio_init_all();
  std::printf("rotord %s (Pico W)%s\n", ROTORD_VERSION,
              watchdog_caused_reboot() ? ": restarted by the watchdog" : "");

  // 2. Settings. TODO(flash settings): load them from the two flash slots
  // (core/storage/flash_slots, not there yet); until then the table's
  // defaults apply at every boot.
  settings::Settings& settings = g_settings;
  const int az_drive = settings.i(settings::Id::kAzDrive);
  const int el_drive = settings.i(settings::Id::kElDrive);
  g_az_drive.configure(drive_pins(az_drive, pin::kAzRelayCw, pin::kAzRelayCcw, pin::kAzSpeed,
                                  pin::kAzBrake, pin::kAzPwmCw, pin::kAzPwmCcw));
  g_el_drive.configure(drive_pins(el_drive, pin::kElRelayUp, pin::kElRelayDown, pin::kElSpeed,
                                  kNoPin, pin::kElPwmUp, pin::kElPwmDown));

  // 3. Inputs. The MA3 interrupt is only enabled for an axis that uses it,
  // so an unwired pin can never load the CPU.
  const bool has_el = settings.b(settings::Id::kElEnabled);
  g_az_pot.begin();
  g_az_t1.begin();
  g_az_t2.begin();
  g_az_limit_cw.begin();
  g_az_limit_ccw.begin();
  if (settings.i(settings::Id::kAzSensor) == 1) g_az_ma3.begin();
  if (has_el) {
    g_el_pot.begin();
    g_el_limit_up.begin();
    g_el_limit_down.begin();
    if (settings.i(settings::Id::kElSensor) == 1) g_el_ma3.begin();
  }
  const AxisIo az_io{&g_az_pot, &g_az_ma3, &g_az_limit_cw, &g_az_limit_ccw,
                     &g_az_t1,  &g_az_t2,  &g_az_drive};
  const AxisIo el_io{&g_el_pot, &g_el_ma3, &g_el_limit_up, &g_el_limit_down,
                     nullptr,   nullptr,   &g_el_drive};
  static Controller controller(settings, az_io, el_io);
  controller.begin(now_ms());

  // 4. Network. Without the Wi-Fi chip the controller still runs (USB logs,
  // safety rules), it just takes no commands.
  const bool network = cyw43_arch_init() == 0;
  if (!network) std::printf("rotord: Wi-Fi chip init failed; running without network\n");

  static Wifi wifi({ROTORD_WIFI_SSID, ROTORD_WIFI_PASSWORD, ROTORD_AP_PASSWORD,
                    ROTORD_WIFI_CONNECT_TIMEOUT_S * Millis{1000}});
  auto make_wrc = [] { return protocol::WrcSession(controller, ROTORD_VERSION); };
  static lwip_port::StaticService<protocol::WrcSession, kWrcSlots, decltype(make_wrc)> wrc(
      {"WRC text protocol", kWrcPort,
       static_cast<std::size_t>(settings.i(settings::Id::kNetMaxClients)),
       protocol::WrcSession::kTooManyConnections},
      make_wrc);
  // TODO(flash settings): give the API the flash storage so that POST
  // /api/settings persists; with nullptr it changes the settings in RAM only.
  static web::Api api(web::ApiContext{controller, nullptr, &g_defaults, &g_reboot, ROTORD_VERSION});
  auto make_http = [] { return web::HttpSession(api); };
  lwip_port::ServerConfig http_config;
  http_config.name = "web UI and REST API";
  http_config.port = kHttpPort;
  http_config.max_clients = kHttpSlots;
  http_config.reject_message = web::HttpSession::kTooManyConnections;
  http_config.is_immutable = &in_program_flash;
  static lwip_port::StaticService<web::HttpSession, kHttpSlots, decltype(make_http)> http(
      http_config, make_http);
  // TODO(protocols): rotctld on 4533 and GS-232/Easycomm join here as
  // StaticServices once their sessions are in the core.
  lwip_port::TcpServer* const servers[] = {&wrc.server(), &http.server()};
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
  absolute_time_t next_tick = make_timeout_time_ms(kTickMs);
  std::uint32_t late_ticks = 0;
  std::uint32_t reported_late_ticks = 0;
  Millis next_report = now_ms() + 10'000;
  Millis reboot_at = 0;
  for (;;) {
    watchdog_update();
    if (network) cyw43_arch_poll();
    if (time_reached(next_tick)) {
      const Millis now = now_ms();
      controller.tick(now);
      if (network) {
        for (lwip_port::TcpServer* server : servers) server->poll(now);
        wifi.step(now);
      }
      if (g_reboot.requested()) {
        if (reboot_at == 0) reboot_at = now + kRebootDelayMs;
        if (now >= reboot_at) {
          std::printf("rotord: rebooting\n");
          controller.shutdown();
          // watchdog_update() would postpone a delayed reboot forever, so
          // reboot now and wait for it here.
          watchdog_reboot(0, 0, 0);
          for (;;) tight_loop_contents();
        }
      }
      next_tick = delayed_by_ms(next_tick, kTickMs);
      if (time_reached(next_tick)) {
        // Fell a whole tick behind: resynchronise instead of running a burst
        // of ticks back to back (the controller works from `now`, not counts).
        ++late_ticks;
        next_tick = make_timeout_time_ms(kTickMs);
      }
      if (now >= next_report) {
        if (late_ticks != reported_late_ticks)
          std::printf("rotord: %lu late control ticks so far\n",
                      static_cast<unsigned long>(late_ticks));
        reported_late_ticks = late_ticks;
        next_report = now + 10'000;
      }
    }
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
