// Checks the test image itself: that startup code, newlib, libstdc++ and the
// soft-float library behave on the target as the core's tests assume. Runs
// before any core test exists and tells a broken harness from a broken core.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <optional>
#include <string>

namespace {

int g_initialised = 42;  // .data: loaded from the ELF
int g_zeroed;            // .bss: cleared by the reset handler

struct Constructed {
  Constructed() : value(7) {}
  int value;
};
Constructed g_constructed;  // .init_array: run by __libc_init_array

TEST(TargetSelfTest, IsA32BitLittleEndianThumbTarget) {
  EXPECT_EQ(sizeof(void*), 4u);
  EXPECT_EQ(sizeof(long), 4u);
  const std::uint32_t word = 0x01020304;
  std::uint8_t first;
  std::memcpy(&first, &word, 1);
  EXPECT_EQ(first, 0x04);
#if !defined(__thumb__) || defined(__thumb2__) || __ARM_ARCH != 6
#error "the embedded tests must be compiled for Thumb-1 / ARMv6-M"
#endif
}

TEST(TargetSelfTest, StaticStorageIsInitialised) {
  EXPECT_EQ(g_initialised, 42);
  EXPECT_EQ(g_zeroed, 0);
  EXPECT_EQ(g_constructed.value, 7);
}

TEST(TargetSelfTest, SoftFloatAndDoubleArithmetic) {
  // volatile: computed at run time by libgcc's soft-float routines, not folded.
  volatile float a = 2.0f;
  volatile double b = 10.0;
  EXPECT_FLOAT_EQ(std::sqrt(a) * std::sqrt(a), 2.0f);
  EXPECT_NEAR(std::sin(b), -0.5440211108893698, 1e-12);
  EXPECT_FLOAT_EQ(std::fmod(-30.0f, 360.0f) + 360.0f, 330.0f);
  EXPECT_EQ(static_cast<int>(std::lround(a * 1.25f)), 3);
  EXPECT_TRUE(std::isnan(std::nanf("")));
}

TEST(TargetSelfTest, FormattingAndParsing) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.1f %d", 123.45, -7);
  EXPECT_STREQ(buf, "123.5 -7");
  EXPECT_DOUBLE_EQ(std::strtod("-12.25", nullptr), -12.25);
}

TEST(TargetSelfTest, HeapAndLibstdcxx) {
  std::string text(1000, 'x');
  text += "end";
  EXPECT_EQ(text.size(), 1003u);
  std::optional<int> value;
  EXPECT_FALSE(value.has_value());
  value = 3;
  EXPECT_EQ(*value, 3);
}

}  // namespace
