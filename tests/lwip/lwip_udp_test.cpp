// The Pico W's UDP glue (ports/pico_w/lwip_udp.cpp) against Debian's lwIP:
// N1MM+'s and PstRotator's datagrams sent from a raw-API UDP pcb over a netif
// that loops its own address back, into the core's protocols on a fake
// rotator: the go-to, STOP, the AZ? answer at port + 1 and the N1MM+ heading
// report at the report port, a read-only sender refused, garbage and an
// oversize datagram ignored. Waits are bounded by a step count, not a clock.
#include <gtest/gtest.h>

#include <chrono>
#include <string>
#include <thread>
#include <vector>

#include "fake_rotator.hpp"
#include "lwip_udp.hpp"
// Debian's lwipopts.h declares the core-lock functions outside lwIP's own
// extern "C" blocks; without this they would get C++ linkage.
extern "C" {
#include "lwip/init.h"
#include "lwip/ip_addr.h"
#include "lwip/netif.h"
#include "lwip/tcpip.h"
#include "lwip/udp.h"
}
#include "lwip_harness.hpp"
#include "protocol/datagram_registry.hpp"

static_assert(NO_SYS == 0 && LWIP_TCPIP_CORE_LOCKING == 1, "not Debian's lwipopts.h");

namespace rotord {
namespace {

using protocol::DatagramOutcome;
using settings::Id;
using testing::CoreLock;

constexpr Millis N1mmRotorPeriod() {
  return protocol::N1mmRotor::kReportPeriodMs;
}

/// A raw-API UDP pcb on the netif's address and what it received.
struct Listener {
  udp_pcb* pcb = nullptr;
  std::vector<std::string> received;

  bool open(std::uint16_t port) {
    pcb = udp_new();
    if (pcb == nullptr || udp_bind(pcb, IP_ANY_TYPE, port) != ERR_OK) return false;
    udp_recv(
        pcb,
        [](void* arg, udp_pcb*, pbuf* p, const ip_addr_t*, u16_t) {
          if (p == nullptr) return;
          std::string text(p->tot_len, '\0');
          pbuf_copy_partial(p, text.data(), p->tot_len, 0);
          pbuf_free(p);
          static_cast<Listener*>(arg)->received.push_back(std::move(text));
        },
        this);
    return true;
  }
  void close() {
    if (pcb != nullptr) udp_remove(pcb);
    pcb = nullptr;
  }
  std::uint16_t port() const { return pcb->local_port; }
};

class LwipUdpTest : public ::testing::Test {
 protected:
  static constexpr int kMaxSteps = 10000;  // x 1 ms sleep: generous, never reached when passing

  void SetUp() override {
    testing::ensure_lwip();
    rotator.run_ms(50);
    CoreLock lock;
    IP4_ADDR(ip_2_ip4(&addr_), 10, 0, 0, 1);
    IP_SET_TYPE_VAL(addr_, IPADDR_TYPE_V4);
    ASSERT_TRUE(testing::add_host_netif(netif_, *ip_2_ip4(&addr_), &init_netif));
    // The defaults: lwIP's own ports here, nothing the host uses.
    ASSERT_TRUE(pst.start(12000));
    ASSERT_TRUE(n1mm.start(12040));
    ASSERT_TRUE(sender.open(0));
    ASSERT_TRUE(reports.open(0));
    // PstRotator's answers go to port + 1 of its port; N1MM+'s reports to
    // n1mm.report_port.
    ASSERT_TRUE(answers.open(static_cast<std::uint16_t>(pst.port() + 1)));
    rotator.settings.set(Id::kPstPort, pst.port());
    rotator.settings.set(Id::kN1mmReportPort, reports.port());
  }
  void TearDown() override {
    CoreLock lock;
    pst.stop();
    n1mm.stop();
    sender.close();
    reports.close();
    answers.close();
    netif_remove(&netif_);
  }

  static err_t init_netif(netif* n) {
    n->name[0] = 'u';
    n->name[1] = 'd';
    n->mtu = 1500;
    n->output = [](netif*, pbuf*, const ip4_addr_t*) -> err_t { return ERR_OK; };
    return ERR_OK;
  }

