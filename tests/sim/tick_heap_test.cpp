// "No heap in the control tick" (docs/architecture.md), checked rather than promised: this
// binary replaces the global allocator with one that counts, and the count is
// taken only inside the control tick (the manual buttons' poll and
// Controller::tick) while the controller runs every kind of work on the
// simulator: go-tos through the overlap, reversals, jogs, stops, stalls,
// sensor loss, resets and settings changes (which the tick applies).
// Its own executable, because the counting allocator is global.
#include <gtest/gtest.h>

#include <cstdlib>
#include <memory>
#include <new>

#include "command/buttons.hpp"
#include "rotator/controller.hpp"
#include "sim/profiles.hpp"
#include "sim/sim_rotator.hpp"

namespace {
// Plain globals: the allocator runs before and after main.
bool g_counting = false;
long g_tick_allocations = 0;
}  // namespace

void* operator new(std::size_t size) {
  if (g_counting) ++g_tick_allocations;
  if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
  std::abort();  // built without exceptions, like the core
}
void* operator new[](std::size_t size) {
  return operator new(size);
}
void operator delete(void* p) noexcept {
  std::free(p);
}
void operator delete[](void* p) noexcept {
  std::free(p);
}
void operator delete(void* p, std::size_t) noexcept {
  std::free(p);
}
void operator delete[](void* p, std::size_t) noexcept {
  std::free(p);
}

namespace rotord {
namespace {

class TickHeap : public ::testing::TestWithParam<const char*> {
 protected:
  TickHeap() : profile_(*sim::find_profile(GetParam())) {
    for (const auto& o : profile_.overrides) settings_.set(*settings::find(o.key), o.value);
    sim_ = std::make_unique<sim::SimRotator>(profile_, 7);
    sim_->set_theta_deg(AxisId::kAz, 100);
    controller_ =
        std::make_unique<Controller>(settings_, sim_->io(AxisId::kAz), sim_->io(AxisId::kEl));
    buttons_ = std::make_unique<command::Buttons>(*controller_, sim_->io(AxisId::kAz),
                                                  sim_->io(AxisId::kEl));
    controller_->begin(now_);
    g_tick_allocations = 0;
  }

  void run_ms(Millis ms) {
    for (Millis t = 0; t < ms; t += 10) {
      now_ += 10;
      sim_->advance_to(now_);
      g_counting = true;
      buttons_->poll(now_);  // the manual buttons' front end, polled before each tick
      controller_->tick(now_);
      g_counting = false;
      ++ticks_;
    }
  }

  const sim::Profile& profile_;
  settings::Settings settings_;
  std::unique_ptr<sim::SimRotator> sim_;
  std::unique_ptr<Controller> controller_;
  std::unique_ptr<command::Buttons> buttons_;
  Millis now_ = 0;
  long ticks_ = 0;
  /// 2019-12-09T17:00:00Z + controller time.
  class Clock final : public hal::WallClock {
   public:
    explicit Clock(const Millis* now) : now_(now) {}
    std::optional<std::int64_t> unix_ms() const override { return 1575910800000LL + *now_; }

   private:
    const Millis* now_;
  } clock_{&now_};
};

TEST_P(TickHeap, NoTickAllocatesWhateverTheControllerDoes) {
  Controller& c = *controller_;
  const Limits limits = c.limits();
  // Go-to to the far end of the travel (through the overlap where there is
  // one), reversed half-way, then back.
  ASSERT_EQ(c.go_to(limits.az_max_deg - 5, std::nullopt, AzTarget::kUnwrapped), Error::kOk);
  run_ms(8000);
  ASSERT_EQ(c.go_to(limits.az_min_deg + 20, std::nullopt, AzTarget::kUnwrapped), Error::kOk);
  run_ms(60000);
  if (c.has_el()) {
    ASSERT_EQ(c.go_to(std::nullopt, 45.0F), Error::kOk);
    run_ms(30000);
  }
  // Jog, stop during the start sequence, jog the other way, dead-man expiry.
  ASSERT_EQ(c.move(AxisId::kAz, Direction::kCw), Error::kOk);
  run_ms(30);
  c.stop();
  run_ms(2000);
  ASSERT_EQ(c.move(AxisId::kAz, Direction::kCcw, 30, 500), Error::kOk);
  run_ms(3000);
  // Settings changed while moving are applied by the tick.
  ASSERT_EQ(c.go_to(180.0F, std::nullopt), Error::kOk);
  run_ms(1000);
  ASSERT_EQ(settings_.set(settings::Id::kAzToleranceDeg, 2.0).error, Error::kOk);
  ASSERT_EQ(settings_.set(settings::Id::kAzOffsetDeg, 3.0).error, Error::kOk);
  run_ms(40000);
  // Faults latch and are reset: a jam (stall), then a lost sensor.
  sim_->jam(AxisId::kAz, sim::kForever_s);
  ASSERT_EQ(c.go_to(limits.az_min_deg + 60, std::nullopt, AzTarget::kUnwrapped), Error::kOk);
  run_ms(10000);
  EXPECT_EQ(c.status().az.fault, AxisFault::kStall) << "the jam should have latched a stall";
  sim_->clear_faults(AxisId::kAz);
  c.reset();
  run_ms(1000);
  sim_->sensor_loss(AxisId::kAz, 2.0);
  ASSERT_EQ(c.go_to(200.0F, std::nullopt), Error::kOk);
  run_ms(5000);
  c.reset();
  ASSERT_EQ(c.park(), Error::kOk);
  run_ms(60000);
  // The tracking mode: pass search, planning and following the Sun (UTC =
  // a fixed morning + controller time), then a STOP ends it.
  c.attach_utc_clock(&clock_);
  settings_.set(settings::Id::kStationLatDeg, 40.0);
  settings_.set(settings::Id::kStationLonDeg, -105.0);
  TrackRequest sun;
  sun.kind = tracking::TargetKind::kSun;
  sun.when = TrackWhen::kNow;
  ASSERT_EQ(c.track(sun), TrackError::kOk);
  run_ms(120000);
  EXPECT_EQ(c.track_status().phase, TrackPhase::kTracking);
  c.stop();
  run_ms(1000);
  // Self-commissioning, run from the tick: a whole run (spid: its creep is
  // slow, so the run is aborted part-way), then STOP.
  Commissioning::Request commission;
  commission.ccw_stop_deg = limits.az_min_deg;
  commission.cw_stop_deg = limits.az_max_deg;
  const char* why = "";
  ASSERT_EQ(c.commission(commission, &why), Error::kOk) << why;
  run_ms(300000);
  EXPECT_GT(c.commissioning().sample_count(), 200u) << c.commissioning().reason();
  c.stop();
  run_ms(1000);

  EXPECT_GT(ticks_, 15000);
  EXPECT_EQ(g_tick_allocations, 0) << "allocations inside Controller::tick";
}

// The counter itself works: an allocation made while counting is seen.
TEST(TickHeapCounter, SeesAnAllocation) {
  g_tick_allocations = 0;
  g_counting = true;
  auto* volatile p = new int(42);
  g_counting = false;
  delete p;
  EXPECT_EQ(g_tick_allocations, 1);
  g_tick_allocations = 0;
}

INSTANTIATE_TEST_SUITE_P(Profiles, TickHeap, ::testing::Values("g5500", "ham4", "spid"));

}  // namespace
}  // namespace rotord
