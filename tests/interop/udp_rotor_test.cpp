// The UDP rotor messages (docs/protocols/udp.md) through the real daemon and
// real UDP sockets, on the manual clock: PstRotator's <PST> control (go-to,
// elevation, STOP, PARK, the AZ?/EL? queries answered to the sender at port
// + 1, Hamlib 4.6's "%f.2" azimuths), N1MM+'s <N1MMRotor> messages (go-to
// with an offset, a bidirectional antenna, the rotor name, stop, the heading
// report), a read-only sender refused everything but STOP and queries, and
// garbage and oversize datagrams ignored without a move. The datagrams are
// the published ones, byte for byte. Log lines (--log-level debug) and the
// replies say when the daemon has read a datagram; no sleeps.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include "daemon_process.hpp"
#include "http_client.hpp"
#include "shell.hpp"
#include "udp_socket.hpp"

namespace rotord::testing {
namespace {

class UdpRotor : public ::testing::Test {
 protected:
  /// Starts rotord on the manual clock with both UDP protocols on free
  /// ports, and the sockets that receive their answers.
  void start(const std::string& more_settings = "") {
    dir = make_temp_dir("rotord-udp");
    // PstRotator answers at its port + 1: find a pair that is free.
    for (int attempt = 0; attempt < 20 && !(pst_replies && pst_replies->bound()); ++attempt) {
      const int port = Udp().port();
      pst_port = port;
      pst_replies = std::make_unique<Udp>(port + 1);
    }
    ASSERT_TRUE(pst_replies->bound());
    n1mm_reports = std::make_unique<Udp>();
    n1mm_port = Udp().port();
    const std::string config = dir + "/rotord.json";
    std::ofstream(config) << R"({"pst.enabled": true, "pst.port": )" << pst_port
                          << R"(, "n1mm.enabled": true, "n1mm.port": )" << n1mm_port
                          << R"(, "n1mm.report_port": )" << n1mm_reports->port() << more_settings
                          << "}\n";
    daemon = std::make_unique<DaemonProcess>(std::vector<std::string>{
        "--sim", "g5500", "--clock", "manual", "--log-level", "debug", "--config", config});
    ASSERT_TRUE(daemon->ready()) << daemon->output();
  }
  void TearDown() override {
    daemon.reset();
    if (!dir.empty()) run_command("rm -rf " + dir);
  }
  /// Sends `datagram` to the PstRotator port, then asks AZ? from the same
  /// socket (read in order), and returns the answer.
  std::string pst_then_az(const std::string& datagram) {
    if (!datagram.empty()) client.send_to(pst_port, datagram);
    client.send_to(pst_port, "<PST>AZ?</PST>");
    return pst_replies->receive();
  }
  std::string pst_el() {
    client.send_to(pst_port, "<PST>EL?</PST>");
    return pst_replies->receive();
  }
  /// Sends an N1MM+ message and returns the heading report it gets (the
  /// reports sent meanwhile while the rotator turned are read first).
  std::string n1mm(const std::string& datagram) {
    drain_reports();
    client.send_to(n1mm_port, datagram);
    return n1mm_reports->receive();
  }
  /// The reports that arrived so far.
  std::vector<std::string> drain_reports() {
    std::vector<std::string> reports;
    for (std::string r = n1mm_reports->receive(0); !r.empty(); r = n1mm_reports->receive(0))
      reports.push_back(r);
    return reports;
  }
  std::string status() { return http(daemon->ports().web, "GET", "/api/status").body; }
  double az_target() {
    const std::string s = status();
    return json_number(s, "target_deg", s.find("\"az\""));
  }
  bool moving() { return status().find("\"moving\":true") != std::string::npos; }

