// The host's NTP state in words (the set-up page's station step, GET
// /api/setup "clock"): the kernel's synchronized flag as timedatectl shows
// it, read through adjtimex.
#include "ntp_state.hpp"

#include <gtest/gtest.h>

#include <cerrno>
#include <string>

namespace rotord::linux_port {
namespace {

std::string words(const NtpReading& r) {
  char text[256];
  return std::string(text, describe_ntp(r, text, sizeof text));
}

TEST(NtpState, SynchronizedWithItsErrors) {
  NtpReading r;
  r.state = TIME_OK;
  r.status = STA_PLL;
  r.esterror_us = 1'250;
  r.maxerror_us = 16'000;
  EXPECT_EQ(words(r),
            "The system clock is synchronized by NTP: estimated error 1.2 ms, at most 16 ms.");
  r.timesyncd = true;
  EXPECT_EQ(words(r),
            "The system clock is synchronized by NTP (systemd-timesyncd): estimated error 1.2 ms, "
            "at most 16 ms.");
}

TEST(NtpState, NotSynchronizedSaysWhatToDo) {
  NtpReading r;
  r.state = TIME_OK;
  r.status = STA_UNSYNC;
  const std::string unsynced = words(r);
  EXPECT_EQ(unsynced,
            "The system clock is not synchronized: no NTP client keeps it. Turn one on (sudo "
            "timedatectl set-ntp true, or install chrony); tracking waits for it unless "
            "time.trust_system_clock is on.");
  r.status = 0;
  r.state = TIME_ERROR;
  EXPECT_EQ(words(r), unsynced);
  r.state = -1;
  r.error = EPERM;
  EXPECT_EQ(words(r),
            "The kernel does not say whether the system clock is synchronized (adjtimex: "
            "Operation not permitted).");
}

TEST(NtpState, TheHostsClockIsOneOfThem) {
  // This machine's own state: whichever it is, it is said in one of the
  // sentences above, never cut short in a buffer of the API's size.
  const NtpState state;
  char text[256];
  const std::string said(text, state.describe(text, sizeof text));
  EXPECT_TRUE(said.rfind("The system clock is synchronized by NTP", 0) == 0 ||
              said.rfind("The system clock is not synchronized", 0) == 0 ||
              said.rfind("The kernel does not say", 0) == 0)
      << said;
  EXPECT_EQ(said.back(), '.');
}

}  // namespace
}  // namespace rotord::linux_port
