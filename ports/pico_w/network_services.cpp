// The Pico W's network side (network_services.hpp): moved out of main.cpp so
// that the plain Pico image (no Wi-Fi chip) is built without it.
#include "network_services.hpp"

#include <algorithm>
#include <array>
#include <cstdio>

#include "lwip/opt.h"
#include "lwip_mqtt.hpp"
#include "lwip_transport.hpp"
#include "lwip_udp.hpp"
#include "pico/cyw43_arch.h"
#include "pico_crypto.hpp"
#include "pico_flash.hpp"
#include "protocol/datagram_registry.hpp"
#include "sntp_clock.hpp"
#include "storage/flash_slots.hpp"
#include "tracking/tle_catalog.hpp"
#include "web/http_session.hpp"
#include "web/http_stop_only_session.hpp"
#include "web/web_api.hpp"
#include "wifi.hpp"
#include "wifi_secrets.h"

namespace rotord::pico_w {
namespace {

// Every line protocol of the registry (core/protocol/protocol_registry.hpp)
// on its TCP port, with a static pool of connection slots each, sized by
// the row's pico_tcp_slots; net.max_clients is clamped to the pool. lwIP's
// pools (config/lwipopts.h) are sized for these slots plus the web's 4.
// The console has none: it writes settings and reboots, which the network
// does through the web and REST with access control; it is on USB only
// (the log port, or usb.personality).
using protocol::Personality;
template <Personality P>
constexpr std::size_t kTcpSlots =
    protocol::rows::kProtocols[static_cast<std::size_t>(P)].pico_tcp_slots;
constexpr std::size_t line_servers() {
  std::size_t n = 0;
  for (const protocol::ProtocolInfo& p : protocol::rows::kProtocols) n += p.pico_tcp_slots > 0;
  return n;
}
// One listener each, and the web's (config/lwipopts.h: MEMP_NUM_TCP_PCB_LISTEN).
static_assert(line_servers() + 1 <= MEMP_NUM_TCP_PCB_LISTEN,
              "a row served on the Pico's TCP needs a listener: raise MEMP_NUM_TCP_PCB_LISTEN");

/// Builds a session of personality P for a static pool (returned by value:
/// guaranteed copy elision builds it in its slot).
template <Personality P>
struct MakeSession {
  const protocol::SessionDeps* deps;
  typename protocol::SessionOf<P>::type operator()() const {
    return protocol::SessionOf<P>::make(*deps);
  }
};
// A stop-only slot per line port (a newcomer to a full port may say STOP,
// net/admission.hpp) would cost a Connection (1.1 KB, its output buffer) and a
// session each, about 9 KB for the five, which the image does not have (RAM
// overflowed by 3,152 bytes). The five share one instead
// (lwip_port::SharedStopOnly): a Connection with a 128-byte output buffer and
// room for the largest line session (rotctld's), taken by one exchange (one
// short line, 2 s at most) at a time. It comes out of the heap's room, the RAM
// between the static data and the stack, where malloc takes under 1 KB (make
// hil prints it per scenario). Images with the slot once looked as if they
// stopped at boot in make hil's goto-mag: that scenario read the log the
// moment USB enumerated, a race its image layout decided, not a stop.
// ports/pico_w/README.md, docs/security.md.
constexpr std::size_t kStopOnlySlots = 0;
template <Personality... Ps>
constexpr std::size_t kLargestSession =
    std::max({sizeof(typename protocol::SessionOf<Ps>::type)...});
template <Personality... Ps>
constexpr std::size_t kLargestAlign =
    std::max({alignof(typename protocol::SessionOf<Ps>::type)...});
using SharedStopOnlySlot = lwip_port::StaticSharedStopOnly<
    kLargestSession<Personality::kWrc, Personality::kRotctld, Personality::kGs232,
                    Personality::kEasycomm, Personality::kSeed>,
    kLargestAlign<Personality::kWrc, Personality::kRotctld, Personality::kGs232,
                  Personality::kEasycomm, Personality::kSeed>>;
template <Personality P>
using LineService = lwip_port::StaticService<typename protocol::SessionOf<P>::type, kTcpSlots<P>,
                                             MakeSession<P>, kStopOnlySlots>;
/// Row P's TCP service, built on first call (a static of its own, as each
/// was when they were listed here); nullptr when the row has no Pico slots.
template <Personality P, typename Config>
lwip_port::TcpServer* serve_line(const protocol::SessionDeps& deps, const Config& line_config) {
  if constexpr (kTcpSlots<P> == 0) {
    return nullptr;
  } else {
    static LineService<P> service(line_config(P), MakeSession<P>{&deps});
    return &service.server();
  }
}
constexpr std::uint16_t kHttpPort = 80;
// A browser holds a page connection and the event stream, plus short API
// requests; each HTTP session is ~6 KB of RAM (request head and body buffers).
constexpr std::size_t kHttpSlots = 4;
// Open pages' event streams share those slots; at most this many, so two
// always remain for requests (web.max_event_streams is clamped to it), and a
// newcomer finding all four taken closes the oldest stream (net/admission.hpp).
constexpr std::size_t kHttpEventStreams = 2;
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

Millis now_ms() {
  return static_cast<Millis>(to_us_since_boot(get_absolute_time()) / 1000);
}

/// The program's flash (XIP) never changes while it runs: the web UI's
/// gzipped files there are sent by reference, without a copy in RAM.
bool in_program_flash(const void* data, std::size_t size) {
  const auto begin = reinterpret_cast<std::uintptr_t>(data);
  return begin >= XIP_BASE && begin + size <= XIP_BASE + PICO_FLASH_SIZE_BYTES;
}

// The stored TLEs: their own two slots right below the settings.
PicoFlash g_tle_flash(PicoFlash::kRegionBytes, PicoFlash::kTleRegionBytes);
FlashSlots g_tle_storage(g_tle_flash);
tracking::TleCatalog g_tles;

/// What the loop calls once network_start() has built it.
struct Running {
  bool network = false;  ///< the Wi-Fi chip answered
  Wifi* wifi = nullptr;
  web::Api* api = nullptr;
  std::span<lwip_port::TcpServer* const> servers;
  std::span<lwip_port::UdpService* const> udp_services;
  lwip_port::LwipMqtt* mqtt = nullptr;
};
Running g_running;

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

}  // namespace

void network_start(const NetworkDeps& d, Millis now) {
  settings::Settings& settings = d.settings;
  Controller& controller = d.controller;
  metrics::Registry& registry = d.registry;
  // Without the HELP lines the page is about 7 KB: it must pass through
  // lwIP's send buffer (TCP_SND_BUF, 11.7 KB) and the 1 KiB output buffer.
  registry.help_text = false;

  // Without the Wi-Fi chip the controller still runs (USB logs, safety
  // rules, the USB protocol port), it just takes no network commands.
  g_running.network = wifi_chip_up();

  // wifi.*, net.*, time.* as loaded at boot (they all need a restart).
  Wifi::Config wifi_config =
      Wifi::config_from(settings, ROTORD_WIFI_CONNECT_TIMEOUT_S * Millis{1000});
  // Announced by mDNS, as rotord on Linux announces them through Avahi; the
  // TCP ports are the registry's (every line protocol is served below).
  const auto tcp_port = [](Personality personality) {
    return protocol::protocol_info(personality).tcp_port;
  };
  wifi_config.ports = protocol::announced_ports(kHttpPort, tcp_port);
  static Wifi wifi(wifi_config);
  // WRC MONITOR lines also go to the USB log port as they happen, where the
  // WRC firmware prints them, but only while a terminal listens (log_port.hpp).
  static protocol::MonitorTap monitor_tap(d.log);
  static const protocol::SessionDeps deps{controller, ROTORD_VERSION, &monitor_tap};
  // Every server admits by net/admission.hpp with the live settings (idle
  // eviction, per-address cap, allow-list), as on Linux; a newcomer to a
  // full line port gets the shared STOP-only exchange when it is free.
  static SharedStopOnlySlot shared_stop_only;
  auto line_config = [&settings, &registry](Personality personality) {
    const protocol::ProtocolInfo& info = protocol::protocol_info(personality);
    lwip_port::ServerConfig config;
    config.name = info.name.data();  // a string literal
    config.port = info.tcp_port;
    config.max_clients = static_cast<std::size_t>(settings.i(settings::Id::kNetMaxClients));
    config.reject_message = info.refusal;
    config.settings = &settings;
    config.shared_stop_only = &shared_stop_only;
    config.metrics = &registry;
    config.protocol = info.metric();
    return config;
  };
  // Each row's service (a static of its own), in the order of the rows.
  static std::array<lwip_port::TcpServer*, line_servers() + 1> servers{};
  [&]<std::size_t... I>(std::index_sequence<I...>) {
    std::size_t n = 0;
    ((servers[n] = serve_line<static_cast<Personality>(I)>(deps, line_config),
      n += servers[n] != nullptr ? 1 : 0),
     ...);
  }
  (std::make_index_sequence<protocol::kPersonalityCount>{});
  static SntpWallClock wall_clock(&now_ms);  // time_utc once SNTP has answered
  // Access control's crypto: seeded once here (its only heap allocation).
  static PicoCrypto crypto;
  if (!crypto.begin()) std::printf("rotord: mbedtls could not seed: web logins refused\n");
  web::ApiContext api_context{controller,     d.storage,   d.defaults, d.system,
                              ROTORD_VERSION, &wall_clock, nullptr,    &registry};
  api_context.crypto = crypto.ready() ? &crypto : nullptr;
  api_context.pbkdf2_iterations = kPbkdf2Iterations;
  api_context.pbkdf2_slice = kPbkdf2SliceIterations;
  api_context.log = &d.log;
  api_context.load_report = d.load_report;
  api_context.platform = settings::Platform::kPicoW;
  static SntpState sntp_state(&now_ms, settings.b(settings::Id::kTimeSntpEnabled),
                              settings.text(settings::Id::kTimeSntpServer));
  api_context.clock_sync = &sntp_state;
  // Tracking: UTC from SNTP (refused until it has answered), one target
  // evaluation (about 3 ms) per tick for the pass search and the plan, and
  // GET /api/passes a slice per loop. The TLEs in their flash slots; a PUT
  // while the rotator moves is refused (a flash write pauses this loop).
  controller.attach_utc_clock(&wall_clock);
  controller.set_track_budget(1);
  // A client's go-to stream is compared with the stored TLEs, the Sun and
  // the Moon (track.recognise): three candidates per go-to at most (about
  // 10-30 ms), so the loop never stalls for the whole catalogue at once.
  controller.attach_catalog(&g_tles);
  controller.set_recognise_budget(3);
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
  // A newcomer to a full web port may still POST /api/stop, in the line
  // ports' shared stop-only slot: a full HttpSession (~10 KB) would not fit
  // there, this small one does (no RAM of its own).
  auto make_http_stop_only = [] { return web::HttpStopOnlySession(api); };
  static_assert(sizeof(web::HttpStopOnlySession) <= sizeof(SharedStopOnlySlot::Storage) &&
                    alignof(web::HttpStopOnlySession) <= SharedStopOnlySlot::kAlign,
                "the web's stop-only session must fit the line ports' shared slot");
  lwip_port::ServerConfig http_config;
  http_config.name = "web UI and REST API";
  http_config.port = kHttpPort;
  http_config.max_clients = kHttpSlots;
  http_config.reject_message = web::HttpSession::kTooManyConnections;
  http_config.is_immutable = &in_program_flash;
  http_config.settings = &settings;
  http_config.max_event_streams = std::min(
      kHttpEventStreams, static_cast<std::size_t>(settings.i(settings::Id::kWebMaxEventStreams)));
  http_config.shared_stop_only = &shared_stop_only;
  http_config.metrics = &registry;
  http_config.protocol = metrics::Protocol::kHttp;
  static lwip_port::StaticService<web::HttpSession, kHttpSlots, decltype(make_http), 0,
                                  decltype(make_http_stop_only)>
      http(http_config, make_http, make_http_stop_only);
  servers.back() = &http.server();
  // The station's MQTT broker (docs/mqtt.md): state, commands and Home
  // Assistant discovery through the same mqtt::Bridge as Linux, on lwIP's
  // MQTT client; 9,888 bytes of static RAM (lwip_mqtt.hpp), whether or not
  // mqtt.enabled is on. The prefix defaults to rotord/<net.hostname>.
  static_assert(sizeof(lwip_port::LwipMqtt) <= 9888,
                "the Pico W's MQTT RAM grew: update docs/mqtt.md and the READMEs, then this");
  static char web_url[48];
  const std::string_view host_name = settings.text(settings::Id::kNetHostname);
  std::snprintf(web_url, sizeof web_url, "http://%.*s.local/", static_cast<int>(host_name.size()),
                host_name.data());
  static lwip_port::LwipMqtt mqtt(api, settings, host_name.empty() ? "rotord" : host_name, web_url,
                                  ROTORD_VERSION);
  g_running.wifi = &wifi;
  g_running.api = &api;
  g_running.servers = servers;
  // The UDP rotor messages (docs/protocols/udp.md), each when enabled:
  // one lwIP UDP pcb apiece (config/lwipopts.h counts them).
  static protocol::DatagramHandlers datagram_handlers(controller);
  const auto udp_name = [](protocol::DatagramPersonality p) {
    return protocol::datagram_protocols()[static_cast<std::size_t>(p)].name.data();  // literals
  };
  using protocol::DatagramPersonality;
  static lwip_port::UdpService n1mm(udp_name(DatagramPersonality::kN1mm),
                                    datagram_handlers.get(DatagramPersonality::kN1mm),
                                    DatagramPersonality::kN1mm, &registry);
  static lwip_port::UdpService pst(udp_name(DatagramPersonality::kPst),
                                   datagram_handlers.get(DatagramPersonality::kPst),
                                   DatagramPersonality::kPst, &registry);
  static_assert(protocol::kDatagramPersonalityCount == 2, "serve every UDP protocol");
  static lwip_port::UdpService* const udp_services[] = {&n1mm, &pst};
  g_running.udp_services = udp_services;
  g_running.mqtt = &mqtt;
  if (g_running.network) {
    wifi.begin(now);
    // lwIP listens on every address, so the servers work on the station and
    // on the setup access point alike.
    for (lwip_port::TcpServer* server : servers) {
      if (server->start())
        std::printf("rotord: %s on port %u\n", server->name(), server->port());
      else
        std::printf("rotord: %s: cannot listen\n", server->name());
    }
    for (const protocol::DatagramInfo& info : protocol::datagram_protocols()) {
      if (!settings.b(info.enabled)) continue;
      lwip_port::UdpService& service = *udp_services[static_cast<std::size_t>(info.personality)];
      const auto port = static_cast<std::uint16_t>(settings.i(info.port));
      if (service.start(port))
        std::printf("rotord: %s on UDP port %u\n", service.name(), service.port());
      else
        std::printf("rotord: %s: cannot listen on UDP port %u\n", service.name(),
                    static_cast<unsigned>(port));
    }
  }
}

void network_service() {
  if (g_running.network) cyw43_arch_poll();
}

void network_tick(Millis now) {
  g_running.api->poll(now);  // hold-to-move's dead-man, with or without a connection
  if (!g_running.network) return;
  for (lwip_port::TcpServer* server : g_running.servers) server->poll(now);
  for (lwip_port::UdpService* service : g_running.udp_services) service->poll();
  g_running.wifi->step(now);
  g_running.mqtt->poll(now, g_running.wifi->state() == Wifi::State::kStation);
}

void network_wait_until(absolute_time_t next_tick) {
  // A login or a new password being hashed: its slices fill the time up to
  // the next tick instead of sleeping (the tick is never late by more than
  // one slice, and the watchdog is fed on every pass).
  while (g_running.api->auth_busy() &&
         absolute_time_diff_us(get_absolute_time(), next_tick) > kSliceHeadroomUs)
    g_running.api->work();
  if (g_running.network)
    cyw43_arch_wait_for_work_until(next_tick);
  else
    sleep_until(next_tick);
}

}  // namespace rotord::pico_w
