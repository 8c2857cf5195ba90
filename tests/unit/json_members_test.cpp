// The one loop every small object body is read with (core/json/json_members.hpp):
// the command layer's arguments (REST, MQTT) and the access-control
// endpoints' bodies (login, tokens) refuse alike, and a string member keeps
// its text in the member's own bytes or in the caller's buffer.
#include "json/json_members.hpp"

#include <gtest/gtest.h>

#include <string>

namespace rotord::web {
namespace {

TEST(JsonMembers, ReadsWhatItIsAskedForAndAnEmptyBodyIsEmpty) {
  char password[72] = {};
  JsonMember m[] = {{"az", JsonType::kNumber},
                    {"dir", JsonType::kString},
                    {"password", JsonType::kString, password}};
  char why[128] = "";
  ASSERT_TRUE(read_members("", m, why, sizeof why));
  EXPECT_FALSE(m[0].present);
  ASSERT_TRUE(read_members(R"({"az": 12.5, "dir": "cw", "password": "correct horse battery"})", m,
                           why, sizeof why));
  EXPECT_TRUE(m[0].present);
  EXPECT_EQ(m[0].value.number, 12.5);
  EXPECT_EQ(m[1].value.text, "cw");
  EXPECT_EQ(m[2].value.text, "correct horse battery");
  EXPECT_STREQ(password, "correct horse battery");  // in the caller's buffer, NUL-ended
  EXPECT_FALSE(m[2].too_long);
}

TEST(JsonMembers, AStringLongerThanItsBufferIsTooLongAndEmpty) {
  JsonMember short_text[] = {{"dir", JsonType::kString}};
  char why[128] = "";
  ASSERT_TRUE(read_members(R"({"dir": "fifteen-letters"})", short_text, why, sizeof why));
  EXPECT_EQ(short_text[0].value.text, "fifteen-letters");
  ASSERT_TRUE(read_members(R"({"dir": "sixteen--letters"})", short_text, why, sizeof why));
  EXPECT_TRUE(short_text[0].too_long);
  EXPECT_EQ(short_text[0].value.text, "");

  char name[17] = {};  // a token name: up to 16 bytes
  JsonMember named[] = {{"name", JsonType::kString, name}};
  ASSERT_TRUE(read_members(R"({"name": "sixteen--letters"})", named, why, sizeof why));
  EXPECT_STREQ(name, "sixteen--letters");
  ASSERT_TRUE(read_members(R"({"name": "seventeen-letters"})", named, why, sizeof why));
  EXPECT_TRUE(named[0].too_long);
  EXPECT_STREQ(name, "");
}

TEST(JsonMembers, RefusesBadJsonAnUnknownMemberAndAWrongType) {
  JsonMember m[] = {{"az", JsonType::kNumber}};
  char why[128] = "";
  EXPECT_FALSE(read_members(R"({"az": 1,})", m, why, sizeof why));
  EXPECT_EQ(std::string(why).rfind("invalid JSON: ", 0), 0u) << why;
  EXPECT_NE(std::string(why).find("(byte "), std::string::npos) << why;
  EXPECT_FALSE(read_members(R"({"azimuth": 1})", m, why, sizeof why));
  EXPECT_STREQ(why, "unknown member 'azimuth'");
  EXPECT_FALSE(read_members(R"({"az": "north"})", m, why, sizeof why));
  EXPECT_STREQ(why, "az must be a number");
}

}  // namespace
}  // namespace rotord::web
