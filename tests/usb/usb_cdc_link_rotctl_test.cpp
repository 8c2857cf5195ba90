// The USB link with a real client: Hamlib's rotctl (GS-232B, model 603) talks
// to the link's GS-232 session through a pseudo-terminal that stands in for
// the Pico's CDC interface. A pty has no DTR, so this is also the path of the
// programs that never raise DTR (replies once the client has spoken).
//
// The test's loop plays the firmware's: link.service() and a control tick
// per pass, in virtual time; rotctl runs in a thread. Waits are bounded by a
// pass count, never by a clock.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <termios.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <thread>

#include "fake_rotator.hpp"
#include "usb_cdc_link.hpp"
#include "usb_personality.hpp"

namespace rotord {
namespace {

/// The pty master as the link's CDC port. The test holds the slave open as
/// well, so rotctl closing it never hangs the line up (as in rotord's pty).
class PtyCdc final : public usb_port::CdcPort {
 public:
  PtyCdc() {
    master_ = ::posix_openpt(O_RDWR | O_NOCTTY);
    if (master_ < 0 || ::grantpt(master_) != 0 || ::unlockpt(master_) != 0) return;
    char name[128] = {};
    if (::ptsname_r(master_, name, sizeof name) != 0) return;
    path_ = name;
    slave_ = ::open(name, O_RDWR | O_NOCTTY);
    termios t{};
    ::tcgetattr(slave_, &t);
    ::cfmakeraw(&t);
    ::tcsetattr(slave_, TCSANOW, &t);
    ::fcntl(master_, F_SETFL, ::fcntl(master_, F_GETFL) | O_NONBLOCK);
  }
  ~PtyCdc() override {
    if (slave_ >= 0) ::close(slave_);
    if (master_ >= 0) ::close(master_);
  }
  PtyCdc(const PtyCdc&) = delete;
  PtyCdc& operator=(const PtyCdc&) = delete;

  const std::string& path() const { return path_; }
  bool ok() const { return slave_ >= 0; }

  bool connected() const override { return true; }
  bool dtr() const override { return false; }  // a pty has no modem lines
  std::uint32_t opens() const override { return 0; }
  std::size_t read(char* buffer, std::size_t max_bytes) override {
    const ssize_t n = ::read(master_, buffer, max_bytes);
    return n > 0 ? static_cast<std::size_t>(n) : 0;
  }
  std::size_t write_available() const override { return 256; }  // the Pico's FIFO
  std::size_t write(const char* data, std::size_t bytes) override {
    const ssize_t n = ::write(master_, data, bytes);
    return n > 0 ? static_cast<std::size_t>(n) : 0;
  }
  void flush() override {}
  void discard_output() override { ::tcflush(slave_, TCIFLUSH); }
  void discard_input() override { ::tcflush(slave_, TCOFLUSH); }

 private:
  int master_ = -1;
  int slave_ = -1;
  std::string path_;
};

struct ClientRun {
  int rc = -1;
  std::string out;
};

/// Runs `command` in a thread while the firmware loop turns.
ClientRun run_with_loop(const std::string& command, usb_port::UsbCdcLink& link,
                        testing::FakeRotator& rotator) {
  ClientRun run;
  std::atomic<bool> done{false};
  std::thread client([&] {
    FILE* p = ::popen((command + " 2>&1").c_str(), "r");
    if (p != nullptr) {
      char buf[256];
      while (std::fgets(buf, sizeof buf, p) != nullptr) run.out += buf;
      const int status = ::pclose(p);
      run.rc = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    }
    done = true;
  });
  // At most ~60 s of passes on a loaded machine; rotctl needs a few ms.
  for (int pass = 0; pass < 60'000 && !done; ++pass) {
    link.service();
    rotator.run_ms(10);
    link.poll(rotator.now);
    // Wall time on purpose: a real rotctl process on the other end of the pty
    // reads at its own pace; controller time above advances by the pass.
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  client.join();
  return run;
}

TEST(UsbCdcLinkRotctl, Hamlib603ReadsAndSetsThePositionThroughTheLink) {
  // rotctl comes with libhamlib-utils (scripts/install-deps.sh): missing means a broken set-up.
  ASSERT_EQ(::access(ROTCTL_PATH, X_OK), 0) << "no rotctl at " << ROTCTL_PATH;
  testing::FakeRotator rotator{false};
  PtyCdc cdc;
  ASSERT_TRUE(cdc.ok());
  usb_port::PersonalitySessions sessions(protocol::Personality::kGs232, *rotator.controller,
                                         "test");
  usb_port::UsbCdcLink link(cdc, sessions);

  const std::string rotctl = std::string(ROTCTL_PATH) + " -m 603 -r " + cdc.path();
  ClientRun r = run_with_loop(rotctl + " p", link, rotator);
  ASSERT_EQ(r.rc, 0) << r.out;
  EXPECT_NE(r.out.find("100.0"), std::string::npos) << r.out;

  // A second program on the same port: the link carries on.
  r = run_with_loop(rotctl + " P 200 0", link, rotator);
  ASSERT_EQ(r.rc, 0) << r.out;
  rotator.run_ms(20);
  EXPECT_TRUE(rotator.az.drive.cw());
  r = run_with_loop(rotctl + " S", link, rotator);
  ASSERT_EQ(r.rc, 0) << r.out;
  rotator.run_ms(20);
  EXPECT_FALSE(rotator.az.drive.cw() || rotator.az.drive.ccw());
  EXPECT_EQ(link.stats().dropped_replies, 0u);
}

}  // namespace
}  // namespace rotord
