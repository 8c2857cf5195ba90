#include "ma3_edge_timer.hpp"

#include <gtest/gtest.h>

#include "fake_edge_line.hpp"
#include "sensors/ma3_sensor.hpp"

namespace rotord::linux_port {
namespace {

constexpr std::uint64_t kUs = 1000;

/// Synthetic MA3 frames: rise, fall after high_us, next rise after low_us.
struct EdgeTrain {
  std::uint64_t t_ns = 1'000'000'000;
  Ma3EdgeTimer timer;

  void rise() { timer.on_edge({true, t_ns}, t_ns); }
  void fall() { timer.on_edge({false, t_ns}, t_ns); }
  /// A frame starting with its rise; ends before the next rise.
  void frame(std::uint64_t high_us, std::uint64_t low_us) {
    rise();
    t_ns += high_us * kUs;
    fall();
    t_ns += low_us * kUs;
  }
  /// An edge `us` after the last one.
  void rise_after(std::uint64_t us) {
    t_ns += us * kUs;
    rise();
  }
  void fall_after(std::uint64_t us) {
    t_ns += us * kUs;
    fall();
  }
  /// The next frame's rise, which closes the period before it; what the
  /// timer gives then.
  hal::PwmPeriod close() {
    rise();
    return timer.take(t_ns);
  }
};

TEST(Ma3EdgeTimerTest, NothingBeforeTheFirstFullPeriod) {
  EdgeTrain e;
  EXPECT_FALSE(e.timer.take(e.t_ns).valid);
  e.frame(1025, 3072);
  EXPECT_FALSE(e.timer.take(e.t_ns).valid);  // no closing rise yet
  const hal::PwmPeriod p = e.close();
  ASSERT_TRUE(p.valid);
  EXPECT_EQ(p.high_us, 1025u);
  EXPECT_EQ(p.low_us, 3072u);
  EXPECT_EQ(ma3_decode_code(p, 12), 1024);  // a quarter turn
}

TEST(Ma3EdgeTimerTest, AveragesThePeriodsOfOneTickToDivideTheJitter) {
  EdgeTrain e;
  // A 10-bit part at 975 Hz, code 511, with +-3 us of interrupt latency on
  // alternate falls: ten frames per 10 ms tick.
  for (int k = 0; k < 10; ++k)
    e.frame(k % 2 == 0 ? 512 + 3 : 512 - 3, k % 2 == 0 ? 513 - 3 : 513 + 3);
  const hal::PwmPeriod p = e.close();
  ASSERT_TRUE(p.valid);
  EXPECT_EQ(p.high_us, 512u);
  EXPECT_EQ(p.low_us, 513u);
  EXPECT_EQ(ma3_decode_code(p, 10), 511);
}

TEST(Ma3EdgeTimerTest, APeriodSplitByANoiseEdgePairIsLeftOut) {
  EdgeTrain e;
  e.frame(2000, 2097);
  // A spike in the low time: fall... rise(spike) fall(spike) ... rise.
  e.frame(2000, 1000);
  e.frame(5, 1092);
  e.frame(2000, 2097);
  const hal::PwmPeriod p = e.close();
  ASSERT_TRUE(p.valid);
  EXPECT_EQ(p.high_us, 2000u);  // only the two full-length frames count
  EXPECT_EQ(p.low_us, 2097u);
}

TEST(Ma3EdgeTimerTest, ALostEdgeNeverJoinsTwoFrames) {
  EdgeTrain e;
  e.frame(1000, 3097);
  ASSERT_TRUE(e.close().valid);
  // The kernel's queue overflowed: the fall of this frame is missing, so two
  // rises come in a row, then a fall whose rise is unknown.
  e.rise_after(4097);  // rise, rise: no period
  e.fall_after(3000);
  e.rise_after(1097);  // rise, fall, rise: a real period again (3000 / 1097)
  const hal::PwmPeriod p = e.timer.take(e.t_ns);
  ASSERT_TRUE(p.valid);
  EXPECT_EQ(p.high_us, 3000u);
  EXPECT_EQ(p.low_us, 1097u);
  // Two falls in a row restart the assembly as well.
  e.fall_after(500);
  e.fall_after(500);
  e.t_ns += 500 * kUs;
  const hal::PwmPeriod same = e.close();
  EXPECT_EQ(same.high_us, 3000u);  // no new period: the last one again
}

TEST(Ma3EdgeTimerTest, TimestampsGoingBackwardsRestart) {
  EdgeTrain e;
  e.frame(1000, 3097);
  e.t_ns -= 10'000 * kUs;
  e.frame(1500, 2597);  // its rise is behind the previous edge: restart
  e.frame(1500, 2597);
  const hal::PwmPeriod p = e.close();
  ASSERT_TRUE(p.valid);
  EXPECT_EQ(p.high_us, 1500u);
}

TEST(Ma3EdgeTimerTest, NoEdgesForTheTimeoutMeansNoSignal) {
  EdgeTrain e;
  e.frame(1025, 3072);
  ASSERT_TRUE(e.close().valid);
  EXPECT_TRUE(e.timer.take(e.t_ns + Ma3EdgeTimer::kTimeoutNs).valid);  // the last period still
  EXPECT_FALSE(e.timer.take(e.t_ns + Ma3EdgeTimer::kTimeoutNs + 1).valid);
}

using testing::FakeEdgeLine;

TEST(GpiodMa3InputTest, FeedsTheCoreMa3SensorFromQueuedEdges) {
  auto line = std::make_unique<FakeEdgeLine>();
  FakeEdgeLine& edges = *line;
  std::uint64_t now_ns = 0;
  GpiodMa3Input input(std::move(line), [&now_ns] { return now_ns; });
  Ma3Sensor sensor(input);
  sensor.configure(12, 0.0f, false);
  // 100 edges (more than one read_edges() batch) of code 2048: half a turn.
  std::uint64_t t = 5'000'000;
  for (int k = 0; k < 50; ++k) {
    edges.queued.push_back({true, t});
    edges.queued.push_back({false, t + 2049 * kUs});
    t += 4097 * kUs;
  }
  edges.queued.push_back({true, t});
  now_ns = t + 100 * kUs;
  const PositionReading r = sensor.read(0);
  ASSERT_TRUE(r.ok);
  EXPECT_NEAR(r.deg, 180.0f, 0.1f);
  EXPECT_TRUE(edges.queued.empty());
  now_ns += Ma3EdgeTimer::kTimeoutNs + 1;  // unplugged
  EXPECT_EQ(sensor.read(0).fault, SensorFault::kNoSignal);
}

}  // namespace
}  // namespace rotord::linux_port
