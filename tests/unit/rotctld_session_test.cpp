// The rotctld byte session on a fake az/el rotator (az 0..450, el 0..180,
// at az 100 el 20). Expected bytes come from the real rotctld 4.5.4
// (docs/protocols/rotctld.md) unless a test says it checks a deviation.
#include "protocol/rotctld_session.hpp"

#include <gtest/gtest.h>

#include <string>

#include "fake_rotator.hpp"
#include "string_sink.hpp"

namespace rotord::protocol {
namespace {

using settings::Id;

using testing::StringSink;

class RotctldTest : public ::testing::Test {
 protected:
  explicit RotctldTest(bool with_el = true) : r(with_el) { r.run_ms(50); }

  std::string ask(const std::string& bytes) {
    StringSink sink;
    session.receive(bytes, sink);
    last_writes = sink.writes;
    return sink.data;
  }
  const RotatorStatus status() const { return r.controller->status(); }
  /// Turns an axis by hand in small steps (a jump would latch a sensor fault).
  void walk(testing::FakeAxisHardware& axis, float from_deg, float to_deg) {
    // 0.4 deg a tick (40 deg/s), each reading within the robust filter's
    // gate (docs/care.md); a bigger step at once is a sensor fault.
    const float step = from_deg < to_deg ? 0.4f : -0.4f;
    for (float deg = from_deg; (step > 0) ? deg < to_deg : deg > to_deg; deg += step) {
      axis.set_deg(deg);
      r.run_ms(10);
    }
    axis.set_deg(to_deg);
    r.run_ms(100);
  }

