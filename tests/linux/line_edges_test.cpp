// LineEdges (ports/linux/line_edges.hpp), under the anemometer's pulse
// counter and the MA3's edge timer: edges queued behind a readable event
// descriptor are read by the asio loop itself, before any tick asks.
#include "line_edges.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <memory>
#include <vector>

#include "fake_edge_line.hpp"
#include "gpiod_pulse_counter.hpp"

namespace rotord::linux_port {
namespace {

using testing::FakeEdgeLine;

class LineEdgesTest : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_EQ(::pipe(fds_), 0);
    line_ = std::make_unique<FakeEdgeLine>(fds_[0]);
    edges_ = line_.get();
  }
  void TearDown() override {
    ::close(fds_[0]);
    ::close(fds_[1]);
  }
  void make_readable() { ASSERT_EQ(::write(fds_[1], "e", 1), 1); }

  int fds_[2] = {-1, -1};
  std::unique_ptr<FakeEdgeLine> line_;
  FakeEdgeLine* edges_ = nullptr;
  asio::io_context io_;
};

TEST_F(LineEdgesTest, TheLoopDrainsEveryBatchWhenTheDescriptorIsReadable) {
  // 150 edges: three batches of at most 64, handed over in order.
  for (int k = 0; k < 150; ++k) edges_->queued.push_back({k % 2 == 0, 1000u * k});
  std::vector<std::size_t> batches;
  std::vector<std::uint64_t> seen_ns;
  LineEdges edges(std::move(line_), [&](std::span<const LineEdge> batch) {
    batches.push_back(batch.size());
    for (const LineEdge& e : batch) seen_ns.push_back(e.timestamp_ns);
  });
  edges.watch(io_);
  EXPECT_EQ(io_.poll_one(), 0u);  // nothing readable yet: nothing read
  EXPECT_EQ(edges_->queued.size(), 150u);
  make_readable();
  EXPECT_EQ(io_.poll_one(), 1u);
  EXPECT_TRUE(edges_->queued.empty());
  EXPECT_EQ(batches, (std::vector<std::size_t>{64, 64, 22}));
  ASSERT_EQ(seen_ns.size(), 150u);
  for (std::size_t k = 0; k < seen_ns.size(); ++k) EXPECT_EQ(seen_ns[k], 1000u * k);
  // An empty queue hands over no batch.
  edges.drain();
  EXPECT_EQ(batches.size(), 3u);
}

TEST_F(LineEdgesTest, TheAnemometerCountsRisingEdgesReadByTheLoop) {
  for (int k = 0; k < 10; ++k) edges_->queued.push_back({k % 2 == 0, 1000u * k});
  GpiodPulseCounter counter(std::move(line_));
  counter.watch(io_);
  make_readable();
  EXPECT_EQ(io_.poll_one(), 1u);
  EXPECT_TRUE(edges_->queued.empty());  // read before count() asked
  EXPECT_EQ(counter.count(), 5u);
}

}  // namespace
}  // namespace rotord::linux_port
