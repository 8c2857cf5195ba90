// The control tick on an absolute schedule (issue 12): the n-th tick is due
// at start + n x period whatever the wake-up latency, late wake-ups skip and
// count ticks instead of bursting, and a long stall restarts the schedule.
// The test owns the clock: every time is a number it passes in.
#include <gtest/gtest.h>

#include "loop/tick_scheduler.hpp"

namespace rotord {
namespace {

constexpr std::int64_t kPeriodUs = 10'000;
constexpr std::int64_t kStartUs = 5'000'000;

TEST(TickScheduler, TheFirstTickIsDueOnePeriodAfterStart) {
  TickScheduler s(kPeriodUs);
  s.start(kStartUs);
  EXPECT_EQ(s.deadline_us(), kStartUs + kPeriodUs);
  EXPECT_FALSE(s.poll(kStartUs + kPeriodUs - 1));
  EXPECT_TRUE(s.poll(kStartUs + kPeriodUs));
  EXPECT_EQ(s.deadline_us(), kStartUs + 2 * kPeriodUs);
}

TEST(TickScheduler, LateWakeUpsDoNotDrift) {
  // Every wake-up 230 us late: re-arming after the last tick would run at
  // 10.23 ms; the absolute schedule keeps the n-th deadline at start + n x 10 ms.
  TickScheduler s(kPeriodUs);
  s.start(kStartUs);
  for (int n = 1; n <= 1000; ++n) {
    ASSERT_EQ(s.deadline_us(), kStartUs + n * kPeriodUs);
    ASSERT_TRUE(s.poll(s.deadline_us() + 230));
  }
  EXPECT_EQ(s.deadline_us(), kStartUs + 1001 * kPeriodUs);
  EXPECT_EQ(s.stats().ticks, 1000u);
  EXPECT_EQ(s.stats().overruns, 0u);
  // The period as run averages exactly 10 ms.
  EXPECT_EQ(s.stats().interval.count(), 999u);
  EXPECT_EQ(s.stats().interval.sum_us(), 999 * kPeriodUs);
  EXPECT_EQ(s.stats().lateness.sum_us(), 1000 * 230);
}

TEST(TickScheduler, AnEarlyWakeUpRunsNoTick) {
  TickScheduler s(kPeriodUs);
  s.start(kStartUs);
  EXPECT_FALSE(s.poll(kStartUs + 3000));
  EXPECT_EQ(s.deadline_us(), kStartUs + kPeriodUs);
  EXPECT_EQ(s.stats().ticks, 0u);
}

TEST(TickScheduler, AnOverrunSkipsTheMissedTicksAndCountsThem) {
  TickScheduler s(kPeriodUs);
  s.start(kStartUs);
  ASSERT_TRUE(s.poll(kStartUs + kPeriodUs));
  // The loop stalls 35 ms past tick 2's deadline: one tick runs now, ticks
  // 3, 4 and 5 are skipped (their deadlines passed), tick 6 keeps its slot.
  ASSERT_TRUE(s.poll(kStartUs + 2 * kPeriodUs + 35'000));
  EXPECT_EQ(s.stats().overruns, 3u);
  EXPECT_EQ(s.deadline_us(), kStartUs + 6 * kPeriodUs);
  // No catch-up burst: the next wake-up before that deadline runs nothing.
  EXPECT_FALSE(s.poll(kStartUs + 2 * kPeriodUs + 36'000));
  EXPECT_TRUE(s.poll(kStartUs + 6 * kPeriodUs));
  EXPECT_EQ(s.stats().ticks, 3u);
  EXPECT_EQ(s.stats().rebases, 0u);
}

TEST(TickScheduler, LateByLessThanAPeriodSkipsNothing) {
  TickScheduler s(kPeriodUs);
  s.start(kStartUs);
  ASSERT_TRUE(s.poll(kStartUs + kPeriodUs + 9'999));
  EXPECT_EQ(s.stats().overruns, 0u);
  EXPECT_EQ(s.deadline_us(), kStartUs + 2 * kPeriodUs);
}

TEST(TickScheduler, ALongStallRestartsTheScheduleFromThatMoment) {
  TickScheduler s(kPeriodUs, 1'000'000);
  s.start(kStartUs);
  ASSERT_TRUE(s.poll(kStartUs + kPeriodUs));
  // A suspended host wakes 5 s later: one tick, then a new schedule from now.
  const std::int64_t woke = kStartUs + 2 * kPeriodUs + 5'000'000 + 1234;
  ASSERT_TRUE(s.poll(woke));
  EXPECT_EQ(s.stats().rebases, 1u);
  EXPECT_EQ(s.stats().overruns, 500u);
  EXPECT_EQ(s.deadline_us(), woke + kPeriodUs);
  EXPECT_TRUE(s.poll(woke + kPeriodUs));
  EXPECT_EQ(s.deadline_us(), woke + 2 * kPeriodUs);
}

TEST(TickScheduler, JitterAndPeriodGoToTheirHistogramBuckets) {
  TickScheduler s(kPeriodUs);
  s.start(0);
  ASSERT_TRUE(s.poll(10'000 + 40));   // 40 us late
  ASSERT_TRUE(s.poll(20'000 + 700));  // 700 us late, 10.66 ms after the last
  const metrics::Histogram& late = s.stats().lateness;
  ASSERT_EQ(late.bounds_us()[0], 50);
  EXPECT_EQ(late.bucket(0), 1u);  // <= 50 us
  EXPECT_EQ(late.bucket(4), 1u);  // 500 < x <= 1000 us
  EXPECT_EQ(late.count(), 2u);
  const metrics::Histogram& interval = s.stats().interval;
  EXPECT_EQ(interval.count(), 1u);
  EXPECT_EQ(interval.sum_us(), 10'660);
  EXPECT_EQ(interval.bucket(6), 1u);  // 10.5 < x <= 11 ms
}

TEST(Histogram, AValueAboveTheLastBoundCountsOnlyInTheTotal) {
  static constexpr std::int64_t kBounds[] = {10, 20};
  metrics::Histogram h(kBounds);
  h.add(5);
  h.add(20);
  h.add(21);
  EXPECT_EQ(h.bucket(0), 1u);
  EXPECT_EQ(h.bucket(1), 1u);
  EXPECT_EQ(h.count(), 3u);
  EXPECT_EQ(h.sum_us(), 46);
}

}  // namespace
}  // namespace rotord
