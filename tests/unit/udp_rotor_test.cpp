// The UDP rotor protocols (docs/protocols/udp.md) on fake hardware: N1MM+'s
// <N1MMRotor> messages (rotor name, offset, bidirectional antennas, stop, the
// heading report) and PstRotator's <PST> control (go-to, STOP, PARK, QRA, the
// AZ?/EL? replies to port + 1); malformed and oversize datagrams move
// nothing; a read-only sender is refused everything but STOP and queries.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "fake_rotator.hpp"
#include "protocol/datagram_registry.hpp"
#include "protocol/flat_xml.hpp"

namespace rotord::protocol {
namespace {

using settings::Id;

class UdpRotorTest : public ::testing::Test {
 protected:
  explicit UdpRotorTest(bool with_el = true) : r(with_el) { r.run_ms(50); }
  testing::FakeRotator r;
  N1mmRotor n1mm{*r.controller};
  PstRotor pst{*r.controller};
  access::Peer lan = access::Peer::from_ipv4(0xC0A80114);  // 192.168.1.20
  DatagramReplies replies;

  DatagramOutcome send(DatagramProtocol& p, const std::string& datagram,
                       access::Peer from = access::Peer::from_ipv4(0xC0A80114)) {
    replies = {};
    return p.receive(datagram, from, replies);
  }
  RotatorStatus status() const { return r.controller->status(); }
  bool has_target() const { return status().az.has_target; }
  float az_target() const { return status().az.target_deg; }
};

std::string goazi(const std::string& rotor, const std::string& az, const std::string& offset = "0",
                  const std::string& bidirectional = "0") {
  return "<N1MMRotor><rotor>" + rotor + "</rotor><goazi>" + az + "</goazi><offset>" + offset +
         "</offset><bidirectional>" + bidirectional +
         "</bidirectional><freqband>14</freqband></N1MMRotor>";
}

TEST(FlatXml, ReadsTheFlatFormatsAndRefusesEverythingElse) {
  FlatXml xml;
  ASSERT_TRUE(
      xml.parse("<?xml version=\"1.0\"?>\r\n<PST>\n <AZIMUTH> 85 </AZIMUTH>AZ?</PST>\r\n", "PST"));
  ASSERT_EQ(xml.items().size(), 2u);
  EXPECT_EQ(xml.items()[0].name, "AZIMUTH");
  EXPECT_EQ(xml.items()[0].value, "85");
  EXPECT_EQ(xml.items()[1].name, "");
  EXPECT_EQ(xml.items()[1].value, "AZ?");
  EXPECT_TRUE(xml.parse("<pst><stop>1</stop></pst>", "PST"));
  for (const char* bad :
       {"", "<PST>", "<PST><AZIMUTH>1</AZIMUTH>", "<PST><A><B>1</B></A></PST>",
        "<PST><AZIMUTH>1</ELEVATION></PST>", "<N1MMRotor></N1MMRotor>", "<PST></PST>junk",
        "<PST><A x=\"1\">2</A></PST>", "<PST><!-- c --></PST>", "<PST><A/></PST>", "<?xml"}) {
    EXPECT_FALSE(xml.parse(bad, "PST")) << bad;
  }
  char out[8];
  EXPECT_EQ(xml_unescape("A &amp; B", out, sizeof(out)), 5u);
  EXPECT_EQ(std::string(out, 5), "A & B");
  EXPECT_EQ(xml_unescape("&nbsp;", out, sizeof(out)), std::string_view::npos);
  EXPECT_EQ(xml_unescape("123456789", out, sizeof(out)), std::string_view::npos);
}

TEST_F(UdpRotorTest, N1mmGoesToTheHeadingAndReportsItBack) {
  EXPECT_EQ(send(n1mm, goazi("Yagi 20", "330.0")), DatagramOutcome::kDone);
  EXPECT_TRUE(has_target());
  EXPECT_NEAR(az_target(), 330.0f, 0.01f);
  ASSERT_EQ(replies.count(), 1u);
  EXPECT_EQ(replies[0].port, 13010);
  EXPECT_EQ(replies[0].text(), "Yagi 20 @ 1000");  // still at 100.0 deg
  // The stop message stops, whoever sends it.
  r.controller->settings().set_text(Id::kAccessControlNetworks, "10.0.0.0/8");
  EXPECT_EQ(send(n1mm, "<N1MMRotor><stop>Yagi 20</stop></N1MMRotor>"), DatagramOutcome::kDone);
  EXPECT_FALSE(has_target());
  EXPECT_EQ(replies[0].text(), "Yagi 20 @ 1000");
}

TEST_F(UdpRotorTest, N1mmReportsTheHeadingEverySecondWhileTurningThenOnceStopped) {
  DatagramReplies out;
  access::Peer to;
  EXPECT_FALSE(n1mm.poll(out, to));  // nothing asked yet
  EXPECT_EQ(send(n1mm, goazi("Yagi 20", "130")), DatagramOutcome::kDone);
  // The antenna turns 2 deg per 100 ms (the test is the plant), polled
  // after every tick as the ports do.
  std::vector<std::string> reports;
  float az = 100.0f;
  for (int step = 0; step < 60; ++step) {
    for (int tick = 0; tick < 10; ++tick) {
      // 20 deg/s in steps of a tick: within the sensor filter's gate.
      if (az < 130.0f) az += 0.2f;
      r.az.set_deg(az);
      r.run_ms(10);
      out = {};
      if (n1mm.poll(out, to)) {
        EXPECT_EQ(to.ipv4, lan.ipv4);
        EXPECT_EQ(out[0].port, 13010);
        reports.emplace_back(out[0].text());
      }
    }
  }
  ASSERT_FALSE(status().moving());
  // About one a second while turning (about 1.5 s), then the last at rest.
  ASSERT_GE(reports.size(), 2u);
  EXPECT_LE(reports.size(), 4u);
  EXPECT_EQ(reports[0].rfind("Yagi 20 @ 1", 0), 0u);
  EXPECT_EQ(reports.back().substr(0, 12), "Yagi 20 @ 13");
}

TEST_F(UdpRotorTest, N1mmAppliesTheOffsetAndPicksTheNearerEndOfABidirectionalBeam) {
  // The antenna points 90 deg clockwise of the rotor: the rotor turns to 240.
  EXPECT_EQ(send(n1mm, goazi("", "330", "90")), DatagramOutcome::kDone);
  EXPECT_NEAR(az_target(), 240.0f, 0.01f);
  // At 100 deg, a bidirectional beam for 290 turns the rotor to 110, not 290.
  EXPECT_EQ(send(n1mm, goazi("", "290", "0", "1")), DatagramOutcome::kDone);
  EXPECT_NEAR(az_target(), 110.0f, 0.01f);
  EXPECT_EQ(send(n1mm, goazi("", "95", "0", "True")), DatagramOutcome::kDone);
  EXPECT_NEAR(az_target(), 95.0f, 0.01f);
  // Offsets wrap: 10 - 30 is 340.
  EXPECT_EQ(send(n1mm, goazi("", "10", "30")), DatagramOutcome::kDone);
  EXPECT_NEAR(az_target(), 340.0f, 0.01f);
}

TEST_F(UdpRotorTest, N1mmObeysOnlyItsOwnRotorName) {
  r.controller->settings().set_text(Id::kN1mmRotorName, "Beam & Co");
  EXPECT_EQ(send(n1mm, goazi("Other", "200")), DatagramOutcome::kNotForUs);
  EXPECT_EQ(send(n1mm, "<N1MMRotor><stop>Other</stop></N1MMRotor>"), DatagramOutcome::kNotForUs);
  EXPECT_EQ(send(n1mm, "<N1MMRotor><goazi>200</goazi></N1MMRotor>"), DatagramOutcome::kNotForUs);
  EXPECT_FALSE(has_target());
  EXPECT_EQ(replies.count(), 0u);
  EXPECT_EQ(send(n1mm, goazi("Beam &amp; Co", "200")), DatagramOutcome::kDone);
  EXPECT_NEAR(az_target(), 200.0f, 0.01f);
  EXPECT_EQ(replies[0].text(), "Beam & Co @ 1000");
  // No report port: no report.
  r.controller->settings().set(Id::kN1mmReportPort, 0);
  EXPECT_EQ(send(n1mm, goazi("Beam &amp; Co", "210")), DatagramOutcome::kDone);
  EXPECT_EQ(replies.count(), 0u);
}

TEST_F(UdpRotorTest, N1mmStopsInEveryFormAStopIsSentIn) {
  // Issue 23 item 4 (docs/protocols/udp.md, "Stop").
  r.controller->settings().set_text(Id::kN1mmRotorName, "teststack");
  const std::string turn = goazi("teststack", "200");
  for (const std::string& stop : {
           std::string("<N1MMRotor><stop>teststack</stop></N1MMRotor>"),
           std::string("<N1MMRotor><stop><rotor>teststack</rotor><freqband>14.0</freqband>"
                       "</stop></N1MMRotor>"),
           std::string("<N1MMRotor>\n <stop>\n  <rotor>teststack</rotor>\n </stop>\n"
                       "</N1MMRotor>"),
           std::string("<N1MMRotor><rotor>teststack</rotor><goazi>123.4</goazi>"
                       "<stop>True</stop></N1MMRotor>"),
           std::string("<N1MMRotor><stop>True</stop></N1MMRotor>"),
           std::string("<N1MMRotor><stop>1</stop></N1MMRotor>"),
           std::string("<N1MMRotor><rotor>teststack</rotor><stop>true</stop></N1MMRotor>"),
           // A stop is obeyed whatever else in the message is wrong.
           std::string("<N1MMRotor><rotor>teststack</rotor><goazi>999</goazi>"
                       "<stop>teststack</stop></N1MMRotor>"),
           std::string("<N1MMRotor><stop><rotor>teststack</rotor><speed>3</speed></stop>"
                       "</N1MMRotor>"),
       }) {
    ASSERT_EQ(send(n1mm, turn), DatagramOutcome::kDone);
    ASSERT_TRUE(has_target());
    EXPECT_EQ(send(n1mm, stop), DatagramOutcome::kDone) << stop;
    EXPECT_FALSE(has_target()) << stop;
  }
  // False is no stop: beside a heading the heading is obeyed.
  EXPECT_EQ(send(n1mm,
                 "<N1MMRotor><rotor>teststack</rotor><goazi>123.4</goazi>"
                 "<stop>False</stop></N1MMRotor>"),
            DatagramOutcome::kDone);
  EXPECT_NEAR(az_target(), 123.4f, 0.01f);
  // Nothing to do and no rotor named: not obeyed (not for this rotor).
  EXPECT_NE(send(n1mm, "<N1MMRotor><stop>False</stop></N1MMRotor>"), DatagramOutcome::kDone);
  EXPECT_NEAR(az_target(), 123.4f, 0.01f);
  // Another rotor's stop, in any form, is that rotor's.
  for (const std::string& other : {
           std::string("<N1MMRotor><stop>Other</stop></N1MMRotor>"),
           std::string("<N1MMRotor><stop><rotor>Other</rotor></stop></N1MMRotor>"),
           std::string("<N1MMRotor><rotor>Other</rotor><stop>True</stop></N1MMRotor>"),
       }) {
    EXPECT_EQ(send(n1mm, other), DatagramOutcome::kNotForUs) << other;
    EXPECT_TRUE(has_target()) << other;
  }
  // Nesting is for <stop> alone, one level deep.
  for (const std::string& bad : {
           std::string("<N1MMRotor><goazi><rotor>a</rotor></goazi></N1MMRotor>"),
           std::string("<N1MMRotor><stop><rotor><a>x</a></rotor></stop></N1MMRotor>"),
           std::string("<N1MMRotor><stop><rotor>x</rotor></N1MMRotor>"),
       }) {
    EXPECT_NE(send(n1mm, bad), DatagramOutcome::kDone) << bad;
  }
}

TEST_F(UdpRotorTest, N1mmIgnoresMalformedMessagesAndMovesNothing) {
  for (const std::string& bad : {
           std::string("<N1MMRotor><goazi>abc</goazi></N1MMRotor>"),
           std::string("<N1MMRotor><goazi>361</goazi></N1MMRotor>"),
           std::string("<N1MMRotor><goazi>-1</goazi></N1MMRotor>"),
           std::string("<N1MMRotor><goazi>200</goazi><goazi>100</goazi></N1MMRotor>"),
           std::string("<N1MMRotor><goazi>200</goazi><speed>3</speed></N1MMRotor>"),
           std::string("<N1MMRotor><goazi>200</goazi><bidirectional>2</bidirectional></N1MMRotor>"),
           std::string("<N1MMRotor><rotor>a</rotor></N1MMRotor>"),
           std::string("<N1MMRotor><rotor>a&b;</rotor><goazi>200</goazi></N1MMRotor>"),
           std::string("<PST><AZIMUTH>200</AZIMUTH></PST>"),
           std::string("200"),
           std::string("\0<N1MMRotor><goazi>200</goazi></N1MMRotor>", 42),
       }) {
    EXPECT_EQ(send(n1mm, bad), DatagramOutcome::kMalformed) << bad;
    EXPECT_EQ(replies.count(), 0u);
  }
  const std::string oversize =
      "<N1MMRotor><goazi>200</goazi>" + std::string(500, ' ') + "</N1MMRotor>";
  EXPECT_EQ(send(n1mm, oversize), DatagramOutcome::kOversize);
  EXPECT_FALSE(has_target());
}

TEST_F(UdpRotorTest, AReadOnlySenderIsRefusedMovesButStopsAndReads) {
  r.controller->settings().set_text(Id::kAccessControlNetworks, "10.0.0.0/8");
  EXPECT_EQ(send(n1mm, goazi("", "200")), DatagramOutcome::kRefused);
  EXPECT_EQ(replies.count(), 1u);  // the heading is still reported
  EXPECT_EQ(send(pst, "<PST><AZIMUTH>200</AZIMUTH>AZ?</PST>"), DatagramOutcome::kRefused);
  EXPECT_EQ(replies.count(), 1u);
  EXPECT_EQ(send(pst, "<PST><PARK>1</PARK></PST>"), DatagramOutcome::kRefused);
  EXPECT_FALSE(has_target());
  // From the allowed network it moves; STOP from anyone stops.
  EXPECT_EQ(send(pst, "<PST><AZIMUTH>200</AZIMUTH></PST>", access::Peer::from_ipv4(0x0A000001)),
            DatagramOutcome::kDone);
  EXPECT_TRUE(has_target());
  EXPECT_EQ(send(pst, "<PST><STOP>1</STOP></PST>"), DatagramOutcome::kDone);
  EXPECT_FALSE(has_target());
  // The control lock makes every sender read-only.
  r.controller->settings().set_text(Id::kAccessControlNetworks, "");
  r.controller->control_lock().take({}, r.now + 60000);
  EXPECT_EQ(send(pst, "<PST><AZIMUTH>200</AZIMUTH></PST>"), DatagramOutcome::kRefused);
}

TEST_F(UdpRotorTest, EveryPstRowThatChangesStateIsRefusedToAReadOnlySender) {
  r.controller->settings().set_text(Id::kAccessControlNetworks, "10.0.0.0/8");
  for (const PstRotor::Command& c : PstRotor::commands()) {
    std::string body;
    switch (c.arg) {
      case PstRotor::Arg::kNumber:
        body = "<" + std::string(c.name) + ">100</" + std::string(c.name) + ">";
        break;
      case PstRotor::Arg::kSwitch:
        body = "<" + std::string(c.name) + ">1</" + std::string(c.name) + ">";
        break;
      case PstRotor::Arg::kLocator:
        body = "<" + std::string(c.name) + ">KO02</" + std::string(c.name) + ">";
        break;
      case PstRotor::Arg::kQuery:
        body = std::string(c.name);
        break;
    }
    const DatagramOutcome outcome = send(pst, "<PST>" + body + "</PST>");
    EXPECT_EQ(outcome == DatagramOutcome::kRefused, c.changes_state) << c.name;
    EXPECT_FALSE(has_target()) << c.name;
  }
}

TEST_F(UdpRotorTest, PstGoesToStopsParksAndAnswersQueriesToPortPlusOne) {
  EXPECT_EQ(send(pst, "<PST><AZIMUTH>85</AZIMUTH></PST>"), DatagramOutcome::kDone);
  EXPECT_NEAR(az_target(), 85.0f, 0.01f);
  EXPECT_EQ(replies.count(), 0u);  // commands get no reply
  EXPECT_EQ(send(pst, "<PST><ELEVATION>45.5</ELEVATION></PST>"), DatagramOutcome::kDone);
  EXPECT_NEAR(status().el.target_deg, 45.5f, 0.01f);
  // Hamlib 4.6's pstrotator model writes "%f.2".
  EXPECT_EQ(send(pst, "<PST><AZIMUTH>123.000000.2</AZIMUTH></PST>"), DatagramOutcome::kDone);
  EXPECT_NEAR(az_target(), 123.0f, 0.01f);
  EXPECT_EQ(send(pst, "<PST>AZ?</PST>"), DatagramOutcome::kDone);
  ASSERT_EQ(replies.count(), 1u);
  EXPECT_EQ(replies[0].port, 12001);
  EXPECT_EQ(replies[0].text(), "AZ:100\r");
  EXPECT_EQ(send(pst, "<PST>EL?</PST>\n"), DatagramOutcome::kDone);
  EXPECT_EQ(replies[0].text(), "EL:20\r");
  r.controller->settings().set(Id::kPstPort, 5000);
  EXPECT_EQ(send(pst, "<PST>AZ?EL?</PST>"), DatagramOutcome::kMalformed);  // one query per text
  EXPECT_EQ(send(pst, "<PST>AZ?<STOP>1</STOP>EL?</PST>"), DatagramOutcome::kDone);
  ASSERT_EQ(replies.count(), 2u);
  EXPECT_EQ(replies[0].port, 5001);
  EXPECT_EQ(replies[1].text(), "EL:20\r");
  EXPECT_FALSE(has_target());
  // The manual's example: stop, tracking off, then turn.
  EXPECT_EQ(send(pst, "<PST><STOP>1</STOP><TRACK>0</TRACK><AZIMUTH>85</AZIMUTH></PST>"),
            DatagramOutcome::kDone);
  EXPECT_NEAR(az_target(), 85.0f, 0.01f);
  r.controller->settings().set(Id::kParkAzDeg, 180);
  EXPECT_EQ(send(pst, "<PST><PARK>1</PARK></PST>"), DatagramOutcome::kDone);
  EXPECT_NEAR(az_target(), 180.0f, 0.01f);
  EXPECT_EQ(status().mode, Mode::kPark);
}

TEST_F(UdpRotorTest, PstTurnsToALocatorFromTheStation) {
  r.controller->settings().set(Id::kStationLatDeg, 52.0);
  r.controller->settings().set(Id::kStationLonDeg, 5.0);
  // Due east along the same latitude starts a little north of east.
  EXPECT_EQ(send(pst, "<PST><QRA>KO02</QRA></PST>"), DatagramOutcome::kDone);
  EXPECT_GT(az_target(), 60.0f);
  EXPECT_LT(az_target(), 90.0f);
  EXPECT_EQ(send(pst, "<PST><QRA>ZZ99</QRA></PST>"), DatagramOutcome::kMalformed);
}

TEST_F(UdpRotorTest, PstIgnoresMalformedMessagesAndMovesNothing) {
  for (const char* bad : {"<PST><AZIMUTH>x</AZIMUTH></PST>", "<PST><AZIMUTH>800</AZIMUTH></PST>",
                          "<PST><AZIMUTH>85.2</AZIMUTH><FOO>1</FOO></PST>",
                          "<PST><STOP>2</STOP></PST>", "<PST>HELLO?</PST>", "<PST></PST>",
                          "<PST><AZ?>1</AZ?></PST>", "<PST><AZIMUTH>85.00.2</AZIMUTH></PST>", "AZ?",
                          "<N1MMRotor><goazi>1</goazi></N1MMRotor>"}) {
    EXPECT_EQ(send(pst, bad), DatagramOutcome::kMalformed) << bad;
    EXPECT_EQ(replies.count(), 0u);
  }
  EXPECT_FALSE(has_target());
  // Out of the travel: the controller refuses it, nothing moves.
  EXPECT_EQ(send(pst, "<PST><AZIMUTH>500</AZIMUTH></PST>"), DatagramOutcome::kFailed);
  EXPECT_FALSE(has_target());
}

class UdpRotorAzOnlyTest : public UdpRotorTest {
 protected:
  UdpRotorAzOnlyTest() : UdpRotorTest(false) {}
};

TEST_F(UdpRotorAzOnlyTest, AnAzimuthOnlyRotatorIgnoresTheElevation) {
  EXPECT_EQ(send(pst, "<PST><ELEVATION>30</ELEVATION></PST>"), DatagramOutcome::kDone);
  EXPECT_FALSE(has_target());
  EXPECT_EQ(send(pst, "<PST>EL?</PST>"), DatagramOutcome::kDone);
  EXPECT_EQ(replies[0].text(), "EL:0\r");
}

TEST(DatagramRegistry, EveryRowIsOffByDefaultAndHasItsHandler) {
  testing::FakeRotator r;
  DatagramHandlers handlers(*r.controller);
  settings::Settings defaults;
  for (const DatagramInfo& info : datagram_protocols()) {
    EXPECT_FALSE(defaults.b(info.enabled)) << info.key;
    EXPECT_GT(defaults.i(info.port), 0) << info.key;
    DatagramReplies replies;
    EXPECT_EQ(handlers.get(info.personality).receive("junk", {}, replies),
              DatagramOutcome::kMalformed);
  }
  EXPECT_EQ(defaults.i(Id::kN1mmPort), 12040);
  EXPECT_EQ(defaults.i(Id::kPstPort), 12000);
}

}  // namespace
}  // namespace rotord::protocol
