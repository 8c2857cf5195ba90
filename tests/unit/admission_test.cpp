// Who gets a connection slot (core/net/admission.hpp), on plain data: the rule
// both transports (Linux asio, the Pico W's lwIP) apply to every protocol port.
#include "net/admission.hpp"

#include <gtest/gtest.h>

#include <vector>

#include "settings/settings.hpp"

namespace rotord::net {
namespace {

using Kind = Admission::Decision::Kind;

/// Fixed slots, some free, as the Pico holds them.
class Slots final : public ClientList {
 public:
  std::size_t size() const override { return entries.size(); }
  const ClientInfo* at(std::size_t i) const override { return open[i] ? &entries[i] : nullptr; }
  /// Opens a client from 10.0.0.<host> at `now` in the first free slot.
  std::size_t add(std::uint8_t host, Millis now, bool stream = false) {
    ClientInfo c;
    const std::uint32_t ip = 0x0A000000u | host;
    c.peer = access::Peer::from_ipv4(ip);
    c.address = Address::from_ipv4(ip);
    c.opened_ms = c.last_receive_ms = c.last_useful_ms = now;
    c.event_stream = stream;
    for (std::size_t i = 0; i < entries.size(); ++i) {
      if (!open[i]) {
        entries[i] = c;
        open[i] = true;
        return i;
      }
    }
    entries.push_back(c);
    open.push_back(true);
    return entries.size() - 1;
  }
  std::vector<ClientInfo> entries;
  std::vector<bool> open;
};

ClientInfo newcomer(std::uint8_t host) {
  ClientInfo c;
  const std::uint32_t ip = 0x0A000000u | host;
  c.peer = access::Peer::from_ipv4(ip);
  c.address = Address::from_ipv4(ip);
  return c;
}

class AdmissionTest : public ::testing::Test {
 protected:
  settings::Settings settings;  // defaults: evict after 60 s, 6 per address
  Slots clients;
};

TEST_F(AdmissionTest, TheDefaultsAreSixtySecondsAndSixPerAddress) {
  Admission gate({8, SIZE_MAX, 0}, &settings);
  EXPECT_EQ(gate.idle_evict_ms(), 60000);
  EXPECT_EQ(gate.per_address_cap(), 6u);
}

TEST_F(AdmissionTest, AFullPortOfBusyClientsRefusesTheNewcomerAsBefore) {
  Admission gate({8, SIZE_MAX, 0}, &settings);
  for (std::uint8_t h = 1; h <= 8; ++h) clients.add(h, 0);
  const auto d = gate.admit(clients, newcomer(9), 59999);
  EXPECT_EQ(d.kind, Kind::kRefuseFull);
  EXPECT_EQ(gate.counters().refused_full, 1u);
  EXPECT_EQ(gate.counters().accepted, 0u);
}

TEST_F(AdmissionTest, AFullPortDropsTheClientIdleLongestOnceItIsIdleLongEnough) {
  Admission gate({8, SIZE_MAX, 0}, &settings);
  for (std::uint8_t h = 1; h <= 8; ++h) clients.add(h, 0);
  for (std::size_t i = 0; i < 8; ++i) clients.entries[i].last_useful_ms = 1000 + Millis(i);
  clients.entries[5].last_useful_ms = 500;  // idle longest, and past the 60 s
  EXPECT_EQ(gate.admit(clients, newcomer(9), 60499).kind, Kind::kRefuseFull);
  const auto d = gate.admit(clients, newcomer(9), 60500);
  EXPECT_EQ(d.kind, Kind::kAdmit);
  EXPECT_EQ(d.evict, 5u);
  EXPECT_EQ(gate.counters().evicted_idle, 1u);
  EXPECT_EQ(gate.counters().accepted, 1u);
}

TEST_F(AdmissionTest, AKeepAliveConnectionBetweenRequestsMakesRoomAtOnce) {
  // A browser's pooled connections from one host at the cap: a second
  // browser window on that host is served by recycling one that waits for
  // its next request, not refused for net.idle_evict_s.
  Admission gate({8, SIZE_MAX, 0}, &settings);
  for (int n = 0; n < 6; ++n) clients.add(1, 0);
  EXPECT_EQ(gate.admit(clients, newcomer(1), 1000).kind, Kind::kRefusePerAddress);
  clients.entries[3].between_requests = true;
  const auto d = gate.admit(clients, newcomer(1), 1000);
  EXPECT_EQ(d.kind, Kind::kAdmit);
  EXPECT_EQ(d.evict, 3u);
}

TEST_F(AdmissionTest, ClientsOnTheControlAllowListAreNeverDroppedForAStranger) {
  ASSERT_EQ(settings.set_text(settings::Id::kAccessControlNetworks, "10.0.0.0/29").error,
            Error::kOk);  // 10.0.0.0 - 10.0.0.7
  Admission gate({8, SIZE_MAX, 0}, &settings);
  for (std::uint8_t h = 1; h <= 7; ++h) clients.add(h, 0);
  EXPECT_TRUE(gate.control_listed(clients.entries[0].peer));
  clients.add(20, 1000);  // not listed, idle a little less long
  auto d = gate.admit(clients, newcomer(30), 100000);
  EXPECT_EQ(d.kind, Kind::kAdmit);
  EXPECT_EQ(d.evict, 7u);  // the stranger, though the listed ones are idle longer
  clients.open[7] = false;
  clients.add(21, 100000);
  d = gate.admit(clients, newcomer(30), 200000);
  EXPECT_EQ(d.kind, Kind::kAdmit);
  EXPECT_EQ(d.evict, 7u);
  clients.entries[7].peer = access::Peer::from_ipv4(0x0A000005);  // now all listed
  d = gate.admit(clients, newcomer(30), 300000);
  EXPECT_EQ(d.kind, Kind::kRefuseFull);
}

TEST_F(AdmissionTest, WithAccessControlOffEveryIdleClientMayBeDropped) {
  Admission gate({2, SIZE_MAX, 0}, &settings);
  clients.add(1, 0);
  clients.add(2, 0);
  EXPECT_FALSE(gate.control_listed(clients.entries[0].peer));
  EXPECT_EQ(gate.admit(clients, newcomer(3), 60000).evict, 0u);
}

TEST_F(AdmissionTest, ZeroSecondsDropsTheIdlestClientAtOnce) {
  ASSERT_EQ(settings.set(settings::Id::kNetIdleEvictS, 0).error, Error::kOk);
  Admission gate({2, SIZE_MAX, 0}, &settings);
  clients.add(1, 10);
  clients.add(2, 5);
  const auto d = gate.admit(clients, newcomer(3), 10);
  EXPECT_EQ(d.kind, Kind::kAdmit);
  EXPECT_EQ(d.evict, 1u);
}

TEST_F(AdmissionTest, OneHostNeverTakesEverySlot) {
  Admission gate({8, SIZE_MAX, 0}, &settings);
  for (int n = 0; n < 6; ++n) {
    const auto d = gate.admit(clients, newcomer(1), 0);
    ASSERT_EQ(d.kind, Kind::kAdmit);
    ASSERT_EQ(d.evict, Admission::kNone);
    clients.add(1, 0);
  }
  EXPECT_EQ(gate.admit(clients, newcomer(1), 1000).kind, Kind::kRefusePerAddress);
  EXPECT_EQ(gate.counters().refused_per_address, 1u);
  // Another host still gets in.
  EXPECT_EQ(gate.admit(clients, newcomer(2), 1000).kind, Kind::kAdmit);
  // Set above max_clients, the cap stays one below it.
  ASSERT_EQ(settings.set(settings::Id::kNetMaxPerAddress, 32).error, Error::kOk);
  EXPECT_EQ(gate.per_address_cap(), 7u);
  Admission single({1, SIZE_MAX, 0}, &settings);
  EXPECT_EQ(single.per_address_cap(), 1u);
}

TEST_F(AdmissionTest, AHostAtItsCapReplacesItsOwnIdleClientEvenAnAllowedOne) {
  ASSERT_EQ(settings.set_text(settings::Id::kAccessControlNetworks, "10.0.0.1").error, Error::kOk);
  ASSERT_EQ(settings.set(settings::Id::kNetMaxPerAddress, 2).error, Error::kOk);
  Admission gate({8, SIZE_MAX, 0}, &settings);
  clients.add(1, 0);
  clients.add(2, 0);
  clients.add(1, 100);
  // A rebooted PC: its old connections are dead but never closed.
  const auto d = gate.admit(clients, newcomer(1), 60000);
  EXPECT_EQ(d.kind, Kind::kAdmit);
  EXPECT_EQ(d.evict, 0u);
}

TEST_F(AdmissionTest, EventStreamsCountApartAndTheOldestGivesWay) {
  Admission gate({2, SIZE_MAX, 3}, &settings);
  clients.add(1, 0, true);
  clients.add(1, 10, true);
  clients.add(1, 20, true);
  // Three streams from one host: neither max_clients nor its cap is reached.
  auto d = gate.admit(clients, newcomer(1), 30);
  EXPECT_EQ(d.kind, Kind::kAdmit);
  EXPECT_EQ(d.evict, Admission::kNone);
  const std::size_t fourth = clients.add(1, 30);
  clients.entries[fourth].event_stream = true;
  EXPECT_EQ(gate.stream_started(clients, fourth), 0u);  // the oldest
  EXPECT_EQ(gate.counters().evicted_event_stream, 1u);
  clients.open[0] = false;
  EXPECT_EQ(gate.stream_started(clients, fourth), Admission::kNone);  // within the limit now
}

TEST_F(AdmissionTest, WhenEveryStaticSlotIsTakenTheOldestStreamMakesRoomFirst) {
  // The Pico's HTTP port: 4 slots, at most 2 streams.
  Admission gate({4, 4, 2}, &settings);
  clients.add(1, 0, true);
  clients.add(2, 5, true);
  clients.add(3, 10);
  clients.add(4, 20);
  const auto d = gate.admit(clients, newcomer(5), 30);
  EXPECT_EQ(d.kind, Kind::kAdmit);
  EXPECT_EQ(d.evict, 0u);
  EXPECT_EQ(gate.counters().evicted_event_stream, 1u);
}

TEST_F(AdmissionTest, WithoutSettingsTheOldRuleHolds) {
  Admission gate({2, SIZE_MAX, 0}, nullptr);
  clients.add(1, 0);
  EXPECT_EQ(gate.admit(clients, newcomer(1), 0).kind, Kind::kAdmit);
  clients.add(1, 0);
  EXPECT_EQ(gate.admit(clients, newcomer(1), 1000000).kind, Kind::kRefuseFull);
}

TEST_F(AdmissionTest, AFullPortGivesANewcomerAStopOnlyExchangeOnePerHost) {
  Admission gate({8, SIZE_MAX, 0, 2}, &settings);
  for (std::uint8_t h = 1; h <= 8; ++h) clients.add(h, 0);
  EXPECT_EQ(gate.admit(clients, newcomer(9), 1000).kind, Kind::kStopOnly);
  ClientInfo first = newcomer(9);
  first.stop_only = true;
  clients.entries.push_back(first);
  clients.open.push_back(true);
  // One per host; another host gets the second; then the port refuses.
  EXPECT_EQ(gate.admit(clients, newcomer(9), 1000).kind, Kind::kRefuseFull);
  EXPECT_EQ(gate.admit(clients, newcomer(10), 1000).kind, Kind::kStopOnly);
  ClientInfo second = newcomer(10);
  second.stop_only = true;
  clients.entries.push_back(second);
  clients.open.push_back(true);
  EXPECT_EQ(gate.admit(clients, newcomer(11), 1000).kind, Kind::kRefuseFull);
  EXPECT_EQ(gate.counters().stop_only, 2u);
  // Stop-only exchanges count against nothing else: the per-address cap,
  // the slots, eviction.
  clients.entries[0].last_useful_ms = -60000;
  const auto d = gate.admit(clients, newcomer(12), 1000);
  EXPECT_EQ(d.kind, Kind::kAdmit);
  EXPECT_EQ(d.evict, 0u);
}

TEST_F(AdmissionTest, TheListedOwnerDropsTheStrangerLeastRecentlyUsefulHoweverBusy) {
  ASSERT_EQ(settings.set_text(settings::Id::kAccessControlNetworks, "10.0.0.1").error, Error::kOk);
  Admission gate({4, SIZE_MAX, 0, 4}, &settings);
  for (std::uint8_t h = 2; h <= 5; ++h) clients.add(h, 0);
  for (std::size_t i = 0; i < 4; ++i) clients.entries[i].last_useful_ms = 100 - Millis(i);
  // Busy strangers (used within the minute): a stranger gets only STOP...
  EXPECT_EQ(gate.admit(clients, newcomer(6), 1000).kind, Kind::kStopOnly);
  // ...the listed owner a slot, the least recently useful stranger's.
  const auto d = gate.admit(clients, newcomer(1), 1000);
  EXPECT_EQ(d.kind, Kind::kAdmit);
  EXPECT_EQ(d.evict, 3u);
  EXPECT_EQ(gate.counters().evicted_for_listed, 1u);
}

TEST_F(AdmissionTest, AmongListedClientsTheLeastRecentlyUsefulGivesWay) {
  ASSERT_EQ(settings.set_text(settings::Id::kAccessControlNetworks, "10.0.0.0/24").error,
            Error::kOk);
  Admission gate({3, SIZE_MAX, 0, 3}, &settings);
  clients.add(2, 0);
  clients.add(3, 0);
  clients.add(4, 0);
  clients.entries[0].last_useful_ms = 900;  // a tracking program, asking every second
  clients.entries[1].last_useful_ms = 10;   // silent since it came
  clients.entries[2].last_useful_ms = 500;
  const auto d = gate.admit(clients, newcomer(1), 1000);
  EXPECT_EQ(d.kind, Kind::kAdmit);
  EXPECT_EQ(d.evict, 1u);
}

TEST_F(AdmissionTest, UnreadableAccessSettingsListNobody) {
  ASSERT_EQ(settings.set_text(settings::Id::kAccessControlNetworks, "10.0.0.0/24").error,
            Error::kOk);
  Admission gate({8, SIZE_MAX, 0}, &settings);
  EXPECT_TRUE(gate.control_listed(newcomer(1).peer));
  settings.set_access_unreadable(true);
  EXPECT_FALSE(gate.control_listed(newcomer(1).peer));
}

TEST(Address, AnIpv4MappedIpv6AddressIsTheSameHostAsItsIpv4) {
  const std::uint8_t mapped[16] = {0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0xFF, 0xFF, 192, 168, 1, 20};
  EXPECT_EQ(Address::from_ipv6(mapped), Address::from_ipv4(0xC0A80114));
  const std::uint8_t other[16] = {0xFE, 0x80, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 192, 168, 1, 20};
  EXPECT_FALSE(Address::from_ipv6(other) == Address::from_ipv4(0xC0A80114));
}

}  // namespace
}  // namespace rotord::net
