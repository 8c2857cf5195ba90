#include "web/http_request.hpp"

#include <gtest/gtest.h>

#include <string>

namespace rotord::web {
namespace {

using Status = HttpRequestParser::Status;

class HttpParse : public ::testing::Test {
 protected:
  HttpRequestParser p;
  Status feed_all(const std::string& bytes) {
    std::string_view in = bytes;
    return p.feed(in);
  }
};

TEST_F(HttpParse, SimpleGet) {
  ASSERT_EQ(feed_all("GET /api/status?x=1 HTTP/1.1\r\nHost: a\r\n\r\n"), Status::kComplete);
  EXPECT_EQ(p.request().method, Method::kGet);
  EXPECT_EQ(p.request().path, "/api/status");
  EXPECT_TRUE(p.request().keep_alive);
  EXPECT_TRUE(p.request().body.empty());
}

TEST_F(HttpParse, ANulInAHeaderNameOrMethodIsMalformed) {
  // RFC 9110 5.6.2: a token has no NUL (strchr found the string's end).
  ASSERT_EQ(feed_all(std::string("GET / HTTP/1.1\r\nHost: a\r\nX\0Y: 1\r\n\r\n", 35)),
            Status::kError);
  EXPECT_EQ(p.error_status(), 400);
  p.reset();
  ASSERT_EQ(feed_all(std::string("G\0T / HTTP/1.1\r\nHost: a\r\n\r\n", 27)), Status::kError);
  EXPECT_EQ(p.error_status(), 400);
}

TEST_F(HttpParse, PostWithBodyArrivingOneByteAtATime) {
  const std::string req =
      "POST /api/goto HTTP/1.1\r\ncontent-type: Application/JSON; charset=utf-8\r\n"
      "Content-Length: 10\r\n\r\n{\"az\":90}X";
  for (std::size_t i = 0; i + 1 < req.size(); ++i) {
    std::string_view one(&req[i], 1);
    ASSERT_EQ(p.feed(one), Status::kNeedMore) << i;
    EXPECT_TRUE(one.empty());
  }
  std::string_view last(&req.back(), 1);
  ASSERT_EQ(p.feed(last), Status::kComplete);
  EXPECT_EQ(p.request().method, Method::kPost);
  EXPECT_TRUE(p.request().json_body);
  EXPECT_EQ(p.request().body, "{\"az\":90}X");
}

TEST_F(HttpParse, PipelinedRequestsStayInTheInput) {
  std::string both = "GET /a HTTP/1.1\r\n\r\nGET /b HTTP/1.0\n\n";
  std::string_view in = both;
  ASSERT_EQ(p.feed(in), Status::kComplete);
  EXPECT_EQ(p.request().path, "/a");
  EXPECT_EQ(in, "GET /b HTTP/1.0\n\n");
  p.reset();
  ASSERT_EQ(p.feed(in), Status::kComplete);
  EXPECT_EQ(p.request().path, "/b");
  EXPECT_FALSE(p.request().keep_alive);  // HTTP/1.0 default
}

TEST_F(HttpParse, ConnectionHeaders) {
  ASSERT_EQ(feed_all("GET / HTTP/1.1\r\nConnection: Close\r\n\r\n"), Status::kComplete);
  EXPECT_FALSE(p.request().keep_alive);
  p.reset();
  ASSERT_EQ(feed_all("GET / HTTP/1.0\r\nConnection: keep-alive\r\n\r\n"), Status::kComplete);
  EXPECT_TRUE(p.request().keep_alive);
}

TEST_F(HttpParse, LeadingEmptyLinesAreIgnored) {
  ASSERT_EQ(feed_all("\r\n\r\nHEAD / HTTP/1.1\r\n\r\n"), Status::kComplete);
  EXPECT_EQ(p.request().method, Method::kHead);
}

TEST_F(HttpParse, OtherMethodsParseForA405) {
  ASSERT_EQ(feed_all("PATCH /api/status HTTP/1.1\r\n\r\n"), Status::kComplete);
  EXPECT_EQ(p.request().method, Method::kOther);
  EXPECT_EQ(p.request().method_text, "PATCH");
}

TEST_F(HttpParse, PutDeleteAndTheQueryString) {
  ASSERT_EQ(feed_all("DELETE /api/tle?object=ISS%20(ZARYA)&x=1 HTTP/1.1\r\n\r\n"),
            Status::kComplete);
  EXPECT_EQ(p.request().method, Method::kDelete);
  EXPECT_EQ(p.request().path, "/api/tle");
  EXPECT_EQ(p.request().query, "object=ISS%20(ZARYA)&x=1");
  p.reset();
  ASSERT_EQ(feed_all("PUT /api/tle HTTP/1.1\r\nContent-Length: 0\r\n\r\n"), Status::kComplete);
  EXPECT_EQ(p.request().method, Method::kPut);
  EXPECT_EQ(p.request().query, "");
}

std::string many_headers(int count) {
  std::string h;
  for (int n = 0; n < count; ++n) h += "X-Header-" + std::to_string(n) + ": value\r\n";
  return h;
}

struct BadCase {
  const char* name;
  std::string request;
  int status;
};

TEST_F(HttpParse, ErrorsCarryTheirStatus) {
  const BadCase cases[] = {
      {"garbage", "\x01\x02\x03 nonsense\r\n\r\n", 400},
      {"no version", "GET /\r\n\r\n", 400},
      {"extra space", "GET / x HTTP/1.1\r\n\r\n", 400},
      {"not a path", "GET http://x/ HTTP/1.1\r\n\r\n", 400},
      {"http2", "PRI * HTTP/2.0\r\n\r\n", 505},
      {"header without colon", "GET / HTTP/1.1\r\nBroken\r\n\r\n", 400},
      {"folded header", "GET / HTTP/1.1\r\nA: b\r\n c\r\n\r\n", 400},
      {"space in header name", "GET / HTTP/1.1\r\nA b: c\r\n\r\n", 400},
      {"signed length", "POST / HTTP/1.1\r\nContent-Length: -1\r\n\r\n", 400},
      {"hex length", "POST / HTTP/1.1\r\nContent-Length: 0x10\r\n\r\n", 400},
      {"two lengths", "POST / HTTP/1.1\r\nContent-Length: 1\r\nContent-Length: 2\r\n\r\n", 400},
      {"chunked", "POST / HTTP/1.1\r\nTransfer-Encoding: chunked\r\n\r\n", 501},
      {"body too large",
       "POST / HTTP/1.1\r\nContent-Length: " +
           std::to_string(HttpRequestParser::kMaxBodyBytes + 1) + "\r\n\r\n",
       413},
      {"huge length", "POST / HTTP/1.1\r\nContent-Length: 99999999999999999999\r\n\r\n", 413},
      {"long request line",
       "GET /" + std::string(HttpRequestParser::kMaxRequestLineBytes, 'a') + " HTTP/1.1\r\n\r\n",
       414},
      {"many headers", "GET / HTTP/1.1\r\n" + many_headers(300) + "\r\n", 431},
  };
  for (const BadCase& c : cases) {
    HttpRequestParser parser;
    std::string_view in = c.request;
    EXPECT_EQ(parser.feed(in), Status::kError) << c.name;
    EXPECT_EQ(parser.error_status(), c.status) << c.name;
    EXPECT_STRNE(parser.error_message(), "") << c.name;
  }
}

TEST_F(HttpParse, AnErrorIsSticky) {
  ASSERT_EQ(feed_all("GET / HTTP/3\r\n\r\n"), Status::kError);
  EXPECT_EQ(feed_all("GET / HTTP/1.1\r\n\r\n"), Status::kError);
}

TEST_F(HttpParse, BodyExactlyAtTheLimitIsAccepted) {
  const std::string body(HttpRequestParser::kMaxBodyBytes, 'b');
  ASSERT_EQ(feed_all("POST / HTTP/1.1\r\nContent-Length: " + std::to_string(body.size()) +
                     "\r\n\r\n" + body),
            Status::kComplete);
  EXPECT_EQ(p.request().body.size(), body.size());
}

TEST_F(HttpParse, HeadAtTheLimitIsAcceptedAndOneMoreByteIsNot) {
  // Request line + one header filling the head buffer exactly (the final
  // CRLF of each line is stored as one LF).
  const std::string line = "GET / HTTP/1.1";
  const std::size_t room = HttpRequestParser::kMaxHeadBytes - line.size() - 1 - 1;
  const std::string header = "X: " + std::string(room - 3, 'v');
  ASSERT_EQ(feed_all(line + "\r\n" + header + "\r\n\r\n"), Status::kComplete);
  p.reset();
  EXPECT_EQ(feed_all(line + "\r\n" + header + "v\r\n\r\n"), Status::kError);
  EXPECT_EQ(p.error_status(), 431);
}

}  // namespace
}  // namespace rotord::web