  std::string dir;
  int pst_port = 0;
  int n1mm_port = 0;
  std::unique_ptr<Udp> pst_replies;
  std::unique_ptr<Udp> n1mm_reports;
  Udp client;
  std::unique_ptr<DaemonProcess> daemon;
};

std::string n1mm_goazi(const std::string& rotor, const std::string& az, const std::string& offset,
                       const std::string& bidirectional) {
  return "<N1MMRotor><rotor>" + rotor + "</rotor><goazi>" + az + "</goazi><offset>" + offset +
         "</offset><bidirectional>" + bidirectional +
         "</bidirectional><freqband>14</freqband></N1MMRotor>";
}

TEST_F(UdpRotor, PstRotatorGoToElevationStopParkAndQueriesToPortPlusOne) {
  start();
  const std::string at_start = pst_then_az("");
  ASSERT_EQ(at_start.rfind("AZ:", 0), 0u) << at_start;
  EXPECT_EQ(at_start.back(), '\r');
  // As Hamlib 4.6's pstrotator model writes them: two datagrams, "%f.2".
  client.send_to(pst_port, "<PST><AZIMUTH>100.000000.2</AZIMUTH></PST>");
  client.send_to(pst_port, "<PST><ELEVATION>30.000000.2</ELEVATION></PST>");
  EXPECT_EQ(pst_then_az(""), at_start);  // read, not moved yet
  daemon->advance_ms(90000);
  EXPECT_EQ(pst_then_az(""), "AZ:100\r");
  EXPECT_EQ(pst_el(), "EL:30\r");
  // STOP halts a move where it is (after the coast).
  pst_then_az("<PST><AZIMUTH>300</AZIMUTH></PST>");
  daemon->advance_ms(5000);
  pst_then_az("<PST><STOP>1</STOP></PST>");
  daemon->advance_ms(5000);
  const std::string stopped_at = pst_then_az("");
  daemon->advance_ms(10000);
  EXPECT_EQ(pst_then_az(""), stopped_at);
  EXPECT_NE(stopped_at, "AZ:100\r");
  EXPECT_NE(stopped_at, "AZ:300\r");
  EXPECT_FALSE(moving());
  // PARK: the park position (park.az_deg, here 180).
  ASSERT_EQ(http(daemon->ports().web, "POST", "/api/settings", R"({"park.az_deg": 180})").status,
            200);
  pst_then_az("<PST><PARK>1</PARK></PST>");
  daemon->advance_ms(90000);
  EXPECT_EQ(pst_then_az(""), "AZ:180\r");
  EXPECT_EQ(pst_el(), "EL:0\r");
}

TEST_F(UdpRotor, N1mmGoesToTheHeadingWithOffsetAndBidirectionalAndStops) {
  start(R"(, "n1mm.rotor_name": "Yagi 20")");
  // The antenna is mounted 90 deg clockwise of the rotor: the rotor turns to 240.
  EXPECT_EQ(n1mm(n1mm_goazi("Yagi 20", "330.0", "90", "0")).rfind("Yagi 20 @ ", 0), 0u);
  EXPECT_NEAR(az_target(), 240.0, 0.1);
  daemon->advance_ms(90000);
  EXPECT_EQ(pst_then_az(""), "AZ:240\r");
  // Every second while it turned, then once stopped, as N1MM+'s window shows it.
  const std::vector<std::string> reports = drain_reports();
  ASSERT_GE(reports.size(), 2u);
  ASSERT_EQ(reports.back().rfind("Yagi 20 @ ", 0), 0u);
  EXPECT_NEAR(std::stoi(reports.back().substr(10)), 2400, 10);  // within the axis tolerance
  // A bidirectional beam for 80 deg: 260 is 20 deg away, 80 is 160.
  n1mm(n1mm_goazi("Yagi 20", "80", "0", "1"));
  EXPECT_NEAR(az_target(), 260.0, 0.1);
  daemon->advance_ms(30000);
  const std::string stopped = n1mm("<N1MMRotor><stop>Yagi 20</stop></N1MMRotor>");
  ASSERT_EQ(stopped.rfind("Yagi 20 @ ", 0), 0u);
  EXPECT_NEAR(std::stoi(stopped.substr(10)), 2600, 10);
  // Another rotor's messages are left alone (the log says when it was read).
  client.send_to(n1mm_port, n1mm_goazi("Tribander", "10", "0", "0"));
  ASSERT_TRUE(daemon->wait_for_output("for another rotor")) << daemon->output();
  EXPECT_FALSE(moving());
  EXPECT_EQ(n1mm_reports->receive(200), "");  // and get no report
}

TEST_F(UdpRotor, N1mmStopsInEveryFormTheStopIsSentIn) {
  // Issue 23 item 4: the stop as programs send it (docs/protocols/udp.md,
  // "Stop"). Each time the rotator is turning towards 300 first.
  start(R"(, "n1mm.rotor_name": "teststack")");
  const std::string turn = n1mm_goazi("teststack", "300", "0", "0");
  for (const std::string& stop : {
           // nested, with the band (sconklin/netrotor's capture of N1MM+)
           std::string("<N1MMRotor><stop><rotor>teststack</rotor>"
                       "<freqband>14.0</freqband></stop></N1MMRotor>"),
           // a flag beside the heading (DK8DE/RotorTcpBridge)
           std::string("<N1MMRotor><rotor>teststack</rotor><goazi>123.4</goazi>"
                       "<stop>True</stop></N1MMRotor>"),
           // a flag and no rotor name at all: every rotator stops
           std::string("<N1MMRotor><stop>1</stop></N1MMRotor>"),
       }) {
    n1mm(turn);
    daemon->advance_ms(3000);
    ASSERT_TRUE(moving()) << stop;
    EXPECT_EQ(n1mm(stop).rfind("teststack @ ", 0), 0u) << stop;
    const std::string st = status();
    const std::size_t az_target_at = st.find("\"target_deg\"", st.find("\"az\""));
    EXPECT_EQ(st.find("\"target_deg\":null", az_target_at), az_target_at) << stop;
    daemon->advance_ms(10000);
    EXPECT_FALSE(moving()) << stop;
  }
  // <stop>False</stop> beside a heading is no stop: the heading is obeyed.
  n1mm("<N1MMRotor><rotor>teststack</rotor><goazi>45</goazi><stop>False</stop></N1MMRotor>");
  // A compass bearing: from near 300 the rotator takes it through the overlap.
  const double target = az_target();
  EXPECT_NEAR(std::fmod(target, 360.0), 45.0, 0.1);
  daemon->advance_ms(1000);
  EXPECT_TRUE(moving());
  // A nested stop for another rotor is that rotor's.
  client.send_to(n1mm_port,
                 "<N1MMRotor><stop><rotor>Tribander</rotor><freqband>14</freqband></stop>"
                 "</N1MMRotor>");
  ASSERT_TRUE(daemon->wait_for_output("for another rotor")) << daemon->output();
  EXPECT_NEAR(az_target(), target, 0.1);
}

TEST_F(UdpRotor, AReadOnlySenderIsRefusedEveryMoveButStopsTheRotator) {
  start();
  pst_then_az("<PST><AZIMUTH>100</AZIMUTH></PST>");
  daemon->advance_ms(3000);
  ASSERT_TRUE(moving());
  ASSERT_EQ(http(daemon->ports().web, "POST", "/api/settings",
                 R"({"access.control_networks": "10.0.0.0/8"})")
                .status,
            200);
  // The test runs on 127.0.0.1, outside the list.
  const std::string before = pst_then_az("<PST><AZIMUTH>300</AZIMUTH></PST>");
  ASSERT_TRUE(daemon->wait_for_output("refused (read-only sender)")) << daemon->output();
  EXPECT_NEAR(az_target(), 100.0, 0.1);
  EXPECT_NE(n1mm(n1mm_goazi("", "300", "0", "0")), "");  // the heading is still reported
  EXPECT_NEAR(az_target(), 100.0, 0.1);
  // It goes on towards 100, not 300; STOP from anyone halts it short of 100.
  daemon->advance_ms(3000);
  EXPECT_LT(std::stoi(pst_then_az("").substr(3)), std::stoi(before.substr(3)));
  pst_then_az("<PST><STOP>1</STOP></PST>");
  daemon->advance_ms(5000);
  const std::string stopped_at = pst_then_az("");
  daemon->advance_ms(10000);
  EXPECT_FALSE(moving());
  EXPECT_EQ(pst_then_az(""), stopped_at);
  EXPECT_NE(stopped_at, before);
  EXPECT_NE(stopped_at, "AZ:100\r");
}

TEST_F(UdpRotor, GarbageAndOversizeDatagramsAreIgnoredAndMoveNothing) {
  start();
  const std::string at_start = pst_then_az("");
  for (const std::string& junk :
       {std::string("<PST><AZIMUTH>abc</AZIMUTH></PST>"), std::string("\xff\xfe\x00\x01", 4),
        std::string("<PST><AZIMUTH>100</AZIMUTH><FOO>1</FOO></PST>"),
        std::string("<PST><AZIMUTH>100"), std::string(2000, '<')}) {
    client.send_to(pst_port, junk);
  }
  EXPECT_EQ(pst_then_az(""), at_start);  // still answering, in order
  client.send_to(n1mm_port, "<N1MMRotor><goazi>200</goazi><goazi>100</goazi></N1MMRotor>");
  client.send_to(n1mm_port,
                 "<N1MMRotor><goazi>100</goazi>" + std::string(600, ' ') + "</N1MMRotor>");
  // Garbage gets no answer; the stop after it does, once all were read.
  EXPECT_NE(n1mm("<N1MMRotor><stop></stop></N1MMRotor>").find(" @ "), std::string::npos);
  EXPECT_TRUE(daemon->wait_for_output("N1MM+ rotor (UDP): datagram from 127.0.0.1 too long"))
      << daemon->output();
  EXPECT_TRUE(daemon->wait_for_output("N1MM+ rotor (UDP): datagram from 127.0.0.1 malformed"));
  EXPECT_TRUE(daemon->wait_for_output("PstRotator UDP: datagram from 127.0.0.1 too long"));
  daemon->advance_ms(5000);
  EXPECT_FALSE(moving());
  EXPECT_EQ(pst_then_az(""), at_start);
  // Counted in GET /metrics by what became of them.
  const std::string metrics = http(daemon->ports().web, "GET", "/metrics").body;
  for (const char* line : {R"(rotord_udp_datagrams_total{protocol="pst",outcome="malformed"} 4)",
                           R"(rotord_udp_datagrams_total{protocol="pst",outcome="oversize"} 1)",
                           R"(rotord_udp_datagrams_total{protocol="n1mm",outcome="malformed"} 1)",
                           R"(rotord_udp_datagrams_total{protocol="n1mm",outcome="oversize"} 1)"})
    EXPECT_NE(metrics.find(line), std::string::npos) << line << "\n" << metrics;
}

}  // namespace
}  // namespace rotord::testing
