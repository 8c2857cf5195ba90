#include "protocol/easycomm_session.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "fake_rotator.hpp"
#include "string_sink.hpp"

namespace rotord::protocol {
namespace {

using testing::StringSink;

class EasycommTest : public ::testing::Test {
 protected:
  explicit EasycommTest(bool with_el = true) : r(with_el) { r.run_ms(50); }
  testing::FakeRotator r;
  EasycommSession session{*r.controller, "9.9.9"};
  int last_writes = 0;
  std::string ask(const std::string& bytes) {
    StringSink sink;
    session.receive(bytes, sink);
    last_writes = sink.writes;
    return sink.data;
  }
  RotatorStatus status() const { return r.controller->status(); }
  /// Turns the pot slowly (a sudden jump would be a sensor fault).
  void walk_az(float to_deg) {
    float deg = static_cast<float>(r.az.adc.counts) / 10.0f;
    // 0.4 deg a tick (40 deg/s), each reading within the robust filter's
    // gate (docs/care.md).
    while (deg != to_deg) {
      deg = deg < to_deg ? std::min(deg + 0.4f, to_deg) : std::max(deg - 0.4f, to_deg);
      r.az.set_deg(deg);
      r.run_ms(10);
    }
    r.run_ms(300);
  }
  bool idle_and_untargeted() const {
    const RotatorStatus s = status();
    return !s.az.has_target && !s.el.has_target && !s.az.jogging && !s.el.jogging;
  }
};

TEST_F(EasycommTest, CombinedQueryOfHamlib45IsOneLineWithASpaceBeforeEl) {
  EXPECT_EQ(ask("AZ EL \n"), "AZ100.0 EL20.0\n");
  EXPECT_EQ(last_writes, 1);  // one unit: one TCP segment
  EXPECT_EQ(ask("AZ EL\r\n"), "AZ100.0 EL20.0\n");
  EXPECT_EQ(ask("az el\r"), "AZ100.0 EL20.0\n");
}

TEST_F(EasycommTest, SeparateQueriesOfHamlib46) {
  EXPECT_EQ(ask("AZ\n"), "AZ100.0\n");
  EXPECT_EQ(ask("EL\n"), "EL20.0\n");
  EXPECT_EQ(ask("AZ\nEL\n"), "AZ100.0\nEL20.0\n");
}

TEST_F(EasycommTest, SetIsSilentAndOneGoToForBothAxes) {
  EXPECT_EQ(ask("AZ200.0 EL45.0\n"), "");
  EXPECT_TRUE(status().az.has_target);
  EXPECT_FLOAT_EQ(status().az.target_deg, 200.0f);
  EXPECT_FLOAT_EQ(status().el.target_deg, 45.0f);
  EXPECT_EQ(status().mode, Mode::kGoto);
  // Any number of decimals, integers, a single axis.
  EXPECT_EQ(ask("AZ150\n"), "");
  EXPECT_FLOAT_EQ(status().az.target_deg, 150.0f);
  EXPECT_EQ(ask("EL12.345\n"), "");
  EXPECT_FLOAT_EQ(status().el.target_deg, 12.345f);
}

TEST_F(EasycommTest, EasycommOneLineWithRadioFieldsSetsThePosition) {
  EXPECT_EQ(ask("AZ10.0 EL20.0 UP000 XXX DN000 XXX\n"), "");
  EXPECT_FLOAT_EQ(status().az.target_deg, 10.0f);
  EXPECT_FLOAT_EQ(status().el.target_deg, 20.0f);
  // A mode word never hides a following command.
  EXPECT_EQ(ask("UP145800000 FM AZ EL\n"), "AZ100.0 EL20.0\n");
  EXPECT_EQ(ask("UMFM DMUSB UR1 DR2 ST24:01:02:03:04:05 AO LO\n"), "");
}

TEST_F(EasycommTest, CompassTargetUsesTheOverlapAndReadsBackAsCompass) {
  walk_az(350);
  EXPECT_EQ(ask("AZ EL \n"), "AZ350.0 EL20.0\n");
  // From 350, 30 is nearest through the overlap: 390 unwrapped (travel 0..450).
  EXPECT_EQ(ask("AZ30.0 EL20.0\n"), "");
  EXPECT_FLOAT_EQ(status().az.target_deg, 390.0f);
  walk_az(390);
  EXPECT_EQ(ask("AZ EL \n"), "AZ30.0 EL20.0\n");
  EXPECT_EQ(ask("AZ\n"), "AZ30.0\n");
  // 360.0 (Hamlib sends it for 359.96) is north, the nearer turn from 390.
  EXPECT_EQ(ask("AZ360.0 EL180.0\n"), "");
  EXPECT_FLOAT_EQ(status().az.target_deg, 360.0f);
  EXPECT_FLOAT_EQ(status().el.target_deg, 180.0f);
}

TEST_F(EasycommTest, UnwrappedTargetsInsideTheTravelAreTakenOutsideRefused) {
  EXPECT_EQ(ask("AZ420.0\n"), "");
  EXPECT_FLOAT_EQ(status().az.target_deg, 420.0f);
  ask("SA SE\n");
  EXPECT_EQ(ask("AZ450.5 EL10\n"), "ALRANGE\n");
  EXPECT_EQ(ask("AZ-10.0 EL10\n"), "ALRANGE\n");
  EXPECT_EQ(ask("AZ10 EL180.1\n"), "ALRANGE\n");
  EXPECT_EQ(ask("AZ10 EL-1\n"), "ALRANGE\n");
  EXPECT_TRUE(idle_and_untargeted());
}

TEST_F(EasycommTest, PipelinedCommandsRunInOrder) {
  // Hamlib's writes coalesced in one TCP segment.
  EXPECT_EQ(ask("AZ10.0 EL20.0\nSA SE \nPARK\nML\n"), "");
  EXPECT_EQ(status().mode, Mode::kManual);
  EXPECT_TRUE(status().az.jogging);
  r.run_ms(500);
  EXPECT_TRUE(r.az.drive.ccw());
}

TEST_F(EasycommTest, PartialLinesWaitForTheirEnd) {
  EXPECT_EQ(ask("AZ E"), "");
  EXPECT_EQ(ask("L \n"), "AZ100.0 EL20.0\n");
  EXPECT_EQ(ask("AZ2"), "");
  EXPECT_FALSE(status().az.has_target);
  EXPECT_EQ(ask("00\n"), "");
  EXPECT_FLOAT_EQ(status().az.target_deg, 200.0f);
}

TEST_F(EasycommTest, StopAzimuthElevationOrBoth) {
  ask("AZ200 EL60\n");
  EXPECT_EQ(ask("SA\n"), "");
  EXPECT_FALSE(status().az.has_target);
  EXPECT_TRUE(status().el.has_target);
  ask("AZ200 EL60\n");
  EXPECT_EQ(ask("SE\n"), "");
  EXPECT_TRUE(status().az.has_target);
  EXPECT_FALSE(status().el.has_target);
  ask("AZ200 EL60\n");
  EXPECT_EQ(ask("SA SE \n"), "");
  EXPECT_TRUE(idle_and_untargeted());
  EXPECT_EQ(status().mode, Mode::kIdle);
}

TEST_F(EasycommTest, MoveCommandsJogEachDirection) {
  ask("MR\n");
  r.run_ms(500);
  EXPECT_TRUE(r.az.drive.cw());
  ask("SA\n");
  r.run_ms(2000);
  EXPECT_FALSE(r.az.drive.cw());
  ask("ML\n");
  r.run_ms(500);
  EXPECT_TRUE(r.az.drive.ccw());
  ask("MU\n");
  r.run_ms(500);
  EXPECT_TRUE(r.el.drive.cw());
  ask("SE\n");
  r.run_ms(2000);
  ask("MD\n");
  r.run_ms(500);
  EXPECT_TRUE(r.el.drive.ccw());
  EXPECT_EQ(ask("SA SE\n"), "");
  r.run_ms(2000);
  EXPECT_FALSE(r.az.drive.ccw());
  EXPECT_FALSE(r.el.drive.ccw());
}

TEST_F(EasycommTest, VelocityCommandsMoveLikeHamlib204) {
  EXPECT_EQ(ask("VL4900\n"), "");
  r.run_ms(500);
  EXPECT_TRUE(r.az.drive.ccw());
  EXPECT_EQ(ask("VR0000\n"), "");
  EXPECT_TRUE(status().az.jogging);
  EXPECT_EQ(ask("VU9900\n"), "");
  EXPECT_EQ(ask("VD5000\n"), "");
  EXPECT_TRUE(status().el.jogging);
  EXPECT_EQ(EasycommSession::speed_pct_from_velocity(0), 1);
  EXPECT_EQ(EasycommSession::speed_pct_from_velocity(4900), 50);
  EXPECT_EQ(EasycommSession::speed_pct_from_velocity(1233), 13);
  EXPECT_EQ(EasycommSession::speed_pct_from_velocity(9900), 100);
  EXPECT_EQ(EasycommSession::speed_pct_from_velocity(250000), 100);
}

TEST_F(EasycommTest, ParkAndReset) {
  r.settings.set(settings::Id::kParkAzDeg, 180);
  r.settings.set(settings::Id::kParkElDeg, 90);
  EXPECT_EQ(ask("PARK\n"), "");
  EXPECT_EQ(status().mode, Mode::kPark);
  EXPECT_FLOAT_EQ(status().az.target_deg, 180.0f);
  EXPECT_FLOAT_EQ(status().el.target_deg, 90.0f);
  r.controller->set_speed_pct(30);
  EXPECT_EQ(ask("RESET\n"), "");
  EXPECT_TRUE(idle_and_untargeted());
  EXPECT_EQ(status().speed_pct, 100);
}

TEST_F(EasycommTest, VersionStatusAndErrorRegisters) {
  EXPECT_EQ(ask("VE\n"), "VErotord-9.9.9\n");
  EXPECT_EQ(ask("GS\n"), "GS1\n");
  EXPECT_EQ(ask("GE\n"), "GE0\n");
  ask("AZ200\n");
  r.run_ms(500);
  EXPECT_EQ(ask("GS\n"), "GS2\n");
  walk_az(200);
  r.run_ms(3000);
  EXPECT_EQ(ask("GS\n"), "GS4\n");
  // Driven without the pot moving: a stall, which is Easycomm's "jam".
  ask("MR\n");
  r.run_ms(5000);
  EXPECT_EQ(ask("GE\n"), "GE2\n");
  EXPECT_EQ(ask("GS\n"), "GS9\n");
  EXPECT_EQ(ask("MR\n"), "ALFAULT\n");
  EXPECT_EQ(ask("AZ10\n"), "ALFAULT\n");
  EXPECT_EQ(ask("PARK\n"), "ALFAULT\n");
  ask("RESET\n");
  EXPECT_EQ(ask("GE\n"), "GE0\n");
}

TEST_F(EasycommTest, SensorFaultIsErrorBitOne) {
  r.az.adc.counts = 0;  // pot at its rail: sensor out of range
  r.run_ms(1000);
  EXPECT_EQ(ask("GE\n"), "GE1\n");
}

TEST_F(EasycommTest, ConfigRegistersReadAndWriteTheSettingsTable) {
  EXPECT_EQ(ask("CR 0\n"), "CR0,100\n");  // Hamlib writes "CR <register>"
  EXPECT_EQ(ask("CR0\n"), "CR0,100\n");
  EXPECT_EQ(ask("CRaz.max_deg\n"), "CRaz.max_deg,450\n");
  EXPECT_EQ(ask("CRaz.drive\n"), "CRaz.drive,relay\n");
  EXPECT_EQ(ask("CW7,12.5\n"), "");
  EXPECT_FLOAT_EQ(r.settings.f(settings::Id::kParkAzDeg), 12.5f);
  EXPECT_EQ(ask("CR7\n"), "CR7,12.5\n");
  EXPECT_EQ(ask("CW 8,45\n"), "");
  EXPECT_FLOAT_EQ(r.settings.f(settings::Id::kParkElDeg), 45.0f);
  EXPECT_EQ(ask("CWaz.coast_learn,false\n"), "");
  EXPECT_FALSE(r.settings.b(settings::Id::kAzCoastLearn));
  // Hamlib 4.5.4 appends a stray ';' after configuration commands.
  EXPECT_EQ(ask("GS\n;AZ EL \n"), "GS1\nAZ100.0 EL20.0\n");
}

TEST_F(EasycommTest, TextRegistersAndSecretsNeverReadBackNorWritten) {
  EXPECT_EQ(ask("CRtime.sntp_server\n"), "CRtime.sntp_server,pool.ntp.org\n");
  // Secrets and the access rules are written through the web only (issue 12).
  EXPECT_EQ(ask("CWwifi.password,hunter2-wpa2\n"), "ALDENIED\n");
  EXPECT_EQ(r.settings.text(settings::Id::kWifiPassword), "");
  EXPECT_EQ(ask("CWaccess.control_networks,0.0.0.0/0\n"), "ALDENIED\n");
  ASSERT_EQ(r.settings.set_text(settings::Id::kWifiPassword, "hunter2-wpa2").error, Error::kOk);
  EXPECT_EQ(ask("CRwifi.password\n"), "CRwifi.password,********\n");
  EXPECT_EQ(ask("CWwifi.password,********\n"), "ALDENIED\n");
  EXPECT_EQ(r.settings.text(settings::Id::kWifiPassword), "hunter2-wpa2");
  EXPECT_EQ(ask("CWnet.ipv4_address,10.0.0.300\n"), "ALRANGE\n");
  EXPECT_EQ(ask("CWnet.ipv4_mode,static\n"), "ALRANGE\n") << "no address: undone";
  EXPECT_EQ(r.settings.i(settings::Id::kNetIpv4Mode), 0);
}

TEST_F(EasycommTest, ConfigErrorsChangeNothing) {
  const auto revision = r.settings.revision();
  EXPECT_EQ(ask("CR\n"), "ALSYNTAX\n");
  EXPECT_EQ(ask("CRnope\n"), "ALUNKNOWN\n");
  EXPECT_EQ(ask("CR1\n"), "ALUNKNOWN\n");  // SatNOGS PID gains: no such thing here
  EXPECT_EQ(ask("CW0\n"), "ALSYNTAX\n");
  EXPECT_EQ(ask("CWnope,1\n"), "ALUNKNOWN\n");
  EXPECT_EQ(ask("CW0,101\n"), "ALRANGE\n");
  EXPECT_EQ(ask("CW0,fast\n"), "ALRANGE\n");
  EXPECT_EQ(revision, r.settings.revision());
  // A park azimuth outside the travel (0..450) is refused (issue 23 item 5).
  EXPECT_EQ(ask("CW7,500\n"), "ALRANGE\n");
  EXPECT_FLOAT_EQ(r.settings.f(settings::Id::kParkAzDeg), 0.0f);
  // In range alone but inconsistent with az.max_deg (450): rolled back.
  EXPECT_EQ(ask("CW7,400\n"), "");
  EXPECT_EQ(ask("CWaz.min_deg,360\n"), "");
  EXPECT_EQ(ask("CWaz.max_deg,300\n"), "ALRANGE\n");
  EXPECT_FLOAT_EQ(r.settings.f(settings::Id::kAzMaxDeg), 450.0f);
}

TEST_F(EasycommTest, BadInputGetsAnAlarmAndMovesNothing) {
  EXPECT_EQ(ask("AZ123.4EL45.6\n"), "ALSYNTAX\n");  // glibc would read an exponent
  EXPECT_EQ(ask("AZabc\n"), "ALSYNTAX\n");
  EXPECT_EQ(ask("AZ1e999\n"), "ALSYNTAX\n");
  EXPECT_EQ(ask("AZnan\n"), "ALSYNTAX\n");
  EXPECT_EQ(ask("ELx\n"), "ALSYNTAX\n");
  EXPECT_EQ(ask("ML5\n"), "ALSYNTAX\n");
  EXPECT_EQ(ask("SA1\n"), "ALSYNTAX\n");
  EXPECT_EQ(ask("SEx\n"), "ALSYNTAX\n");
  EXPECT_EQ(ask("VL\n"), "ALSYNTAX\n");
  EXPECT_EQ(ask("VR-100\n"), "ALSYNTAX\n");
  EXPECT_EQ(ask("VUfast\n"), "ALSYNTAX\n");
  // Issue 29 item 7: four digits exactly, as Hamlib's 204 writes "%04d".
  EXPECT_EQ(ask("VU999\n"), "ALSYNTAX\n");
  EXPECT_EQ(ask("VD-0\n"), "ALSYNTAX\n");
  EXPECT_EQ(ask("VL+100\n"), "ALSYNTAX\n");
  EXPECT_EQ(ask("VR10000\n"), "ALSYNTAX\n");
  EXPECT_FALSE(status().moving());
  EXPECT_EQ(ask("VEx\n"), "ALSYNTAX\n");
  EXPECT_EQ(ask("GSx\n"), "ALSYNTAX\n");
  EXPECT_EQ(ask("FOO\n"), "ALUNKNOWN\n");
  EXPECT_EQ(ask("X\n"), "ALUNKNOWN\n");
  EXPECT_EQ(ask("PARKING\n"), "ALUNKNOWN\n");
  EXPECT_EQ(ask(std::string("\0\xff\x01", 3) + "\n"), "ALUNKNOWN\n");
  // One bad token and the whole line is refused: the good set does not run.
  EXPECT_EQ(ask("AZ200.0 EL20.0 BOGUS\n"), "ALUNKNOWN\n");
  EXPECT_EQ(ask("MR ELx\n"), "ALSYNTAX\n");
  // Digital and analogue I/O channels do not exist here.
  EXPECT_EQ(ask("IP1\n"), "ALUNSUPPORTED\n");
  EXPECT_EQ(ask("OP1\n"), "ALUNSUPPORTED\n");
  EXPECT_EQ(ask("AN0\n"), "ALUNSUPPORTED\n");
  // A line longer than the buffer: one alarm, then the session works again.
  EXPECT_EQ(ask(std::string(10000, 'A') + "\nAZ EL\n"), "ALOVERFLOW\nAZ100.0 EL20.0\n");
  EXPECT_EQ(ask("\n\r\n \n;;\n"), "");  // empty lines are ignored
  EXPECT_TRUE(idle_and_untargeted());
  r.run_ms(500);
  EXPECT_FALSE(r.az.drive.cw() || r.az.drive.ccw() || r.el.drive.cw() || r.el.drive.ccw());
}

TEST_F(EasycommTest, MoveIntoALimitIsRefused) {
  walk_az(450);
  EXPECT_EQ(ask("MR\n"), "ALLIMIT\n");
  EXPECT_EQ(ask("VR5000\n"), "ALLIMIT\n");
  EXPECT_FALSE(status().az.jogging);
}

class EasycommAzOnlyTest : public EasycommTest {
 protected:
  EasycommAzOnlyTest() : EasycommTest(false) {}
};

TEST_F(EasycommAzOnlyTest, ElevationReadsZeroAndIsIgnoredOnSet) {
  EXPECT_EQ(ask("AZ EL \n"), "AZ100.0 EL0.0\n");
  EXPECT_EQ(ask("EL\n"), "EL0.0\n");
  EXPECT_EQ(ask("AZ200.0 EL45.0\n"), "");
  EXPECT_FLOAT_EQ(status().az.target_deg, 200.0f);
  EXPECT_EQ(ask("SE\n"), "");
  EXPECT_TRUE(status().az.has_target);
  EXPECT_EQ(ask("MU\n"), "ALUNSUPPORTED\n");
  EXPECT_EQ(ask("VD0100\n"), "ALUNSUPPORTED\n");
  EXPECT_EQ(ask("EL10\n"), "");  // nothing to do, nothing moves
}

}  // namespace
}  // namespace rotord::protocol
