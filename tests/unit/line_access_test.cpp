// Access control on the line protocols (issue 12): a client outside
// access.control_networks gets its queries answered and STOP obeyed, and
// every command that moves the rotator or changes a setting refused in its
// protocol's own way; a line port follows access.serial_control.
#include "net/line_access.hpp"

#include <gtest/gtest.h>

#include <initializer_list>
#include <string>

#include "fake_rotator.hpp"
#include "protocol/easycomm_session.hpp"
#include "protocol/gs232_session.hpp"
#include "protocol/rotctld_session.hpp"
#include "protocol/seed_session.hpp"
#include "protocol/wrc_session.hpp"
#include "settings/network_list.hpp"
#include "string_sink.hpp"

namespace rotord {
namespace {

using access::Peer;
using settings::Id;

constexpr std::uint32_t ip(unsigned a, unsigned b, unsigned c, unsigned d) {
  return (a << 24) | (b << 16) | (c << 8) | d;
}

TEST(NetworkList, ParsesNetworksAndAddresses) {
  settings::Ipv4Network n;
  ASSERT_TRUE(settings::parse_ipv4_network("192.168.1.0/24", n));
  EXPECT_TRUE(n.contains(ip(192, 168, 1, 77)));
  EXPECT_FALSE(n.contains(ip(192, 168, 2, 1)));
  ASSERT_TRUE(settings::parse_ipv4_network("10.0.0.5", n));
  EXPECT_TRUE(n.contains(ip(10, 0, 0, 5)));
  EXPECT_FALSE(n.contains(ip(10, 0, 0, 6)));
  ASSERT_TRUE(settings::parse_ipv4_network("10.1.2.3/8", n));  // host bits ignored
  EXPECT_TRUE(n.contains(ip(10, 200, 0, 1)));
  ASSERT_TRUE(settings::parse_ipv4_network("0.0.0.0/0", n));
  EXPECT_TRUE(n.contains(ip(8, 8, 8, 8)));
  for (const char* bad : {"", "/24", "10.0.0.0/", "10.0.0.0/33", "10.0.0.0/-1", "10.0.0/8",
                          "10.0.0.0/8/8", "256.0.0.0/8", "fe80::/64", "10.0.0.0/ 8"})
    EXPECT_FALSE(settings::parse_ipv4_network(bad, n)) << bad;
  EXPECT_TRUE(settings::in_network_list("10.0.0.0/8, 192.168.1.5", ip(192, 168, 1, 5)));
  EXPECT_TRUE(settings::in_network_list("10.0.0.0/8,192.168.1.5", ip(10, 9, 9, 9)));
  EXPECT_FALSE(settings::in_network_list("10.0.0.0/8 192.168.1.5", ip(192, 168, 1, 6)));
}

TEST(NetworkList, TheSettingsRefuseMalformedLists) {
  settings::Settings s;
  EXPECT_EQ(s.set_text(Id::kAccessControlNetworks, "192.168.1.0/24, 10.0.0.5").error, Error::kOk);
  EXPECT_NE(s.set_text(Id::kAccessControlNetworks, "192.168.1.0/24, nope").error, Error::kOk);
  EXPECT_EQ(s.text(Id::kAccessControlNetworks), "192.168.1.0/24, 10.0.0.5");
  EXPECT_EQ(s.set_text(Id::kWebAllowedHosts, "shack.example.org, rotor").error, Error::kOk);
  EXPECT_NE(s.set_text(Id::kWebAllowedHosts, "bad_name!").error, Error::kOk);
  EXPECT_FALSE(settings::line_writable(Id::kAccessControlNetworks));
  EXPECT_FALSE(settings::line_writable(Id::kWebAllowedHosts));
  EXPECT_FALSE(settings::line_writable(Id::kAccessLineControl));
  EXPECT_FALSE(settings::line_writable(Id::kWifiPassword));
  EXPECT_TRUE(settings::line_writable(Id::kParkAzDeg));
}

TEST(LineAccess, WhoMayControl) {
  settings::Settings s;
  const Peer lan = Peer::from_ipv4(ip(192, 168, 1, 20));
  const Peer wan = Peer::from_ipv4(ip(203, 0, 113, 9));
  access::IpBytes doc{};  // 2001:db8::1
  doc[0] = 0x20;
  doc[1] = 0x01;
  doc[2] = 0x0D;
  doc[3] = 0xB8;
  doc[15] = 1;
  const Peer v6 = Peer::from_ipv6(doc);
  // Off by default: everyone, as before access control.
  EXPECT_TRUE(access::may_control(s, lan));
  EXPECT_TRUE(access::may_control(s, wan));
  EXPECT_TRUE(access::may_control(s, v6));
  ASSERT_EQ(s.set_text(Id::kAccessControlNetworks, "192.168.1.0/24").error, Error::kOk);
  EXPECT_TRUE(access::may_control(s, lan));
  EXPECT_FALSE(access::may_control(s, wan));
  EXPECT_FALSE(access::may_control(s, v6));
  EXPECT_TRUE(access::may_control(s, Peer{}));  // no transport said: a session on its own
  EXPECT_TRUE(access::may_control(s, Peer::line()));
  s.set(Id::kAccessLineControl, 0);
  EXPECT_FALSE(access::may_control(s, Peer::line()));
}

/// One session of each protocol for a client outside the allow-list.
/// Why a client is read-only: its address is outside
/// access.control_networks, or a web operator holds the control lock (which
/// binds every line client, whatever its address).
enum class Why { kNetworks, kLock };

class ReadOnly : public ::testing::TestWithParam<Why> {
 protected:
  void SetUp() override {
    ASSERT_EQ(r.settings.set_text(Id::kAccessControlNetworks, "10.0.0.0/8").error, Error::kOk);
    if (GetParam() == Why::kLock) {
      ASSERT_EQ(r.settings.set_text(Id::kAccessControlNetworks, "").error, Error::kOk);
      r.controller->control_lock().take(access::LockHolder{}, 60'000);
    }
    r.run_ms(50);
  }
  template <typename Session>
  std::string ask(Session& session, const std::string& bytes) {
    session.set_peer(Peer::from_ipv4(ip(192, 168, 1, 20)));
    testing::StringSink sink;
    session.receive(bytes, sink);
    return sink.data;
  }
  /// Nothing moved and no setting changed.
  void expect_untouched(std::uint32_t revision) {
    r.run_ms(200);
    EXPECT_FALSE(r.controller->status().moving());
    EXPECT_FALSE(r.controller->status().az.has_target);
    EXPECT_EQ(r.settings.revision(), revision);
  }
  struct Exchange {
    const char* command;
    const char* reply;
  };
  /// What a read-only client of one protocol sees: a query answered, every
  /// command that moves or writes refused in the protocol's own words, the
  /// commands everyone may send (STOP and its kin) answered; and afterwards
  /// nothing moved and no setting changed.
  template <typename Session>
  void expect_read_only(Session& s, Exchange query, std::initializer_list<const char*> refused,
                        const char* refusal, std::initializer_list<Exchange> allowed) {
    const auto revision = r.settings.revision();
    EXPECT_EQ(ask(s, query.command), query.reply);
    for (const char* command : refused) EXPECT_EQ(ask(s, command), refusal) << command;
    for (const Exchange& e : allowed) EXPECT_EQ(ask(s, e.command), e.reply) << e.command;
    expect_untouched(revision);
  }
  testing::FakeRotator r;
};

TEST_P(ReadOnly, RotctldAnswersQueriesAndRefusesTheRestWithRigErjcted) {
  protocol::RotctldSession s(*r.controller, "9");
  expect_read_only(s, {"p\n", "100.00\n20.00\n"},
                   {"P 200 30\n", "K\n", "R 1\n", "M 8 50\n", "V SPEED 20\n", "C park.az_deg 10\n"},
                   "RPRT -9\n", {{"S\n", "RPRT 0\n"}});
}

TEST_P(ReadOnly, Gs232RefusesWithItsError) {
  protocol::Gs232Session s(*r.controller);
  expect_read_only(
      s, {"C\r", "AZ=100\r\n"},
      {"M200\r", "W200 030\r", "R\r", "L\r", "U\r", "D\r", "X2\r", "O\r", "F2\r", "T\r"}, "?>\r\n",
      {{"S\r", "\r"}, {"A\r", "\r"}});
}

TEST_P(ReadOnly, EasycommRefusesWithAnAlarm) {
  protocol::EasycommSession s(*r.controller, "9");
  expect_read_only(
      s, {"AZ EL\n", "AZ100.0 EL20.0\n"},
      {"AZ200.0 EL30.0\n", "MR\n", "VL0500\n", "PARK\n", "RESET\n", "CW7,10\n", "CW 7,10\n"},
      "ALDENIED\n", {{"SA SE\n", ""}});
}

TEST_P(ReadOnly, WrcRefusesWithAnError) {
  protocol::WrcSession s(*r.controller, "9");
  expect_read_only(
      s, {"AZ?\n", "OK AZ 100.0\r\n"},
      {"AZ 200\n", "EL 30\n", "MOVE CW\n", "SPEED 20\n", "PARK\n", "RESET\n", "AZOFFSET 5\n"},
      "ERROR NOT ALLOWED\r\n", {{"STOP\n", "OK STOP\r\n"}});
}

TEST_P(ReadOnly, SeedRefusesWithAnError) {
  protocol::SeedSession s(*r.controller);
  expect_read_only(s, {"$E\n", "$OK,E\r\n"}, {"$R,cw\n", "$S,20\n"}, "$ERR,DENIED\r\n",
                   {{"$D\n", "$OK,D\r\n"}});
}

TEST_P(ReadOnly, AClientInTheListControls) {
  protocol::RotctldSession s(*r.controller, "9");
  s.set_peer(Peer::from_ipv4(ip(10, 1, 2, 3)));
  testing::StringSink sink;
  s.receive("P 200 30\n", sink);
  EXPECT_EQ(sink.data, GetParam() == Why::kLock ? "RPRT -9\n" : "RPRT 0\n");
}

INSTANTIATE_TEST_SUITE_P(OutsideTheNetworksOrUnderTheLock, ReadOnly,
                         ::testing::Values(Why::kNetworks, Why::kLock),
                         [](const ::testing::TestParamInfo<Why>& param) {
                           return param.param == Why::kLock ? "Lock" : "Networks";
                         });

}  // namespace
}  // namespace rotord
