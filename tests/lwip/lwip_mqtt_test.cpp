// The Pico W's MQTT glue (ports/pico_w/lwip_mqtt.cpp) with lwIP's own MQTT
// client (apps/mqtt/mqtt.c, from Debian's lwIP 2.1.3 source, fetched by
// scripts/install-deps.sh) on Debian's liblwip, talking to a real Mosquitto.
//
// lwIP gets a tap interface (/dev/net/tun, so root or CAP_NET_ADMIN) with a
// small Ethernet driver of this file's; its host side carries an address in
// 198.18.0.0/15 (the benchmarking range, never routed), on which a Mosquitto
// listens: the glue's bytes cross lwIP's TCP and IP, an Ethernet frame, the
// kernel's stack and reach a real broker; what the Pico would publish is read
// back with mosquitto_sub, and commands are sent with mosquitto_rr. Where no
// tap can be made (no /dev/net/tun, not root) the tests skip and say why.
//
// A loop thread stands for the Pico's main loop: every pass, with lwIP's core
// lock held (the one context the Pico's poll loop gives), it ticks the
// controller 10 ms and polls the API and the glue on that same 10 ms clock.
// Waits are bounded for liveness only; nothing asserts durations.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <linux/if.h>
#include <linux/if_tun.h>
#include <signal.h>
#include <sys/ioctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <functional>
#include <memory>
#include <string>
#include <thread>

#include "fake_rotator.hpp"
#include "lwip_harness.hpp"
#include "lwip_mqtt.hpp"
#include "mosquitto_broker.hpp"
#include "shell.hpp"
#include "web/web_api.hpp"

extern "C" {
#include "lwip/etharp.h"
#include "lwip/ip4_addr.h"
#include "lwip/netif.h"
#include "lwip/pbuf.h"
#include "lwip/tcpip.h"
}

static_assert(NO_SYS == 0 && LWIP_TCPIP_CORE_LOCKING == 1, "not Debian's lwipopts.h");

namespace rotord {
namespace {

using settings::Id;
using testing::CommandOutput;
using testing::CoreLock;
using testing::ensure_lwip;
using testing::run_command;

/// lwIP's tap interface and its host side, made once per process: a /30 of
/// 198.18.0.0/15, the host (and the broker) on .1, lwIP on .2. The driver
/// is this file's (a frame per read and write on /dev/net/tun): Debian's
/// tapif_init writes past its receive pbufs under full-size frames (valgrind).
struct TapNet {
  std::string name;
  std::string host_ip, lwip_ip;
  std::string why_not;  ///< not empty: no tap here, and why
  int fd = -1;
  netif nif{};

  static err_t link_output(netif* n, pbuf* p) {
    auto* self = static_cast<TapNet*>(n->state);
    char frame[1600];
    const u16_t len = pbuf_copy_partial(p, frame, sizeof frame, 0);
    return ::write(self->fd, frame, len) == static_cast<ssize_t>(len) ? ERR_OK : ERR_IF;
  }
  static err_t init(netif* n) {
    n->name[0] = 't';
    n->name[1] = 'p';
    n->output = etharp_output;
    n->linkoutput = &TapNet::link_output;
    n->mtu = 1500;
    n->hwaddr_len = 6;
    const u8_t mac[6] = {0x02, 0x52, 0x54, 0x44, 0x00, 0x02};  // locally administered
    std::memcpy(n->hwaddr, mac, sizeof mac);
    n->flags = NETIF_FLAG_BROADCAST | NETIF_FLAG_ETHARP | NETIF_FLAG_ETHERNET;
    return ERR_OK;
  }
  /// The host's frames into lwIP (its tcpip thread takes them from here).
  void read_frames() {
    char frame[1600];
    for (;;) {
      const ssize_t n = ::read(fd, frame, sizeof frame);
      if (n <= 0) {
        if (n < 0 && errno == EINTR) continue;
        return;
      }
      pbuf* p = pbuf_alloc(PBUF_RAW, static_cast<u16_t>(n), PBUF_RAM);
      if (p == nullptr) continue;
      pbuf_take(p, frame, static_cast<u16_t>(n));
      if (nif.input(p, &nif) != ERR_OK) pbuf_free(p);
    }
  }

