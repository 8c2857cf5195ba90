// Instructions the tracking layer costs on ARMv6-M code, measured under qemu
// with -icount shift=0 (the virtual clock advances 1 ns per instruction), read
// from SysTick and calibrated against a loop of known length. Instructions,
// not time: the M0+ needs about 1.2-1.5 cycles per instruction of this kind,
// and the Pico's ROM double routines are faster than libgcc's soft float used
// here, so the counts are an upper bound for the firmware. Prints a table;
// fails only if a count is far beyond what the Pico W can afford (see README).
#include <gtest/gtest.h>

#include <cstdint>
#include <cstdio>

#include "tracking/julian.hpp"
#include "tracking/pass_finder.hpp"
#include "tracking/sky_target.hpp"

namespace rotord::tracking {
namespace {

volatile std::uint32_t& reg(std::uintptr_t address) {
  return *reinterpret_cast<volatile std::uint32_t*>(address);
}
constexpr std::uintptr_t kSystCsr = 0xE000E010, kSystRvr = 0xE000E014, kSystCvr = 0xE000E018;
constexpr std::uint32_t kMask24 = 0xFFFFFF;

void systick_start() {
  reg(kSystRvr) = kMask24;
  reg(kSystCvr) = 0;
  reg(kSystCsr) = 5;  // enable, processor clock, no interrupt
}

std::uint32_t systick_now() {
  return reg(kSystCvr) & kMask24;
}

/// SysTick ticks spent in f (the counter counts down; one wrap is 2^24 ticks).
template <typename F>
std::uint32_t ticks(F&& f) {
  systick_start();
  const std::uint32_t start = systick_now();
  f();
  const std::uint32_t end = systick_now();
  return (start - end) & kMask24;
}

/// Instructions per SysTick tick, from a loop of exactly two instructions per turn.
double instructions_per_tick() {
  constexpr std::uint32_t kTurns = 2'000'000;
  const std::uint32_t t = ticks([] {
    std::uint32_t n = kTurns;
    asm volatile(".syntax unified\n1: subs %0, %0, #1\n bne 1b" : "+l"(n) : : "cc");
  });
  return 2.0 * kTurns / t;
}

constexpr const char* kIss[] = {
    "1 25544U 98067A   19343.69339541  .00001764  00000-0  38792-4 0  9991",
    "2 25544  51.6439 211.2001 0007417  17.6667  85.6398 15.50103472202482"};
constexpr const char* kMolniya[] = {
    "1 08195U 75081A   06176.33215444  .00000099  00000-0  11873-3 0   813",
    "2 08195  64.1586 279.0717 6877146 264.7651  20.2257  2.00491383225656"};

double per_call(double ipt, std::uint32_t t, int calls) {
  return ipt * t / calls;
}

TEST(TrackingTiming, InstructionsOfOneSgp4StepAndItsNeighbours) {
  const double ipt = instructions_per_tick();
  std::printf("calibration: %.3f instructions per SysTick tick\n", ipt);
  ASSERT_GT(ipt, 1.0) << "run with qemu -icount shift=0 (QEMU_EXTRA_ARGS)";

  Tle iss, molniya;
  ASSERT_TRUE(parse_tle(kIss[0], kIss[1], iss).ok());
  ASSERT_TRUE(parse_tle(kMolniya[0], kMolniya[1], molniya).ok());
  Sgp4 near_earth, deep;
  ASSERT_EQ(near_earth.init(iss), Sgp4Error::kOk);
  ASSERT_EQ(deep.init(molniya), Sgp4Error::kOk);

  constexpr int kCalls = 50;
  TemeState s;
  std::uint32_t t = ticks([&] { (void)near_earth.init(iss); });
  const double init_near = per_call(ipt, t, 1);
  t = ticks([&] {
    for (int i = 0; i < kCalls; ++i) (void)near_earth.propagate(i * 1.7, s);
  });
  const double step_near = per_call(ipt, t, kCalls);
  // Deep space within one 720 min integrator step of the cached one.
  t = ticks([&] {
    for (int i = 0; i < kCalls; ++i) (void)deep.propagate(100.0 + i * 1.7, s);
  });
  const double step_deep = per_call(ipt, t, kCalls);

  SkyTarget sat, sun, moon;
  ASSERT_EQ(sat.set_satellite(iss), Sgp4Error::kOk);
  sun.set_body(Body::kSun);
  moon.set_body(Body::kMoon);
  const Observer observer(Geodetic{40.015, -105.27, 1655.0});
  const std::int64_t when = 1'575'912'000'000;  // 2019-12-09T17:20:00Z
  LookAngles look;
  t = ticks([&] {
    for (int i = 0; i < kCalls; ++i) (void)sat.look(when + i * 1000, observer, look);
  });
  const double look_sat = per_call(ipt, t, kCalls);
  t = ticks([&] {
    for (int i = 0; i < 10; ++i) (void)sun.look(when + i * 1000, observer, look);
  });
  const double look_sun = per_call(ipt, t, 10);
  t = ticks([&] {
    for (int i = 0; i < 10; ++i) (void)moon.look(when + i * 1000, observer, look);
  });
  const double look_moon = per_call(ipt, t, 10);

  // The passes of a day for the ISS, in calls of 10 evaluations.
  PassFinder finder;
  int passes = 0, calls = 0;
  t = ticks([&] {
    finder.start(sat, observer, when, when + 86'400'000, 0.0);
    for (PassFinder::Status st = PassFinder::Status::kSearching;
         st != PassFinder::Status::kDone && st != PassFinder::Status::kError;) {
      st = finder.step(10);
      ++calls;
      if (st == PassFinder::Status::kFound) ++passes;
    }
  });
  const double day = ipt * t;

  std::printf("instructions (ARMv6-M, libgcc soft float):\n");
  std::printf("  SGP4 init, near Earth        %10.0f\n", init_near);
  std::printf("  SGP4 step, near Earth (ISS)  %10.0f\n", step_near);
  std::printf("  SDP4 step, Molniya           %10.0f\n", step_deep);
  std::printf("  look angles, ISS             %10.0f\n", look_sat);
  std::printf("  look angles, Sun             %10.0f\n", look_sun);
  std::printf("  look angles, Moon            %10.0f\n", look_moon);
  std::printf(
      "  ISS passes of a day          %10.0f (%d passes, %d calls of 10 evaluations, "
      "%.0f per call)\n",
      day, passes, calls, day / calls);
  // At 133 MHz and >= 1 cycle per instruction, 1.3 M instructions are 10 ms:
  // a tracking update once a second would cost 1 % of the CPU.
  EXPECT_LT(step_near, 1.3e6);
  EXPECT_LT(step_deep, 1.3e6);
  EXPECT_LT(look_moon, 1.3e6);
  EXPECT_GT(passes, 3);
}

}  // namespace
}  // namespace rotord::tracking