  testing::FakeRotator r;
  RotctldSession session{*r.controller, "9.9.9"};
  int last_writes = 0;
};

class RotctldAzOnlyTest : public RotctldTest {
 protected:
  RotctldAzOnlyTest() : RotctldTest(false) {}
};

constexpr const char* kDumpState =
    "1\n1\nmin_az=0.000000\nmax_az=450.000000\nmin_el=0.000000\nmax_el=180.000000\n"
    "south_zero=0\nrot_type=AzEl\ndone\n";

// ---- get and set commands, default protocol --------------------------------

TEST_F(RotctldTest, DumpStateReportsTheRealLimitsWithFlipElevation) {
  EXPECT_EQ(ask("\\dump_state\n"), kDumpState);
  EXPECT_EQ(last_writes, 1);
  // The raw internal code 0x8f is dump_state too.
  EXPECT_EQ(ask("\x8f\n"), kDumpState);
}

TEST_F(RotctldTest, DumpStateFollowsTheSettings) {
  r.settings.set(Id::kAzMinDeg, -180);
  r.settings.set(Id::kAzMaxDeg, 540);
  r.settings.set(Id::kElMaxDeg, 90);
  r.run_ms(20);
  EXPECT_EQ(ask("\\dump_state\n"),
            "1\n1\nmin_az=-180.000000\nmax_az=540.000000\nmin_el=0.000000\nmax_el=90.000000\n"
            "south_zero=0\nrot_type=AzEl\ndone\n");
}

TEST_F(RotctldAzOnlyTest, AzimuthOnlyRotatorAcceptsAndIgnoresElevation) {
  EXPECT_EQ(ask("\\dump_state\n"),
            "1\n1\nmin_az=0.000000\nmax_az=450.000000\nmin_el=0.000000\nmax_el=90.000000\n"
            "south_zero=0\nrot_type=Az\ndone\n");
  EXPECT_EQ(ask("p\n"), "100.00\n0.00\n");
  EXPECT_EQ(ask("P 200 20\n"), "RPRT 0\n");
  EXPECT_FLOAT_EQ(status().az.target_deg, 200.0f);
  EXPECT_EQ(ask("P 200 91\n"), "RPRT -1\n");
  EXPECT_EQ(ask("M UP 50\n"), "RPRT -11\n");  // RIG_ENAVAIL: no elevation axis
  EXPECT_EQ(ask("+\\dump_caps\n").find("Rot type:\t\tAz\n") != std::string::npos, true);
}

TEST_F(RotctldTest, GetPosIsTwoLinesWithTwoDecimals) {
  EXPECT_EQ(ask("p\n"), "100.00\n20.00\n");
  EXPECT_EQ(last_writes, 1);
  EXPECT_EQ(ask("\\get_pos\n"), "100.00\n20.00\n");
}

TEST_F(RotctldTest, SetPosTakesUnwrappedAzimuthsAndFlipElevations) {
  EXPECT_EQ(ask("P 420 150\n"), "RPRT 0\n");
  EXPECT_FLOAT_EQ(status().az.target_deg, 420.0f);  // not 60
  EXPECT_FLOAT_EQ(status().el.target_deg, 150.0f);
  EXPECT_EQ(ask("P 60 10\n"), "RPRT 0\n");
  EXPECT_FLOAT_EQ(status().az.target_deg, 60.0f);  // not 420
  EXPECT_EQ(ask("\\set_pos 450 180\n"), "RPRT 0\n");
  EXPECT_FLOAT_EQ(status().az.target_deg, 450.0f);
  EXPECT_FLOAT_EQ(status().el.target_deg, 180.0f);
  EXPECT_EQ(ask("P 0 0\n"), "RPRT 0\n");
}

TEST_F(RotctldTest, SetPosNumberFormats) {
  EXPECT_EQ(ask("P 10,5 20,5\n"), "RPRT 0\n");  // Gpredict in a comma locale
  EXPECT_FLOAT_EQ(status().az.target_deg, 10.5f);
  EXPECT_FLOAT_EQ(status().el.target_deg, 20.5f);
  EXPECT_EQ(ask("P +11.250000 +21.000000\n"), "RPRT 0\n");
  EXPECT_FLOAT_EQ(status().az.target_deg, 11.25f);
  EXPECT_EQ(ask("P 1.2e2 3e1\n"), "RPRT 0\n");
  EXPECT_FLOAT_EQ(status().az.target_deg, 120.0f);
  EXPECT_EQ(ask("P 12abc 22\n"), "RPRT 0\n");  // sscanf("%f") reads the prefix
  EXPECT_FLOAT_EQ(status().az.target_deg, 12.0f);
}

TEST_F(RotctldTest, SetPosOutsideTheLimitsIsRefusedAndMovesNothing) {
  for (const char* bad :
       {"P 450.01 10\n", "P -0.5 10\n", "P 10 180.5\n", "P 10 -1\n", "P 500 20\n", "P abc 20\n",
        "P 10 x\n", "P inf 20\n", "P nan 20\n", "P 0x10 20\n", "P - 20\n", "P . 20\n", "P ?\n"}) {
    EXPECT_EQ(ask(bad), "RPRT -1\n") << bad;
  }
  EXPECT_FALSE(status().az.has_target);
  EXPECT_FALSE(status().el.has_target);
  r.run_ms(200);
  EXPECT_FALSE(r.az.drive.cw() || r.az.drive.ccw());
}

TEST_F(RotctldTest, StopParkResetMove) {
  EXPECT_EQ(ask("P 300 60\n"), "RPRT 0\n");
  EXPECT_EQ(ask("S\n"), "RPRT 0\n");
  EXPECT_FALSE(status().az.has_target);
  r.settings.set(Id::kParkAzDeg, 180);
  r.settings.set(Id::kParkElDeg, 90);
  EXPECT_EQ(ask("K\n"), "RPRT 0\n");
  EXPECT_EQ(status().mode, Mode::kPark);
  EXPECT_FLOAT_EQ(status().az.target_deg, 180.0f);
  EXPECT_FLOAT_EQ(status().el.target_deg, 90.0f);
  EXPECT_EQ(ask("\\stop\n"), "RPRT 0\n");
  EXPECT_EQ(ask("\\park\n"), "RPRT 0\n");
  EXPECT_EQ(ask("R 1\n"), "RPRT 0\n");
  EXPECT_EQ(status().mode, Mode::kIdle);
  EXPECT_EQ(ask("\\reset 1\n"), "RPRT 0\n");
  EXPECT_EQ(ask("R abc\n"), "RPRT -1\n");
  EXPECT_EQ(ask("R\n1\n"), "RPRT 0\n");  // the argument on the next line
}

TEST_F(RotctldTest, MoveDirectionsAndSpeeds) {
  EXPECT_EQ(ask("M 16 50\n"), "RPRT 0\n");
  EXPECT_TRUE(status().az.jogging);
  r.run_ms(100);
  EXPECT_TRUE(r.az.drive.cw());
  EXPECT_EQ(ask("S\n"), "RPRT 0\n");
  EXPECT_EQ(ask("M CCW -1\n"), "RPRT 0\n");
  EXPECT_TRUE(status().az.jogging);
  EXPECT_EQ(ask("S\n"), "RPRT 0\n");
  EXPECT_EQ(ask("M UP 100\n"), "RPRT 0\n");
  EXPECT_TRUE(status().el.jogging);
  EXPECT_EQ(ask("\\move 4 1\n"), "RPRT 0\n");
  for (const char* ok :
       {"M 2 50\n", "M 8 50\n", "M LEFT 1\n", "M RIGHT 100\n", "M CW 5\n", "M DOWN 5\n"}) {
    EXPECT_EQ(ask("S\n"), "RPRT 0\n");
    EXPECT_EQ(ask(ok), "RPRT 0\n") << ok;
  }
  EXPECT_EQ(ask("S\n"), "RPRT 0\n");
  for (const char* bad : {"M 3 50\n", "M 1 50\n", "M 32 50\n", "M 8 0\n", "M 8 101\n", "M 8 -2\n",
                          "M left 50\n", "M FOO 50\n", "M 8 x\n"}) {
    EXPECT_EQ(ask(bad), "RPRT -1\n") << bad;
  }
  EXPECT_FALSE(status().az.jogging);
  EXPECT_FALSE(status().el.jogging);
}

TEST_F(RotctldTest, SpeedLevel) {
  EXPECT_EQ(ask("V SPEED 42\n"), "RPRT 0\n");
  EXPECT_EQ(status().speed_pct, 42);
  EXPECT_EQ(ask("v SPEED\n"), "42\n");
  EXPECT_EQ(ask("\\set_level SPEED 7\n"), "RPRT 0\n");
  EXPECT_EQ(ask("\\get_level SPEED\n"), "7\n");
  EXPECT_EQ(ask("V SPEED 0\n"), "RPRT -1\n");
  EXPECT_EQ(ask("V SPEED 101\n"), "RPRT -1\n");
  EXPECT_EQ(ask("V SPEED fast\n"), "RPRT -1\n");
  EXPECT_EQ(ask("V FOO 1\n"), "RPRT -11\n");
  EXPECT_EQ(ask("v FOO\n"), "RPRT -1\n");
  EXPECT_EQ(ask("V ?\n"), "SPEED \nRPRT 0\n");
  EXPECT_EQ(ask("v ?\n"), "SPEED \n");
  EXPECT_EQ(status().speed_pct, 7);
}

TEST_F(RotctldTest, NoFunctionsOrParameters) {
  EXPECT_EQ(ask("U ?\n"), "\nRPRT 0\n");
  EXPECT_EQ(ask("u ?\n"), "\n");
  EXPECT_EQ(ask("X ?\n"), "\nRPRT 0\n");
  EXPECT_EQ(ask("x ?\n"), "\n");
  EXPECT_EQ(ask("U MGEF 1\n"), "RPRT -11\n");
  EXPECT_EQ(ask("u MGEF\n"), "RPRT -1\n");
  EXPECT_EQ(ask("X MGP 0.5\n"), "RPRT -1\n");
  EXPECT_EQ(ask("\\get_parm MGP\n"), "RPRT -1\n");
}

TEST_F(RotctldTest, SetConfChangesTheLimitsDumpStateReports) {
  EXPECT_EQ(ask("C min_az -90\n"), "RPRT 0\n");
  EXPECT_FLOAT_EQ(r.settings.f(Id::kAzMinDeg), -90.0f);
  r.run_ms(20);  // the controller applies changed settings on its next tick
  EXPECT_EQ(ask("\\dump_state\n").substr(0, 24), "1\n1\nmin_az=-90.000000\nma");
  EXPECT_EQ(ask("\\set_conf max_el 90\n"), "RPRT 0\n");
  EXPECT_EQ(ask("C park.az_deg 180\n"), "RPRT 0\n");  // any settings key
  EXPECT_FLOAT_EQ(r.settings.f(Id::kParkAzDeg), 180.0f);
  EXPECT_EQ(ask("C south_zero 0\n"), "RPRT 0\n");
  EXPECT_EQ(ask("C south_zero 1\n"), "RPRT -1\n");
  EXPECT_EQ(ask("C foo 1\n"), "RPRT -1\n");
  EXPECT_EQ(ask("C min_az abc\n"), "RPRT -1\n");
  EXPECT_EQ(ask("C max_az 5000\n"), "RPRT -1\n");
  EXPECT_EQ(ask("C min_az 450\n"), "RPRT -1\n");  // not below max_az: kept
  EXPECT_FLOAT_EQ(r.settings.f(Id::kAzMinDeg), -90.0f);
  EXPECT_EQ(ask("C ?\n"), "RPRT -1\n");
}

TEST_F(RotctldTest, GetConfAsHamlib46) {
  EXPECT_EQ(ask("\\get_conf min_az\n"), "min_az=0.000000\n");
  EXPECT_EQ(ask("\\get_conf max_el\n"), "max_el=180.000000\n");
  EXPECT_EQ(ask("\\get_conf south_zero\n"), "south_zero=0\n");
  EXPECT_EQ(ask("\\get_conf speed_pct\n"), "RPRT -1\n");
  EXPECT_EQ(ask("\\get_conf rotator.speed_pct\n"), "rotator.speed_pct=100\n");
  EXPECT_EQ(ask("\\get_conf foo\n"), "RPRT -1\n");
  EXPECT_EQ(ask("\\get_conf ?\n"), "min_az max_az min_el max_el south_zero \n");
  EXPECT_EQ(ask("+\\get_conf max_az\n"), "get_conf: max_az\nmax_az=450.000000\nRPRT 0\n");
}

TEST_F(RotctldTest, InfoStatusSendCmdDumpCaps) {
  EXPECT_EQ(ask("_\n"), "rotord 9.9.9\n");
  EXPECT_EQ(ask("\\get_info\n"), "rotord 9.9.9\n");
  EXPECT_EQ(ask("s\n"), "\n");  // idle, inside 0..360 and 0..90: no flags
  EXPECT_EQ(ask("w XYZ\n"), "RPRT -6\n");
  EXPECT_EQ(ask("\\send_cmd XYZ\n"), "RPRT -6\n");
  EXPECT_EQ(ask("w\nXYZ\n"), "RPRT -6\n");  // fgets skips the bare line end
  const std::string caps = ask("1\n");
  EXPECT_EQ(last_writes, 1);
  EXPECT_EQ(caps.rfind("Caps dump for model:\t1\n", 0), 0u) << caps;
  EXPECT_NE(caps.find("Max Elevation:\t\t180.00\n"), std::string::npos) << caps;
  EXPECT_EQ(caps.substr(caps.size() - 36), "\nOverall backend warnings: 0\nRPRT 0\n");
  EXPECT_EQ(ask("\\dump_caps\n"), caps);
}

TEST_F(RotctldTest, StatusFlagsInHamlibBitOrder) {
  EXPECT_EQ(ask("M RIGHT 50\n"), "RPRT 0\n");
  r.run_ms(100);
  EXPECT_EQ(ask("s\n"), "MOVING MOVING_AZ MOVING_RIGHT \n");
  EXPECT_EQ(ask("S\n"), "RPRT 0\n");
  r.run_ms(3000);
  EXPECT_EQ(ask("M DOWN 50\n"), "RPRT 0\n");
  r.run_ms(100);
  EXPECT_EQ(ask("\\get_status\n"), "MOVING MOVING_EL MOVING_DOWN \n");
  EXPECT_EQ(ask("S\n"), "RPRT 0\n");
  r.run_ms(3000);
  walk(r.az, 100, 400);
  walk(r.el, 20, 150);
  EXPECT_EQ(ask("s\n"), "OVERLAP_UP OVERLAP_RIGHT \n");
  EXPECT_EQ(ask("+s\n"), "get_status:\nStatus flags: OVERLAP_UP OVERLAP_RIGHT \nRPRT 0\n");
}

TEST_F(RotctldTest, LimitFlagsAtTheEnds) {
  walk(r.az, 100, 450);
  walk(r.el, 20, 180);
  EXPECT_EQ(ask("s\n"), "LIMIT_UP LIMIT_RIGHT OVERLAP_UP OVERLAP_RIGHT \n");
}

TEST_F(RotctldTest, LocatorHelpersAsRotctl) {
  EXPECT_EQ(ask("L 2.0 51.0 6\n"), "JO11AA\n");
  EXPECT_EQ(ask("l JO01aa\n"), "0.041667\n51.020833\n");
  EXPECT_EQ(ask("B 0 51 2 52\n"), "177.564346\n50.000000\n");
  EXPECT_EQ(ask("A 10\n"), "190.000000\n");
  EXPECT_EQ(ask("a 100\n"), "39932.000000\n");
  EXPECT_EQ(ask("D 51 30 0 0\n"), "51.500000\n");
  EXPECT_EQ(ask("d 51.5\n"), "51\n30\n0.000000\n0\n");
  EXPECT_EQ(ask("d -96.8333\n"), "96\n49\n59.880000\n1\n");
  EXPECT_EQ(ask("d 270\n"), "90\n0\n0.000000\n1\n");
  EXPECT_EQ(ask("E 51 30.5 0\n"), "51.508333\n");
  EXPECT_EQ(ask("e 51.5\n"), "51\n30.000000\n0\n");
  EXPECT_EQ(ask("+L 2 51 6\n"), "lonlat2loc: 2 51 6\nLocator: JO11AA\nRPRT 0\n");
  EXPECT_EQ(ask(";l JO01aa\n"),
            "loc2lonlat: JO01aa;Longitude: 0.041667;Latitude: 51.020833;RPRT 0\n");
  EXPECT_EQ(ask("B 0 0 180 0\n"), "20016.000000\n0.000000\n");  // antipodes
  EXPECT_EQ(ask("L 2 51 12\n"), "JO11AA00AA00\n");
  for (const char* bad : {"L 2 51 1\n", "L 2 51 14\n", "l ZZ\n", "l J\n", "A 400\n", "A -5\n",
                          "B 0 91 0 0\n", "D x 1 1 0\n"}) {
    EXPECT_EQ(ask(bad), "RPRT -1\n") << bad;
  }
}

// ---- Extended Response Protocol ---------------------------------------------

TEST_F(RotctldTest, ExtendedResponses) {
  EXPECT_EQ(ask("+p\n"), "get_pos:\nAzimuth: 100.00\nElevation: 20.00\nRPRT 0\n");
  EXPECT_EQ(last_writes, 1);
  EXPECT_EQ(ask(";p\n"), "get_pos:;Azimuth: 100.00;Elevation: 20.00;RPRT 0\n");
  EXPECT_EQ(ask("+\\get_pos\n"), "get_pos:\nAzimuth: 100.00\nElevation: 20.00\nRPRT 0\n");
  EXPECT_EQ(ask("|P 1 2\n"), "set_pos: 1 2|RPRT 0\n");
  EXPECT_EQ(ask("+P 10 500\n"), "set_pos: 10 500\nRPRT -1\n");
  EXPECT_EQ(ask("+P 10,5 20,5\n"), "set_pos: 10,5 20,5\nRPRT 0\n");  // echoed as typed
  EXPECT_EQ(ask("+S\n"), "stop:\nRPRT 0\n");
  EXPECT_EQ(ask("+K\n"), "park:\nRPRT 0\n");
  EXPECT_EQ(ask("+R 1\n"), "reset: 1\nRPRT 0\n");
  EXPECT_EQ(ask("+M 8 50\n"), "move: 8 50\nRPRT 0\n");
  EXPECT_EQ(ask("+\\move RIGHT 10\n"), "move: RIGHT 10\nRPRT 0\n");
  EXPECT_EQ(ask("+_\n"), "get_info:\nInfo: rotord 9.9.9\nRPRT 0\n");
  EXPECT_EQ(ask("+v SPEED\n"), "get_level: SPEED\n100\nRPRT 0\n");  // bare value, as rotctld
  EXPECT_EQ(ask("+V SPEED 2\n"), "set_level: SPEED 2\nRPRT 0\n");
  EXPECT_EQ(ask("+C foo 1\n"), "set_conf: foo 1\nRPRT -1\n");
  EXPECT_EQ(ask("+w XYZ\n"), "send_cmd: XYZ\nRPRT -6\n");
  EXPECT_EQ(ask("+\\dump_state\n"),
            "dump_state:\nrotctld Protocol Ver: 1\nRotor Model: 1\nMinimum Azimuth: 0.000000\n"
            "Maximum Azimuth: 450.000000\nMinimum Elevation: 0.000000\n"
            "Maximum Elevation: 180.000000\nSouth Zero: 0\nrot_type=AzEl\ndone\nRPRT 0\n");
  EXPECT_EQ(ask(";\\dump_state\n"),
            "dump_state:;rotctld Protocol Ver: 1;Rotor Model: 1;Minimum Azimuth: 0.000000;"
            "Maximum Azimuth: 450.000000;Minimum Elevation: 0.000000;"
            "Maximum Elevation: 180.000000;South Zero: 0;rot_type=AzEl;done;RPRT 0\n");
  const std::string caps = ask("+1\n");
  EXPECT_EQ(caps.rfind("dump_caps:\nCaps dump for model:", 0), 0u);
}

TEST_F(RotctldTest, EveryPunctuationSeparator) {
  // Every ASCII punctuation but '\', '_' and '#', '?' included.
  for (char sep : std::string("!\"$%&'()*+,-./:;<=>?@[]^`{|}~")) {
    if (sep == '+') continue;  // '+' is the newline form, tested below
    const std::string s(1, sep);
    EXPECT_EQ(ask(s + "S\n"), "stop:" + s + "RPRT 0\n") << sep;
  }
  EXPECT_EQ(ask("+S\n"), "stop:\nRPRT 0\n");
  EXPECT_EQ(ask("++S\n"), "stop:+RPRT 0\n");  // '+' then a separator
  EXPECT_EQ(ask("+;S\n"), "stop:;RPRT 0\n");
  EXPECT_EQ(ask("?_\n"), "get_info:?Info: rotord 9.9.9?RPRT 0\n");
}

// ---- stream parsing ------------------------------------------------------------

TEST_F(RotctldTest, LineEndsAndPipelining) {
  EXPECT_EQ(ask("P 11.5 21.5\r\n"), "RPRT 0\n");
  EXPECT_EQ(ask("P 12 22\r"), "RPRT 0\n");
  EXPECT_EQ(ask("S\r\nS\r\n"), "RPRT 0\nRPRT 0\n");
  EXPECT_EQ(last_writes, 2);  // one write per reply
  EXPECT_EQ(ask("p\np\n"), "100.00\n20.00\n100.00\n20.00\n");
  EXPECT_EQ(ask("\n\r\n\r"), "");
  EXPECT_EQ(ask(" p\n"), "100.00\n20.00\n");
  EXPECT_EQ(ask("\tp\n"), "100.00\n20.00\n");
  EXPECT_EQ(ask("#comment P 1 2\np\n"), "100.00\n20.00\n");
  EXPECT_EQ(ask("S K S\n"), "RPRT 0\nRPRT 0\nRPRT 0\n");
  EXPECT_EQ(ask("+\np\n"), "100.00\n20.00\n");  // a lone prefix is dropped
}

TEST_F(RotctldTest, CommandsSplitAcrossPacketsAndLines) {
  EXPECT_EQ(ask("P 1"), "");
  EXPECT_EQ(ask("0 20\n"), "RPRT 0\n");
  EXPECT_FLOAT_EQ(status().az.target_deg, 10.0f);
  EXPECT_EQ(ask("P\n15\n25\n"), "RPRT 0\n");
  EXPECT_FLOAT_EQ(status().az.target_deg, 15.0f);
  EXPECT_EQ(ask("P 10\n"), "");  // rotctld waits for the second argument
  EXPECT_EQ(ask("30\n"), "RPRT 0\n");
  EXPECT_FLOAT_EQ(status().el.target_deg, 30.0f);
  EXPECT_EQ(ask("\\dump_"), "");
  EXPECT_EQ(ask("state\n"), kDumpState);
  EXPECT_EQ(ask("+"), "");
  EXPECT_EQ(ask("p\n"), "get_pos:\nAzimuth: 100.00\nElevation: 20.00\nRPRT 0\n");
  std::string all;
  for (char c : std::string("M\n8\n50\n")) all += ask(std::string(1, c));
  EXPECT_EQ(all, "RPRT 0\n");
}

TEST_F(RotctldTest, QuitClosesWithoutAReply) {
  EXPECT_FALSE(session.wants_close());
  EXPECT_EQ(ask("q\nP 300 20\n"), "");
  EXPECT_TRUE(session.wants_close());
  EXPECT_FALSE(status().az.has_target);
}

TEST_F(RotctldTest, UpperCaseQuitAndQuitAfterAPrefix) {
  EXPECT_EQ(ask("p\nQ\n"), "100.00\n20.00\n");
  EXPECT_TRUE(session.wants_close());
}

// ---- errors and bad input ----------------------------------------------------

TEST_F(RotctldTest, UnknownCommandsGetAnErrorNotSilence) {
  // Deviation: rotctld says nothing; we answer RPRT -4 (RIG_ENIMPL) once and
  // skip the rest of the line.
  EXPECT_EQ(ask("Z\n"), "RPRT -4\n");
  EXPECT_EQ(ask("\\foo\n"), "RPRT -4\n");
  EXPECT_EQ(ask("+Z\n"), "RPRT -4\n");
  EXPECT_EQ(ask("+\\foo\n"), "RPRT -4\n");
  EXPECT_EQ(ask("\\foo K S\np\n"), "RPRT -4\n100.00\n20.00\n");  // K and S not run
  EXPECT_EQ(ask("p 99\n"), "100.00\n20.00\nRPRT -4\n");
  EXPECT_EQ(ask("\\\n"), "RPRT -4\n");
  EXPECT_EQ(ask("\\" + std::string(40, 'a') + "\n"), "RPRT -4\n");
  EXPECT_EQ(status().mode, Mode::kIdle);
  EXPECT_FALSE(status().az.has_target);
}

TEST_F(RotctldTest, GarbageNeverMovesAnythingAndTheSessionRecovers) {
  const char bytes[] = "\x00\x01\xff\xfe\x80\x00 Zq\x00\n\x07\x1b[2J\n\x00\x00\x00\n";
  const std::string garbage(bytes, sizeof(bytes) - 1);
  const std::string reply = ask(garbage);
  EXPECT_EQ(reply, "RPRT -4\nRPRT -4\nRPRT -4\n");
  EXPECT_FALSE(session.wants_close());
  // A 1 MB line costs one reply and no memory.
  EXPECT_EQ(ask(std::string(1 << 20, 'z') + "\n"), "RPRT -4\n");
  // ('x' would be get_parm with a 1 MB argument: refused the same way.)
  EXPECT_EQ(ask(std::string(1 << 20, 'x') + "\n"), "RPRT -1\n");
  // A 1 MB argument: refused once it ends.
  EXPECT_EQ(ask("P " + std::string(1 << 20, '1') + " 20\n"), "RPRT -1\n");
  EXPECT_EQ(ask("C " + std::string(300, 'a') + " 1\n"), "RPRT -1\n");
  EXPECT_EQ(status().mode, Mode::kIdle);
  EXPECT_FALSE(status().az.has_target);
  EXPECT_FALSE(status().el.has_target);
  EXPECT_EQ(ask("p\n"), "100.00\n20.00\n");
}

TEST_F(RotctldTest, AThousandCommandsInOnePacket) {
  std::string many;
  for (int i = 0; i < 1000; ++i) many += "p\n";
  const std::string reply = ask(many);
  EXPECT_EQ(last_writes, 1000);
  EXPECT_EQ(reply.size(), 1000u * 13u);
}

TEST_F(RotctldTest, FaultsAreRejected) {
  r.az.set_deg(0);  // the pot at its rail: a sensor fault latches
  r.run_ms(500);
  ASSERT_TRUE(status().any_fault());
  EXPECT_EQ(ask("P 200 20\n"), "RPRT -9\n");  // RIG_ERJCTED
  EXPECT_EQ(ask("K\n"), "RPRT -9\n");
  EXPECT_EQ(ask("M CW 50\n"), "RPRT -9\n");
  EXPECT_FALSE(status().az.has_target);
  // The last good reading is still reported (Gpredict keeps its display);
  // the fault shows in the refused commands.
  EXPECT_EQ(ask("p\n"), "100.00\n20.00\n");
  r.az.set_deg(100);
  r.run_ms(100);
  EXPECT_EQ(ask("R 1\n"), "RPRT 0\n");
  r.run_ms(100);
  EXPECT_EQ(ask("P 200 20\n"), "RPRT 0\n");
}

TEST_F(RotctldTest, PauseHoldsTheReplyAndLaterInput) {
  EXPECT_EQ(ask("\\pause 0\n"), "RPRT 0\n");
  EXPECT_EQ(ask("\\pause 61\n"), "RPRT -1\n");
  EXPECT_EQ(ask("\\pause 2\np\n"), "");
  EXPECT_EQ(ask("_\n"), "");
  StringSink sink;
  session.poll(r.now, sink);  // the transport's next poll starts the pause
  r.run_ms(1000);
  session.poll(r.now, sink);
  EXPECT_EQ(sink.data, "");
  r.run_ms(1000);
  session.poll(r.now, sink);
  EXPECT_EQ(sink.data, "RPRT 0\n100.00\n20.00\nrotord 9.9.9\n");
  EXPECT_EQ(ask("p\n"), "100.00\n20.00\n");
}

TEST_F(RotctldTest, PauseOnAFreshConnectionLastsItsSecondsFromWhenItArrives) {
  // Issue 23 item 1: a session that has not been polled yet took its deadline
  // from transport time 0, so on a daemon up for a while it ended at once.
  StringSink sink;
  const Millis uptime_ms = 3000;
  EXPECT_EQ(ask("\\pause 2\n"), "");
  session.poll(uptime_ms, sink);
  session.poll(uptime_ms + 10, sink);
  session.poll(uptime_ms + 1990, sink);
  EXPECT_EQ(sink.data, "");
  session.poll(uptime_ms + 2000, sink);
  EXPECT_EQ(sink.data, "RPRT 0\n");
}

TEST_F(RotctldTest, OldClientsSettingAddsThePositionalLimitsBeforeTheTags) {
  // Issue 23 item 2: Hamlib before 4.5.1 reads lines 3-6 with atof; 4.5.1
  // and later skip lines without '=' and read the tags.
  r.settings.set(Id::kRotctldOldClients, 1);
  EXPECT_EQ(ask("\\dump_state\n"),
            "1\n1\n0.000000\n450.000000\n0.000000\n180.000000\n"
            "min_az=0.000000\nmax_az=450.000000\nmin_el=0.000000\nmax_el=180.000000\n"
            "south_zero=0\nrot_type=AzEl\ndone\n");
  EXPECT_EQ(last_writes, 1);
  // The extended form is for people and stays as it was.
  r.settings.set(Id::kRotctldOldClients, 0);
  const std::string extended = ask("+\\dump_state\n");
  r.settings.set(Id::kRotctldOldClients, 1);
  EXPECT_EQ(ask("+\\dump_state\n"), extended);
}

TEST_F(RotctldTest, DumpConfAnswersAsHamlib46sRotctld) {
  // rotctld 4.6 prints the list on its own stdout and the client gets RPRT 0.
  EXPECT_EQ(ask("\\dump_conf\n"), "RPRT 0\n");
  EXPECT_EQ(ask("3\n"), "RPRT 0\n");
  EXPECT_EQ(ask("+\\dump_conf\n"), "dump_conf:\nRPRT 0\n");
}

TEST_F(RotctldTest, IntegerArgumentsMustBeWholeIntegers) {
  // Issue 29 item 7: sscanf("%d") would read 1, 60, 3 and 1.
  for (const char* bad : {"\\pause 1e9\n", "\\pause 60.5\n", "\\pause 3abc\n", "M 16 1e400\n",
                          "M 16 50.5\n", "M 16x 50\n", "V SPEED 2.5\n", "R 1x\n"}) {
    EXPECT_EQ(ask(bad), "RPRT -1\n") << bad;
  }
  EXPECT_FALSE(status().moving());
  EXPECT_EQ(ask("M 16 +50\n"), "RPRT 0\n");
  EXPECT_EQ(ask("S\n"), "RPRT 0\n");
}

}  // namespace
}  // namespace rotord::protocol
