// IPv6 in access control (issue 29): the address parser and printer the
// allow-list and the logs use, IPv6 prefixes on access.control_networks,
// IPv4-mapped clients matching IPv4 entries, and an IPv6 host counted by its
// /64 for the per-address caps, the login limiter and the log's summaries.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "access/log_gate.hpp"
#include "access/login_limiter.hpp"
#include "net/admission.hpp"
#include "net/line_access.hpp"
#include "settings/network_list.hpp"
#include "settings/settings.hpp"

namespace rotord {
namespace {

using access::IpBytes;
using access::Peer;

IpBytes v6(const char* text) {
  IpBytes a{};
  EXPECT_TRUE(settings::parse_ipv6(text, a)) << text;
  return a;
}

std::string text_of(const IpBytes& a) {
  char buf[access::kAddressTextBytes];
  return access::address_text(a, buf);
}

TEST(Ipv6Text, ParsesTheForms) {
  EXPECT_EQ(v6("::")[15], 0);
  EXPECT_EQ(v6("::1")[15], 1);
  const IpBytes a = v6("2001:DB8::a:1");
  EXPECT_EQ(a[0], 0x20);
  EXPECT_EQ(a[1], 0x01);
  EXPECT_EQ(a[3], 0xB8);
  EXPECT_EQ(a[13], 0x0A);
  EXPECT_EQ(a[15], 0x01);
  EXPECT_EQ(v6("1:2:3:4:5:6:7:8")[15], 8);
  EXPECT_EQ(v6("fe80::")[0], 0xFE);
  const IpBytes mapped = v6("::ffff:192.168.1.20");
  EXPECT_EQ(mapped[10], 0xFF);
  EXPECT_EQ(mapped[12], 192);
  EXPECT_EQ(mapped[15], 20);
  EXPECT_EQ(v6("64:ff9b::10.0.0.1")[12], 10);
  IpBytes ignored{};
  for (const char* bad : {"", ":", ":::", "1", "1::2::3", "1:2:3:4:5:6:7:8:9", "1:2:3:4:5:6:7",
                          "12345::", "g::", "1:", ":1", "::1%eth0", "::1/64", "1::2:3:4:5:6:7:8",
                          "::ffff:1.2.3", "::ffff:1.2.3.4:5", "1.2.3.4", " ::1", "::1 "})
    EXPECT_FALSE(settings::parse_ipv6(bad, ignored)) << bad;
}

TEST(Ipv6Text, PrintsAsRfc5952Says) {
  EXPECT_EQ(text_of(v6("2001:0db8:0000:0000:0000:0000:0000:0001")), "2001:db8::1");
  EXPECT_EQ(text_of(v6("::1")), "::1");
  EXPECT_EQ(text_of(v6("::")), "::");
  EXPECT_EQ(text_of(v6("fe80::")), "fe80::");
  EXPECT_EQ(text_of(v6("2001:db8:0:1:0:0:0:1")), "2001:db8:0:1::1");       // the longer run
  EXPECT_EQ(text_of(v6("2001:db8:0:0:1:0:0:1")), "2001:db8::1:0:0:1");     // the first of equals
  EXPECT_EQ(text_of(v6("2001:db8:1:2:3:4:0:8")), "2001:db8:1:2:3:4:0:8");  // no single "::"
  EXPECT_EQ(text_of(v6("::ffff:10.0.0.1")), "::ffff:10.0.0.1");
  EXPECT_EQ(text_of(v6("1:2:3:4:5:6:7:8")), "1:2:3:4:5:6:7:8");
}

TEST(Ipv6Peer, AMappedAddressIsAnIpv4Client) {
  const Peer p = Peer::from_ipv6(v6("::ffff:192.168.1.20"));
  EXPECT_EQ(p.kind, Peer::Kind::kIpv4);
  EXPECT_EQ(p.ipv4, 0xC0A80114u);
  EXPECT_EQ(Peer::from_ipv6(v6("2001:db8::1")).kind, Peer::Kind::kIpv6);
}

TEST(Ipv6Peer, AHostIsItsSlash64) {
  const Peer a = Peer::from_ipv6(v6("2001:db8:1:2::1"));
  const Peer b = Peer::from_ipv6(v6("2001:db8:1:2:aaaa:bbbb:cccc:dddd"));
  const Peer c = Peer::from_ipv6(v6("2001:db8:1:3::1"));
  EXPECT_TRUE(a.same_host(b));
  EXPECT_FALSE(a.same_host(c));
  EXPECT_FALSE(a.same_host(Peer::from_ipv4(0x0A000001)));
  EXPECT_NE(a.address_hash(), b.address_hash());  // the web's command streams tell them apart
}

TEST(Ipv6Networks, ThePrefixesOfTheAllowList) {
  settings::IpNetwork n;
  ASSERT_TRUE(settings::parse_network("fd00::/8", n));
  EXPECT_TRUE(n.contains(v6("fd12:3456::1")));
  EXPECT_FALSE(n.contains(v6("fe80::1")));
  ASSERT_TRUE(settings::parse_network("2001:db8::/32", n));
  EXPECT_TRUE(n.contains(v6("2001:db8:ffff::1")));
  EXPECT_FALSE(n.contains(v6("2001:db9::1")));
  ASSERT_TRUE(settings::parse_network("::1", n));  // a /128
  EXPECT_TRUE(n.contains(v6("::1")));
  EXPECT_FALSE(n.contains(v6("::2")));
  ASSERT_TRUE(settings::parse_network("2001:db8::1/60", n));  // host bits ignored
  EXPECT_TRUE(n.contains(v6("2001:db8:0:f::9")));
  EXPECT_FALSE(n.contains(v6("2001:db8:0:10::")));
  ASSERT_TRUE(settings::parse_network("::/0", n));
  EXPECT_TRUE(n.contains(v6("1234::")));
  for (const char* bad : {"fd00::/129", "fd00::/", "fd00::/-1", "fd00::/1a", "fe80::1%eth0/64",
                          "fd00:/8", "10.0.0.0/33"})
    EXPECT_FALSE(settings::parse_network(bad, n)) << bad;
}

TEST(Ipv6Networks, Ipv4ClientsMatchIpv4EntriesHoweverTheyCame) {
  const Peer direct = Peer::from_ipv4(0xC0A80114);                 // 192.168.1.20
  const Peer mapped = Peer::from_ipv6(v6("::ffff:192.168.1.20"));  // a dual-stack socket
  const Peer lan6 = Peer::from_ipv6(v6("fd00::20"));
  for (const Peer& p : {direct, mapped}) {
    EXPECT_TRUE(settings::in_network_list("192.168.1.0/24", p));
    EXPECT_TRUE(settings::in_network_list("::ffff:192.168.1.0/120", p));
    EXPECT_FALSE(settings::in_network_list("fd00::/8", p));
  }
  EXPECT_TRUE(settings::in_network_list("192.168.1.0/24, fd00::/8", lan6));
  EXPECT_FALSE(settings::in_network_list("192.168.1.0/24, ::/96", lan6));
  EXPECT_FALSE(settings::in_network_list("::/0", Peer::line()));
  EXPECT_FALSE(settings::in_network_list("::/0", Peer{Peer::Kind::kOther, 0, {}}));
}

TEST(Ipv6Networks, TheSettingTakesIpv6AndSaysSo) {
  settings::Settings s;
  EXPECT_EQ(s.set_text(settings::Id::kAccessControlNetworks, "192.168.1.0/24, fd00::/8, ::1").error,
            Error::kOk);
  EXPECT_TRUE(access::may_control(s, Peer::from_ipv6(v6("fd00::7"))));
  EXPECT_TRUE(access::may_control(s, Peer::from_ipv6(v6("::1"))));
  EXPECT_FALSE(access::may_control(s, Peer::from_ipv6(v6("2001:db8::1"))));
  EXPECT_TRUE(access::may_control(s, Peer::from_ipv6(v6("::ffff:192.168.1.9"))));
  const settings::Rejection bad = s.set_text(settings::Id::kAccessControlNetworks, "fd00::/200");
  EXPECT_NE(bad.error, Error::kOk);
  EXPECT_NE(std::string(bad.reason).find("fd00::/8"), std::string::npos) << bad.reason;
}

net::ClientInfo client6(const char* address) {
  net::ClientInfo c;
  c.peer = Peer::from_ipv6(v6(address));
  c.address.bytes = c.peer.address();
  return c;
}

class Clients final : public net::ClientList {
 public:
  std::size_t size() const override { return entries.size(); }
  const net::ClientInfo* at(std::size_t i) const override { return &entries[i]; }
  std::vector<net::ClientInfo> entries;
};

TEST(Ipv6Admission, TheAddressesOfOneSlash64AreOneHostUnlessListed) {
  settings::Settings s;
  ASSERT_EQ(s.set(settings::Id::kNetMaxPerAddress, 2).error, Error::kOk);
  net::Admission gate({8, SIZE_MAX, 0, 8}, &s);
  Clients clients;
  clients.entries = {client6("2001:db8:1:2::a"), client6("2001:db8:1:2::b")};
  // A third address of the same /64: at the host's cap, nobody of it idle.
  EXPECT_EQ(gate.admit(clients, client6("2001:db8:1:2::c"), 1000).kind,
            net::Admission::Decision::Kind::kStopOnly);
  // Another /64 is another host.
  EXPECT_EQ(gate.admit(clients, client6("2001:db8:1:3::c"), 1000).kind,
            net::Admission::Decision::Kind::kAdmit);
  // The owner's own devices share their LAN's /64: listed, each is a host.
  ASSERT_EQ(s.set_text(settings::Id::kAccessControlNetworks, "2001:db8:1:2::/64").error,
            Error::kOk);
  EXPECT_EQ(gate.admit(clients, client6("2001:db8:1:2::c"), 1000).kind,
            net::Admission::Decision::Kind::kAdmit);
}

TEST(Ipv6Limits, TheLoginLimiterAndTheLogCountASlash64AsOne) {
  access::LoginLimiter limiter;
  for (unsigned n = 0; n < access::LoginLimiter::kFreeFailures; ++n)
    limiter.failed(Peer::from_ipv6(v6("2001:db8:1:2::1")), 100);
  // Another address of the same /64 waits too; another /64 does not.
  EXPECT_GT(limiter.wait_ms(Peer::from_ipv6(v6("2001:db8:1:2::99")), 100), 0);
  EXPECT_EQ(limiter.wait_ms(Peer::from_ipv6(v6("2001:db8:1:3::1")), 100), 0);

  access::LogGate gate;
  access::LogGate::Summary evicted;
  EXPECT_TRUE(gate.admit(Peer::from_ipv6(v6("2001:db8:1:2::1")), 0, evicted));
  EXPECT_FALSE(gate.admit(Peer::from_ipv6(v6("2001:db8:1:2::2")), 10, evicted));
  EXPECT_TRUE(gate.admit(Peer::from_ipv6(v6("2001:db8:1:3::1")), 20, evicted));
}

}  // namespace
}  // namespace rotord
