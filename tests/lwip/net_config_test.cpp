// The Pico W's network settings on Debian's lwIP: a static address from the
// settings applied to a netif with ports/pico_w/net_config.cpp, then proven
// live by a UDP datagram that lwIP delivers to that address (looped back by
// the stack, LWIP_NETIF_LOOPBACK); and the SNTP hook's time base
// (ports/pico_w/sntp_clock.cpp) read back as the API's wall clock.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cstring>
#include <string>
#include <thread>

#include "net_config.hpp"
#include "sntp_clock.hpp"
extern "C" {
#include "lwip/ip_addr.h"
#include "lwip/netif.h"
#include "lwip/tcpip.h"
#include "lwip/udp.h"
}

#include "lwip_harness.hpp"

static_assert(NO_SYS == 0 && LWIP_TCPIP_CORE_LOCKING == 1, "not Debian's lwipopts.h");

namespace rotord::pico_w {
namespace {

using settings::Id;

using testing::CoreLock;
using testing::ensure_lwip;

std::string text_of(const ip4_addr_t* a) {
  char buf[IP4ADDR_STRLEN_MAX];
  return ip4addr_ntoa_r(a, buf, sizeof buf);
}

err_t init_netif(netif* n) {
  n->name[0] = 's';
  n->name[1] = 't';
  n->mtu = 1500;
  n->output = [](netif*, pbuf*, const ip4_addr_t*) -> err_t { return ERR_OK; };  // no wire
  return ERR_OK;
}

settings::Settings static_settings(const char* address, const char* gateway) {
  settings::Settings s;
  EXPECT_EQ(s.set_from_text(Id::kNetIpv4Mode, "static").error, Error::kOk);
  EXPECT_EQ(s.set_text(Id::kNetIpv4Address, address).error, Error::kOk);
  EXPECT_EQ(s.set_text(Id::kNetIpv4Netmask, "255.255.255.0").error, Error::kOk);
  EXPECT_EQ(s.set_text(Id::kNetIpv4Gateway, gateway).error, Error::kOk);
  EXPECT_EQ(s.check_consistency().error, Error::kOk);
  return s;
}

TEST(NetConfig, DhcpModeHasNoStaticAddress) {
  const settings::Settings defaults;
  EXPECT_FALSE(static_ipv4_from(defaults).has_value());
}

TEST(NetConfig, TheDnsServerDefaultsToTheGateway) {
  settings::Settings s = static_settings("192.168.7.20", "192.168.7.1");
  std::optional<StaticIpv4> c = static_ipv4_from(s);
  ASSERT_TRUE(c.has_value());
  EXPECT_EQ(c->dns, 0xC0A80701u);
  ASSERT_EQ(s.set_text(Id::kNetIpv4Dns, "9.9.9.9").error, Error::kOk);
  EXPECT_EQ(static_ipv4_from(s)->dns, 0x09090909u);
}

TEST(NetConfig, AStaticAddressIsAppliedToTheNetifAndReceivesTraffic) {
  ensure_lwip();
  static netif n;  // lwIP keeps a pointer in its netif list until removed
  {
    CoreLock lock;
    ASSERT_NE(netif_add(&n, IP4_ADDR_ANY4, IP4_ADDR_ANY4, IP4_ADDR_ANY4, nullptr, &init_netif,
                        tcpip_input),
              nullptr);
    netif_set_up(&n);
    netif_set_link_up(&n);
    const std::optional<StaticIpv4> c =
        static_ipv4_from(static_settings("10.77.0.20", "10.77.0.1"));
    ASSERT_TRUE(c.has_value());
    apply_static_ipv4(n, *c);
    EXPECT_EQ(text_of(netif_ip4_addr(&n)), "10.77.0.20");
    EXPECT_EQ(text_of(netif_ip4_netmask(&n)), "255.255.255.0");
    EXPECT_EQ(text_of(netif_ip4_gw(&n)), "10.77.0.1");
  }

  // A datagram to the new address reaches a pcb listening on it.
  static std::atomic<int> received{0};
  static std::string payload;
  udp_pcb* server = nullptr;
  udp_pcb* client = nullptr;
  {
    CoreLock lock;
    server = udp_new();
    client = udp_new();
    ASSERT_NE(server, nullptr);
    ASSERT_NE(client, nullptr);
    ip_addr_t address;
    ASSERT_TRUE(ipaddr_aton("10.77.0.20", &address));
    ASSERT_EQ(udp_bind(server, &address, 5123), ERR_OK);
    udp_recv(
        server,
        [](void*, udp_pcb*, pbuf* p, const ip_addr_t*, u16_t) {
          payload.assign(static_cast<const char*>(p->payload), p->len);
          pbuf_free(p);
          ++received;
        },
        nullptr);
    pbuf* p = pbuf_alloc(PBUF_TRANSPORT, 5, PBUF_RAM);
    ASSERT_NE(p, nullptr);
    std::memcpy(p->payload, "hello", 5);
    EXPECT_EQ(udp_sendto(client, p, &address, 5123), ERR_OK);
    pbuf_free(p);
  }
  for (int i = 0; i < 5000 && received == 0; ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  EXPECT_EQ(received, 1);
  EXPECT_EQ(payload, "hello");
  CoreLock lock;
  udp_remove(server);
  udp_remove(client);
  netif_remove(&n);
}

Millis g_now_ms = 0;
Millis fake_now() {
  return g_now_ms;
}

TEST(SntpClock, TheHookSetsTheWallClockAndItFollowsTheMonotonicTime) {
  const SntpWallClock clock(&fake_now);
  const std::uint32_t before = sntp_updates();
  g_now_ms = 12'000;
  // What lwIP's sntp.c passes to SNTP_SET_SYSTEM_TIME_US for an answer of
  // 2026-11-23T17:40:11.250000Z: seconds since 1970 and microseconds.
  on_sntp_time(1'795'455'611u, 250'000u, g_now_ms);
  EXPECT_EQ(sntp_updates(), before + 1);
  g_now_ms = 12'000 + 90'500;  // 90.5 s later on the monotonic clock
  const std::optional<std::int64_t> t = clock.unix_ms();
  ASSERT_TRUE(t.has_value());
  char text[32];
  ASSERT_GT(format_utc_iso8601(*t, text, sizeof text), 0u);
  EXPECT_STREQ(text, "2026-11-23T17:41:41.750Z");
}

std::string words(const SntpState& state) {
  char text[256];
  const std::size_t n = state.describe(text, sizeof text);
  return std::string(text, n);
}

// The set-up page's station step says how the Pico W's clock is kept.
TEST(SntpClock, ItsStateInWords) {
  EXPECT_EQ(words(SntpState(&fake_now, false, "pool.ntp.org")),
            "SNTP is off (time.sntp_enabled): the clock is not set, and tracking is refused.");
  EXPECT_EQ(words(SntpState(&fake_now, true, "")),
            "SNTP is off (time.sntp_enabled): the clock is not set, and tracking is refused.");
  const SntpState on(&fake_now, true, "pool.ntp.org");
  if (sntp_updates() == 0) {
    EXPECT_EQ(words(on),
              "Waiting for the first answer of the SNTP server pool.ntp.org (once the Wi-Fi is "
              "up): tracking waits for it.");
  }
  g_now_ms = 500'000;
  on_sntp_time(1'795'455'611u, 0u, g_now_ms);
  g_now_ms = 500'000 + 42'300;
  EXPECT_EQ(words(on), "Set by SNTP from pool.ntp.org 42 s ago (" + std::to_string(sntp_updates()) +
                           " answers).");
  // A buffer too short is cut, never overrun.
  char small[8];
  EXPECT_EQ(on.describe(small, sizeof small), 7u);
  EXPECT_STREQ(small, "Set by ");
}

}  // namespace
}  // namespace rotord::pico_w