  /// 198.18.0.0/15 as /30 networks: the n-th one's two addresses.
  static std::string address(std::uint32_t n, std::uint32_t host) {
    const std::uint32_t a = (198u << 24) | (18u << 16) | ((n % 32768u) * 4u + host);
    return std::to_string(a >> 24) + "." + std::to_string((a >> 16) & 255) + "." +
           std::to_string((a >> 8) & 255) + "." + std::to_string(a & 255);
  }

  TapNet() {
    name = "rtdmq" + std::to_string(::getpid() % 100000);
    // A network of its own per test process (ctest runs them in parallel):
    // from the process id, the next free one if another process has it.
    std::uint32_t n = static_cast<std::uint32_t>(::getpid());
    while (!run_command("ip -4 addr show to " + address(n, 0) + "/30").out.empty()) ++n;
    host_ip = address(n, 1);
    lwip_ip = address(n, 2);
    for (const char* tool : {"ip", "mosquitto", "mosquitto_sub", "mosquitto_rr"}) {
      if (run_command(std::string("command -v ") + tool + " >/dev/null").rc != 0) {
        why_not = std::string(tool) + " is not installed (scripts/install-deps.sh)";
        return;
      }
    }
    fd = ::open("/dev/net/tun", O_RDWR);
    if (fd < 0) {
      why_not = std::string("cannot open /dev/net/tun: ") + std::strerror(errno);
      return;
    }
    ifreq ifr{};
    std::strncpy(ifr.ifr_name, name.c_str(), IFNAMSIZ - 1);
    ifr.ifr_flags = IFF_TAP | IFF_NO_PI;
    if (::ioctl(fd, TUNSETIFF, &ifr) != 0) {
      why_not = std::string("cannot make a tap interface (needs root or CAP_NET_ADMIN): ") +
                std::strerror(errno);
      return;
    }
    // The interface lives as long as this process holds fd.
    const CommandOutput up = run_command("ip addr add " + host_ip + "/30 dev " + name +
                                         " && ip link set " + name + " up 2>&1");
    if (up.rc != 0) {
      why_not = "cannot give the tap an address: " + up.out;
      return;
    }
    ensure_lwip();
    {
      CoreLock lock;
      ip4_addr_t ip, mask, gw;
      ip4addr_aton(lwip_ip.c_str(), &ip);
      ip4addr_aton("255.255.255.252", &mask);
      ip4addr_aton(host_ip.c_str(), &gw);
      netif_add(&nif, &ip, &mask, &gw, this, &TapNet::init, tcpip_input);
      netif_set_up(&nif);
      netif_set_link_up(&nif);
    }
    std::thread([this] { read_frames(); }).detach();  // until the process exits
  }
};

TapNet& tap() {
  // lwIP cannot be de-initialised, nor its netif removed under a running
  // reader: one per process, never destroyed.
  static TapNet* net = new TapNet;
  return *net;
}

/// A Mosquitto on the tap's host side.
class Broker : public testing::MosquittoBroker {
 public:
  explicit Broker(const std::string& dir)
      : MosquittoBroker(dir, tap().host_ip, 1883, "allow_anonymous true\n", "-h " + tap().host_ip) {
  }
};

class LwipMqttTest : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!tap().why_not.empty()) GTEST_SKIP() << "SKIPPED: no tap interface: " << tap().why_not;
    dir = testing::make_temp_dir("rotord-lwip-mqtt");
    broker = std::make_unique<Broker>(dir);
  }
  void TearDown() override {
    stop_loop();
    if (mqtt) {
      CoreLock lock;
      mqtt->abort_connection();
    }
    broker.reset();
    if (HasFailure()) std::printf("%s", run_command("cat " + dir + "/mosquitto.log").out.c_str());
    if (!dir.empty()) run_command("rm -rf " + dir);
  }

  /// The glue as the Pico builds it (network_services.cpp), on `r`'s controller.
  void start(bool control, const std::string& extra_host = "") {
    r.settings.set(Id::kMqttEnabled, 1);
    r.settings.set_text(Id::kMqttHost, extra_host.empty() ? tap().host_ip : extra_host);
    r.settings.set_text(Id::kMqttPrefix, "rotord/pico");
    r.settings.set_text(Id::kMqttClientId, "rotord-pico");
    r.settings.set(Id::kMqttControl, control ? 1 : 0);
    {
      CoreLock lock;
      mqtt = std::make_unique<lwip_port::LwipMqtt>(api, r.controller->settings(), "pico",
                                                   "http://pico.local/", "9.9.9");
    }
    ASSERT_TRUE(mqtt->enabled());
    loop = std::thread([this] {
      while (!stopping) {
        {
          CoreLock lock;
          r.run_ms(10);
          now += 10;
          api.poll(now);
          mqtt->poll(now, true);
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(1));  // the Pico's idle time
      }
    });
  }
  void stop_loop() {
    stopping = true;
    if (loop.joinable()) loop.join();
  }
  /// Waits (bounded, liveness only) until `done` holds, checked under the lock.
  bool wait_for(const std::function<bool()>& done, int steps = 4000) {
    for (int i = 0; i < steps; ++i) {
      {
        CoreLock lock;
        if (done()) return true;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    return false;
  }
  bool wait_connected() {
    return wait_for([this] { return mqtt->connected() && mqtt->bridge().states_published() > 0; });
  }
  std::string h() const { return " -h " + tap().host_ip; }
  std::string retained(const std::string& topic) {
    return run_command("mosquitto_sub" + h() + " -t '" + topic + "' -C 1 -W 10 2>&1").out;
  }
  std::string command(const std::string& name, const std::string& body) {
    return run_command("mosquitto_rr" + h() + " -t rotord/pico/cmd/" + name +
                       " -e rotord/pico/result -W 10 -m '" + body + "' 2>&1")
        .out;
  }

  testing::FakeRotator r;
  web::Api api{web::ApiContext{*r.controller, nullptr, nullptr, nullptr, "9.9.9"}};
  std::unique_ptr<lwip_port::LwipMqtt> mqtt;
  std::string dir;
  std::unique_ptr<Broker> broker;
  std::thread loop;
  std::atomic<bool> stopping{false};
  Millis now = 1000;
};

TEST_F(LwipMqttTest, RetainedStateAvailabilityAndDiscoveryReachTheBroker) {
  start(false);
  ASSERT_TRUE(wait_connected());
  EXPECT_EQ(retained("rotord/pico/availability"), "online\n");
  const std::string state = retained("rotord/pico/state");
  EXPECT_NE(state.find(R"("mode":"idle")"), std::string::npos) << state;
  EXPECT_NE(retained("rotord/pico/info").find(R"("web":"http://pico.local/")"), std::string::npos);
  // Home Assistant's discovery, against the schema the Linux test uses.
  const std::string file = dir + "/discovery.txt";
  // 7 entities, and 16 sensors of the wear odometer and the slips (az/el).
  ASSERT_EQ(
      run_command("mosquitto_sub" + h() + " -t 'homeassistant/#' -v -C 23 -W 10 > " + file).rc, 0);
  const CommandOutput check = run_command("python3 " ROTORD_SOURCE_DIR
                                          "/tests/interop/ha_discovery_check.py " ROTORD_SOURCE_DIR
                                          "/tests/data/mqtt/ha_discovery.schema.json " +
                                          file + " rotord/pico");
  EXPECT_NE(check.out.find("23 messages, 23 entities, 0 problems"), std::string::npos) << check.out;
}

TEST_F(LwipMqttTest, CommandsAndTheirErrorsAreTheRestApis) {
  start(true);
  ASSERT_TRUE(wait_connected());
  EXPECT_EQ(command("goto", R"({"az": 200})"),
            R"({"cmd":"goto","status":200,"response":{"ok":true,"az_target":200,"el_target":null}})"
            "\n");
  EXPECT_TRUE(wait_for([this] { return r.controller->status().moving(); }));
  EXPECT_EQ(command("goto", R"({"az": "north"})"),
            R"({"cmd":"goto","status":400,"response":{"error":"az must be a number"}})"
            "\n");
  EXPECT_NE(command("speed", R"({"speed_pct": 400})").find(R"("status":422)"), std::string::npos);
  EXPECT_NE(command("fly", "{}").find(R"("cmd":"fly","status":404)"), std::string::npos);
  // Bodies over 512 bytes arrive in pieces (lwIP's 160-byte header buffer):
  // answered 413 unread, and the connection lives on.
  EXPECT_NE(command("goto", std::string(600, ' ')).find(R"("status":413)"), std::string::npos);
  EXPECT_NE(command("park", std::string(5000, ' ')).find(R"("status":413)"), std::string::npos);
  // A body just under the limit, split across pieces, is read whole.
  const std::string padded = R"({"speed_pct": 40})" + std::string(490, ' ');
  const std::string padded_result = command("speed", padded);
  EXPECT_NE(padded_result.find(R"("status":200)"), std::string::npos) << padded_result;
  // An empty stop (mosquitto_rr -n): obeyed.
  EXPECT_EQ(run_command("mosquitto_rr" + h() +
                        " -t rotord/pico/cmd/stop -e rotord/pico/result -W 10 -n 2>&1")
                .out,
            R"({"cmd":"stop","status":200,"response":{"ok":true}})"
            "\n");
  EXPECT_TRUE(wait_for([this] { return r.controller->status().mode == Mode::kIdle; }));
  EXPECT_TRUE(mqtt->connected());
}

TEST_F(LwipMqttTest, WithoutMqttControlOnlyStopIsObeyed) {
  start(false);
  ASSERT_TRUE(wait_connected());
  EXPECT_NE(command("goto", R"({"az": 200})").find(R"("status":403)"), std::string::npos);
  EXPECT_EQ(command("stop", "{}"), R"({"cmd":"stop","status":200,"response":{"ok":true}})"
                                   "\n");
}

TEST_F(LwipMqttTest, TheAllowListAppliesToTheBrokersAddress) {
  // The broker's address is not on the list: its commands are read-only.
  r.settings.set_text(Id::kAccessControlNetworks, "192.0.2.0/24");
  start(true);
  ASSERT_TRUE(wait_connected());
  EXPECT_NE(command("goto", R"({"az": 200})").find(R"("cmd":"goto","status":403)"),
            std::string::npos);
  EXPECT_EQ(command("stop", ""), R"({"cmd":"stop","status":200,"response":{"ok":true}})"
                                 "\n");
  // Now it is (the list is read at each command).
  {
    CoreLock lock;
    r.controller->settings().set_text(Id::kAccessControlNetworks, tap().host_ip + "/32");
  }
  EXPECT_NE(command("goto", R"({"az": 200})").find(R"("status":200)"), std::string::npos);
}

TEST_F(LwipMqttTest, TheWillSaysOfflineWhenTheConnectionDies) {
  start(false);
  ASSERT_TRUE(wait_connected());
  EXPECT_EQ(retained("rotord/pico/availability"), "online\n");
  stop_loop();  // the Pico stops (power cut): no more polls, the TCP reset
  {
    CoreLock lock;
    mqtt->abort_connection();
  }
  EXPECT_EQ(retained("rotord/pico/availability"), "offline\n");
}

TEST_F(LwipMqttTest, ReconnectsAfterTheBrokerRestartsAndPublishesItAllAgain) {
  start(false);
  ASSERT_TRUE(wait_connected());
  broker->stop();  // everything retained is gone with it
  ASSERT_TRUE(wait_for([this] { return !mqtt->connected(); }));
  broker->start();
  // Backoff 1, 2, 4 s ... of the loop's clock.
  ASSERT_TRUE(wait_for([this] { return mqtt->connected() && mqtt->counters().connects >= 2; }));
  EXPECT_EQ(retained("rotord/pico/availability"), "online\n");
  EXPECT_NE(retained("rotord/pico/state").find(R"("mode":"idle")"), std::string::npos);
  EXPECT_NE(retained("homeassistant/button/rotord-pico/stop/config").find("cmd/stop"),
            std::string::npos);
}

TEST_F(LwipMqttTest, ABrokerThatIsNotThereIsRetriedQuietly) {
  broker->stop();
  start(false);
  ASSERT_TRUE(wait_for([this] { return mqtt->counters().failed_connects >= 3; }));
  {
    CoreLock lock;
    EXPECT_FALSE(mqtt->connected());
  }
  broker->start();
  EXPECT_TRUE(wait_connected());
}

TEST_F(LwipMqttTest, AFloodIsBoundedAndAStopStillGetsThrough) {
  start(true);
  ASSERT_TRUE(wait_connected());
  const std::string gotos = dir + "/gotos.txt";
  ASSERT_EQ(run_command("seq 3000 | sed 's/.*/{\"az\": 100}/' > " + gotos +
                        " && for i in $(seq 100); do printf '%0700d\\n' $i; done >> " + gotos)
                .rc,
            0);
  // Every result is recorded (the subscriber is ready once it saw a probe).
  const std::string results = dir + "/results.txt";
  const pid_t sub = static_cast<pid_t>(
      std::stol(run_command("(mosquitto_sub" + h() + " -t rotord/pico/result -W 60 > " + results +
                            " 2>&1 & echo $!)")
                    .out));
  ASSERT_EQ(run_command("for i in $(seq 100); do mosquitto_pub" + h() +
                        " -t rotord/pico/result -m probe; grep -q probe " + results +
                        " && exit 0; sleep 0.05; done; exit 1")
                .rc,
            0);
  ASSERT_EQ(run_command("mosquitto_pub" + h() + " -t rotord/pico/cmd/goto -l < " + gotos).rc, 0);
  // The stop comes after the flood and is answered.
  ASSERT_EQ(run_command("mosquitto_pub" + h() + " -t rotord/pico/cmd/stop -n").rc, 0);
  const bool stopped = run_command("for i in $(seq 200); do grep -q '\"cmd\":\"stop\"' " + results +
                                   " && exit 0; sleep 0.05; done; exit 1")
                           .rc == 0;
  ::kill(sub, SIGTERM);
  EXPECT_TRUE(stopped) << run_command("tail -5 " + results).out;
  EXPECT_TRUE(wait_for([this] { return r.controller->status().mode == Mode::kIdle; }));
  // Results are bounded by what was handled; each the REST API's answer.
  std::ifstream in(results);
  std::string line;
  std::size_t count = 0;
  while (std::getline(in, line)) {
    if (line == "probe") continue;
    ++count;
    EXPECT_EQ(line.rfind(R"({"cmd":")", 0), 0u) << line;
    EXPECT_LE(line.size(), mqtt::Bridge::kMaxDiscoveryBytes);
  }
  CoreLock lock;
  EXPECT_TRUE(mqtt->connected());
  EXPECT_EQ(mqtt->counters().connects, 1u);  // never dropped by the flood
  EXPECT_GT(mqtt->counters().commands, 0u);
  EXPECT_LE(count, mqtt->counters().commands);
  RecordProperty("handled", static_cast<int>(mqtt->counters().commands));
  RecordProperty("dropped", static_cast<int>(mqtt->counters().dropped_commands));
}

TEST(LwipMqttBudget, TheGlueFitsItsStatedRam) {
  // docs/mqtt.md, docs/pico_w.md and ports/pico_w/README.md give this number:
  // keep them in step.
  EXPECT_LE(sizeof(lwip_port::LwipMqtt), 10u * 1024u) << sizeof(lwip_port::LwipMqtt);
  RecordProperty("bytes", static_cast<int>(sizeof(lwip_port::LwipMqtt)));
}

}  // namespace
}  // namespace rotord