  void send(const lwip_port::UdpService& to, const std::string& datagram) {
    CoreLock lock;
    pbuf* p = pbuf_alloc(PBUF_TRANSPORT, static_cast<u16_t>(datagram.size()), PBUF_RAM);
    ASSERT_NE(p, nullptr);
    pbuf_take(p, datagram.data(), static_cast<u16_t>(datagram.size()));
    EXPECT_EQ(udp_sendto(sender.pcb, p, &addr_, to.port()), ERR_OK);
    pbuf_free(p);
  }
  /// Sends and waits (bounded) until the service has handled it.
  DatagramOutcome handled(const lwip_port::UdpService& to, const std::string& datagram) {
    std::uint32_t before = 0;
    {
      CoreLock lock;
      before = to.datagrams();
    }
    send(to, datagram);
    EXPECT_TRUE(wait([&] { return to.datagrams() > before; }));
    CoreLock lock;
    return to.last_outcome();
  }
  template <typename Pred>
  bool wait(Pred pred) {
    for (int i = 0; i < kMaxSteps; ++i) {
      {
        CoreLock lock;
        if (pred()) return true;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    return false;
  }
  /// The next datagram `at` receives.
  std::string next(Listener& at) {
    EXPECT_TRUE(wait([&] { return !at.received.empty(); }));
    CoreLock lock;
    if (at.received.empty()) return "";
    std::string first = at.received.front();
    at.received.erase(at.received.begin());
    return first;
  }
  bool has_target() {
    CoreLock lock;
    return rotator.controller->status().az.has_target;
  }
  float az_target() {
    CoreLock lock;
    return rotator.controller->status().az.target_deg;
  }

  testing::FakeRotator rotator;
  protocol::DatagramHandlers handlers{*rotator.controller};
  metrics::Registry registry;
  lwip_port::UdpService pst{"PstRotator UDP", handlers.get(protocol::DatagramPersonality::kPst),
                            protocol::DatagramPersonality::kPst, &registry};
  lwip_port::UdpService n1mm{"N1MM+ rotor", handlers.get(protocol::DatagramPersonality::kN1mm),
                             protocol::DatagramPersonality::kN1mm, &registry};
  Listener sender, reports, answers;
  netif netif_{};
  ip_addr_t addr_{};
};

TEST_F(LwipUdpTest, PstRotatorGoToStopAndTheAnswerAtPortPlusOne) {
  EXPECT_EQ(handled(pst, "<PST><AZIMUTH>200</AZIMUTH></PST>"), DatagramOutcome::kDone);
  EXPECT_NEAR(az_target(), 200.0f, 0.01f);
  EXPECT_EQ(handled(pst, "<PST>AZ?</PST>"), DatagramOutcome::kDone);
  EXPECT_EQ(next(answers), "AZ:100\r");
  EXPECT_EQ(handled(pst, "<PST><STOP>1</STOP></PST>"), DatagramOutcome::kDone);
  EXPECT_FALSE(has_target());
}

TEST_F(LwipUdpTest, N1mmGoToWithItsHeadingReport) {
  {
    CoreLock lock;
    rotator.settings.set_text(Id::kN1mmRotorName, "Yagi 20");
  }
  EXPECT_EQ(handled(n1mm,
                    "<N1MMRotor><rotor>Yagi 20</rotor><goazi>330.0</goazi><offset>0</offset>"
                    "<bidirectional>0</bidirectional><freqband>14</freqband></N1MMRotor>"),
            DatagramOutcome::kDone);
  EXPECT_NEAR(az_target(), 330.0f, 0.01f);
  EXPECT_EQ(next(reports), "Yagi 20 @ 1000");
  // A second later, still turning: the port's poll sends the heading again.
  {
    CoreLock lock;
    rotator.run_ms(N1mmRotorPeriod());
    n1mm.poll();
  }
  EXPECT_EQ(next(reports), "Yagi 20 @ 1000");
  EXPECT_EQ(handled(n1mm, "<N1MMRotor><stop>Tribander</stop></N1MMRotor>"),
            DatagramOutcome::kNotForUs);
  EXPECT_TRUE(has_target());
}

TEST_F(LwipUdpTest, AReadOnlySenderIsRefusedButStops) {
  {
    CoreLock lock;
    rotator.settings.set_text(Id::kAccessControlNetworks, "192.168.1.0/24");  // not 10.0.0.1
  }
  EXPECT_EQ(handled(pst, "<PST><AZIMUTH>200</AZIMUTH></PST>"), DatagramOutcome::kRefused);
  EXPECT_FALSE(has_target());
  {
    CoreLock lock;
    rotator.settings.set_text(Id::kAccessControlNetworks, "10.0.0.0/24");
  }
  EXPECT_EQ(handled(pst, "<PST><AZIMUTH>200</AZIMUTH></PST>"), DatagramOutcome::kDone);
  {
    CoreLock lock;
    rotator.settings.set_text(Id::kAccessControlNetworks, "192.168.1.0/24");
  }
  EXPECT_EQ(handled(pst, "<PST><STOP>1</STOP></PST>"), DatagramOutcome::kDone);
  EXPECT_FALSE(has_target());
}

TEST_F(LwipUdpTest, GarbageAndOversizeDatagramsAreIgnored) {
  EXPECT_EQ(handled(pst, "<PST><AZIMUTH>abc</AZIMUTH></PST>"), DatagramOutcome::kMalformed);
  EXPECT_EQ(handled(pst, std::string("\x00\xff<PST>", 7)), DatagramOutcome::kMalformed);
  EXPECT_EQ(
      handled(n1mm, "<N1MMRotor><goazi>100</goazi>" + std::string(1000, ' ') + "</N1MMRotor>"),
      DatagramOutcome::kOversize);
  EXPECT_FALSE(has_target());
  CoreLock lock;
  EXPECT_TRUE(answers.received.empty());
  EXPECT_TRUE(reports.received.empty());
  // Counted for GET /metrics.
  EXPECT_EQ(registry.datagrams(protocol::DatagramPersonality::kPst, DatagramOutcome::kMalformed),
            2u);
  EXPECT_EQ(registry.datagrams(protocol::DatagramPersonality::kN1mm, DatagramOutcome::kOversize),
            1u);
}

}  // namespace
}  // namespace rotord
