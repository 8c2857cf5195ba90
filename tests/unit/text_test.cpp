#include "util/text.hpp"

#include <gtest/gtest.h>

namespace rotord {
namespace {

TEST(Text, ParsesNumbersAsClientsWriteThem) {
  double v = 0;
  EXPECT_TRUE(text::parse_double("123.45", v));
  EXPECT_DOUBLE_EQ(v, 123.45);
  EXPECT_TRUE(text::parse_double("123,45", v));  // Gpredict in a comma locale
  EXPECT_DOUBLE_EQ(v, 123.45);
  EXPECT_TRUE(text::parse_double("+10", v));
  EXPECT_DOUBLE_EQ(v, 10.0);
  EXPECT_TRUE(text::parse_double("-10.500000", v));
  EXPECT_DOUBLE_EQ(v, -10.5);
  EXPECT_TRUE(text::parse_double("1e2", v));
  EXPECT_DOUBLE_EQ(v, 100.0);
  EXPECT_TRUE(text::parse_double(".5", v));
  EXPECT_DOUBLE_EQ(v, 0.5);
}

TEST(Text, RejectsWhatIsNotANumber) {
  double v = 7;
  for (const char* bad :
       {"", "abc", "12abc", "0x10", "inf", "nan", "1e", "--1", "1.2.3", "+", "1e999", " 1"}) {
    EXPECT_FALSE(text::parse_double(bad, v)) << bad;
  }
  EXPECT_DOUBLE_EQ(v, 7.0);  // untouched on failure
}

TEST(Text, ParsesIntegers) {
  long v = 0;
  EXPECT_TRUE(text::parse_int("42", v));
  EXPECT_EQ(v, 42);
  EXPECT_TRUE(text::parse_int("-3", v));
  EXPECT_EQ(v, -3);
  EXPECT_FALSE(text::parse_int("4.2", v));
  EXPECT_FALSE(text::parse_int("99999999999", v));
  EXPECT_FALSE(text::parse_int("", v));
}

TEST(Text, TokensAndCase) {
  std::string_view rest = "  MOVE   CW \r\n";
  EXPECT_EQ(text::next_token(rest), "MOVE");
  EXPECT_EQ(text::next_token(rest), "CW");
  EXPECT_EQ(text::next_token(rest), "");
  EXPECT_TRUE(text::iequals("move", "MOVE"));
  EXPECT_FALSE(text::iequals("mov", "MOVE"));
}

}  // namespace
}  // namespace rotord
