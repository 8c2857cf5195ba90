#include "util/slice.hpp"

#include <gtest/gtest.h>

namespace rotord {
namespace {

// text::slice replaces std::string_view::substr in the core (no exception
// runtime in the firmware): the same views wherever substr would not throw.
TEST(Slice, InRangeItIsSubstr) {
  constexpr std::string_view s = "GET /api/status";
  for (std::size_t pos = 0; pos <= s.size(); ++pos) {
    for (std::size_t count : {std::size_t{0}, std::size_t{3}, s.size(), std::string_view::npos}) {
      const std::string_view got = text::slice(s, pos, count);
      EXPECT_EQ(got, s.substr(pos, count)) << pos << " " << count;
      EXPECT_EQ(got.data(), s.data() + pos);  // a view into s, not a copy
    }
  }
  EXPECT_EQ(text::slice(s, 4), "/api/status");
}

TEST(Slice, PastTheEndIsTheEmptyViewAtTheEnd) {
  constexpr std::string_view s = "C2";
  EXPECT_TRUE(text::slice(s, 3).empty());
  EXPECT_EQ(text::slice(s, 3).data(), s.data() + s.size());
  EXPECT_TRUE(text::slice(s, std::string_view::npos, 5).empty());
  EXPECT_TRUE(text::slice(std::string_view{}, 1).empty());
  static_assert(text::slice("abc", 1, 1) == "b");
}

}  // namespace
}  // namespace rotord
