#include <gtest/gtest.h>

#include <limits>
#include <string>

#include "http_test_client.hpp"
#include "json/json_reader.hpp"
#include "json/json_writer.hpp"

namespace rotord::web {
namespace {

TEST(JsonReader, ReadsScalarMembersInOrder) {
  JsonObjectReader r(
      R"( { "az" : 12.5, "el":-3e1 ,"on":true,"off":false,"n":null,"s":"a\"b\u00e9\n" } )");
  ASSERT_TRUE(r.valid()) << r.error();
  std::string_view key;
  JsonValue v;
  ASSERT_TRUE(r.next(key, v));
  EXPECT_EQ(key, "az");
  EXPECT_EQ(v.type, JsonType::kNumber);
  EXPECT_DOUBLE_EQ(v.number, 12.5);
  ASSERT_TRUE(r.next(key, v));
  EXPECT_DOUBLE_EQ(v.number, -30.0);
  ASSERT_TRUE(r.next(key, v));
  EXPECT_EQ(v.type, JsonType::kBool);
  EXPECT_TRUE(v.boolean);
  ASSERT_TRUE(r.next(key, v));
  EXPECT_FALSE(v.boolean);
  ASSERT_TRUE(r.next(key, v));
  EXPECT_EQ(v.type, JsonType::kNull);
  ASSERT_TRUE(r.next(key, v));
  EXPECT_EQ(key, "s");
  EXPECT_EQ(v.text, "a\"b\xc3\xa9\n");
  EXPECT_FALSE(r.next(key, v));
}

TEST(JsonReader, NestedValuesAreTypedAndSkipped) {
  JsonObjectReader r(R"({"a":{"x":[1,{"y":"]"}]},"b":[],"c":1})");
  ASSERT_TRUE(r.valid()) << r.error();
  std::string_view key;
  JsonValue v;
  ASSERT_TRUE(r.next(key, v));
  EXPECT_EQ(v.type, JsonType::kObject);
  ASSERT_TRUE(r.next(key, v));
  EXPECT_EQ(v.type, JsonType::kArray);
  ASSERT_TRUE(r.next(key, v));
  EXPECT_EQ(key, "c");
}

TEST(JsonReader, EmptyObject) {
  JsonObjectReader r(" {} ");
  ASSERT_TRUE(r.valid());
  std::string_view key;
  JsonValue v;
  EXPECT_FALSE(r.next(key, v));
}

TEST(JsonReader, RejectsWhatRfc8259Rejects) {
  for (const char* bad : {"",
                          "   ",
                          "[1]",
                          "\"x\"",
                          "{",
                          "{\"a\"}",
                          "{\"a\":}",
                          "{\"a\":1,}",
                          "{\"a\":1}x",
                          "{'a':1}",
                          "{\"a\":01}",
                          "{\"a\":1.}",
                          "{\"a\":.5}",
                          "{\"a\":+1}",
                          "{\"a\":NaN}",
                          "{\"a\":Infinity}",
                          "{\"a\":tru}",
                          "{\"a\":\"\\x\"}",
                          "{\"a\":\"\\u12\"}",
                          "{\"a\":\"tab\there\"}",
                          "{\"a\":\"open}",
                          "{\"a\":1 \"b\":2}",
                          "{a:1}",
                          "{\"a\":1e}",
                          "{\"a\":1e999}",
                          "{\"a\":[1,]}",
                          "{\"a\":1}}"}) {
    JsonObjectReader r(bad);
    EXPECT_FALSE(r.valid()) << bad;
    EXPECT_NE(r.error(), nullptr) << bad;
  }
}

TEST(JsonReader, NestingLimitStopsDeepDocuments) {
  std::string deep = "{\"a\":";
  for (int n = 0; n < 100; ++n) deep += "[";
  for (int n = 0; n < 100; ++n) deep += "]";
  deep += "}";
  JsonObjectReader r(deep);
  EXPECT_FALSE(r.valid());
  EXPECT_STREQ(r.error(), "JSON nested too deeply");
}

TEST(JsonReader, LongStringsAreMarkedTruncatedNotOverflowed) {
  const std::string doc = "{\"" + std::string(200, 'k') + "\":\"" + std::string(500, 'v') + "\"}";
  JsonObjectReader r(doc);
  ASSERT_TRUE(r.valid());
  std::string_view key;
  JsonValue v;
  ASSERT_TRUE(r.next(key, v));
  EXPECT_TRUE(key.empty());  // an over-long key matches nothing
  EXPECT_TRUE(v.truncated);
  EXPECT_EQ(v.text.size(), JsonObjectReader::kMaxStringBytes);
}

TEST(JsonWriter, WritesValidCompactJson) {
  testing::StringSink sink;
  {
    JsonWriter w(sink);
    w.begin_object()
        .member("s", "q\"\\\n\x01")
        .member("f", 1.5)
        .member("i", -42)
        .member("big", 1234567890123LL)
        .member("b", true);
    w.key("nan").number(std::numeric_limits<double>::quiet_NaN());
    w.key("a").begin_array().integer(1).null().begin_object().end_object().end_array();
    w.member("neg0", -0.0).end_object();
  }
  EXPECT_EQ(sink.data,
            R"({"s":"q\"\\\n\u0001","f":1.5,"i":-42,"big":1234567890123,"b":true,"nan":null,)"
            R"("a":[1,null,{}],"neg0":0})");
  JsonObjectReader check(sink.data);
  EXPECT_TRUE(check.valid()) << check.error();
}

TEST(JsonWriter, PrettyPrintsOneMemberPerLine) {
  testing::StringSink sink;
  {
    JsonWriter w(sink);
    w.set_pretty(true);
    w.begin_object().member("a", 1).member("b", false).end_object();
  }
  EXPECT_EQ(sink.data, "{\n  \"a\": 1,\n  \"b\": false\n}");
}

TEST(JsonWriter, CountingSinkMeasuresWithoutStoring) {
  CountingSink counter;
  {
    JsonWriter w(counter);
    w.begin_object().member("key", std::string_view(std::string(1000, 'x'))).end_object();
  }
  EXPECT_EQ(counter.count(), 1000u + 10u);
}

}  // namespace
}  // namespace rotord::web
