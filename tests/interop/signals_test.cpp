// Signals while the rotator moves (issue 12): every catchable signal that
// would end rotord stops the motors first, through the controller's STOP
// and the driver, and rotord exits 0 saying what the driver's outputs were
// left at; SIGPIPE is ignored. The simulated G-5500 on the manual clock, so
// "moving" is a known state, not a race with the wall clock.
#include <gtest/gtest.h>
#include <signal.h>

#include <memory>
#include <string>
#include <vector>

#include "daemon_process.hpp"

namespace rotord::testing {
namespace {

class SignalWhileMoving : public ::testing::TestWithParam<int> {
 protected:
  /// A daemon with the azimuth turning CW and the elevation turning UP.
  void start_moving() {
    daemon = std::make_unique<DaemonProcess>(std::vector<std::string>{"--clock", "manual"});
    ASSERT_TRUE(daemon->ready()) << daemon->output();
    TcpClient wrc(daemon->ports().wrc);
    ASSERT_EQ(wrc.ask("AZ 400\n"), "OK AZ 400.00");
    ASSERT_EQ(wrc.ask("EL 90\n"), "OK EL 90.00");
    ASSERT_GT(daemon->advance_ms(2000), 0);
    const std::string state = wrc.ask("STATE\n");
    ASSERT_NE(state.find("CW"), std::string::npos) << state;
    ASSERT_NE(state.find("UP"), std::string::npos) << state;
  }
  std::unique_ptr<DaemonProcess> daemon;
};

TEST_P(SignalWhileMoving, StopsTheMotorsThenExitsCleanly) {
  start_moving();
  const int signal = GetParam();
  EXPECT_EQ(daemon->stop_with(signal), 0) << daemon->output();
  const std::string& out = daemon->output();
  EXPECT_NE(out.find("(" + std::to_string(signal) + "), stopping the motors"), std::string::npos)
      << out;
  EXPECT_NE(out.find("rotord: stopped; outputs at the driver: az off, el off"), std::string::npos)
      << out;
}

// Every catchable signal whose default action ends the process, but the
// CPU's own fault signals (docs/running.md, "Signals"); two real-time ones stand for
// the whole SIGRTMIN..SIGRTMAX range.
INSTANTIATE_TEST_SUITE_P(EveryTerminatingSignal, SignalWhileMoving,
                         ::testing::Values(SIGTERM, SIGINT, SIGHUP, SIGQUIT, SIGUSR1, SIGUSR2,
                                           SIGALRM, SIGPOLL, SIGVTALRM, SIGPROF, SIGXCPU, SIGXFSZ,
                                           SIGPWR, SIGSTKFLT, SIGRTMIN, SIGRTMAX),
                         [](const ::testing::TestParamInfo<int>& signal) {
                           if (signal.param == SIGRTMIN) return std::string("SIGRTMIN");
                           if (signal.param == SIGRTMAX) return std::string("SIGRTMAX");
                           return std::string("SIG") + ::sigabbrev_np(signal.param);
                         });

TEST(Signals, ASentSigpipeIsIgnored) {
  DaemonProcess daemon({"--clock", "manual"});
  ASSERT_TRUE(daemon.ready()) << daemon.output();
  TcpClient wrc(daemon.ports().wrc);
  ASSERT_EQ(wrc.ask("AZ 300\n"), "OK AZ 300.00");
  ::kill(daemon.pid(), SIGPIPE);
  // Still there and still moving: it answers, and time still runs.
  ASSERT_GT(daemon.advance_ms(1000), 0);
  EXPECT_NE(wrc.ask("STATE\n").find("CW"), std::string::npos);
  EXPECT_EQ(daemon.terminate(), 0) << daemon.output();
  EXPECT_NE(daemon.output().find("outputs at the driver: az off, el off"), std::string::npos);
}

TEST(Signals, AHangupWithTheTerminalGoneStillStopsAndExitsCleanly) {
  // A dropped SSH session: rotord's output goes nowhere (writes fail with
  // EPIPE instead of raising SIGPIPE), then the SIGHUP arrives.
  DaemonProcess daemon({"--clock", "manual"});
  ASSERT_TRUE(daemon.ready()) << daemon.output();
  TcpClient wrc(daemon.ports().wrc);
  ASSERT_EQ(wrc.ask("AZ 300\n"), "OK AZ 300.00");
  ASSERT_GT(daemon.advance_ms(1000), 0);
  daemon.close_output();
  EXPECT_EQ(daemon.stop_with(SIGHUP), 0);
}

}  // namespace
}  // namespace rotord::testing
