#pragma once
#include <cstddef>
#include <string_view>

namespace rotord::web {

enum class Method : unsigned char { kGet, kHead, kPost, kPut, kDelete, kOther };

/// One parsed request. Views point into the parser's buffers and stay valid
/// until the parser is reset for the next request.
struct HttpRequest {
  Method method = Method::kOther;
  std::string_view method_text;
  std::string_view path;   ///< without the query string
  std::string_view query;  ///< after '?', still percent-encoded; empty when none
  bool keep_alive = true;
  bool json_body = false;  ///< Content-Type: application/json
  std::string_view if_none_match;
  std::string_view host;           ///< the Host header as sent (name[:port]); empty when absent
  std::string_view origin;         ///< the Origin header (scheme://host[:port]); empty when absent
  std::string_view cookie;         ///< the first Cookie header; empty when absent
  std::string_view authorization;  ///< the Authorization header; empty when absent
  std::string_view body;
};

/// The rules for a request head, one line at a time: what the full parser
/// below and the stop-only session (http_stop_only_session.hpp, which keeps
/// no whole head) both apply, so both refuse the same heads the same way.
/// Views in `request` point into the lines given; they stay valid only as
/// long as those do.
struct HeadFields {
  HttpRequest request;
  std::size_t content_length = 0;
  bool has_content_length = false;
  bool has_host = false;
  bool has_cookie = false;
  bool has_authorization = false;
  int error_status = 0;  ///< when a line is refused: 400, 413, 501, 505
  const char* error_message = "";

  /// METHOD SP request-target SP HTTP-version. False: refused (error_status).
  bool request_line(std::string_view line);
  /// One header field line (no line end). False: refused (error_status).
  bool header_line(std::string_view field);
  /// After the last header line: the body's length within `max_body_bytes`.
  bool head_done(std::size_t max_body_bytes);
  /// Refuses the head with `status`; returns false.
  bool fail(int status, const char* message);

 private:
  bool header(std::string_view name, std::string_view value);
};

/// Incremental HTTP/1.1 request parser over fixed buffers (the same code runs
/// on the Pico's lwIP, where a request arrives in pieces of any size). Limits
/// are named constants; exceeding one is an error with its HTTP status, and
/// the excess bytes are never stored. Bodies need a Content-Length; chunked
/// uploads are refused (no client of this API sends them).
class HttpRequestParser {
 public:
  static constexpr std::size_t kMaxRequestLineBytes = 256;  ///< 414 beyond
  static constexpr std::size_t kMaxHeadBytes = 2048;        ///< line + headers; 431 beyond
  /// 413 beyond. Holds the whole settings document with room to grow: the
  /// settings page's import posts back what its export saved, pretty-printed
  /// (about 4.5 KB with the Raspberry Pi rows; 3.7 KB compact). A unit test
  /// keeps the two in step. 4 KB more per HTTP session on the Pico W.
  static constexpr std::size_t kMaxBodyBytes = 8192;

  enum class Status : unsigned char { kNeedMore, kComplete, kError };

  /// Consumes bytes from the front of `in` until one request is complete (the
  /// rest stays in `in`, e.g. a pipelined request) or an error is found.
  Status feed(std::string_view& in);

  const HttpRequest& request() const { return fields_.request; }
  /// kError: the status to answer with (400, 413, 414, 431, 501, 505) and why.
  int error_status() const { return fields_.error_status; }
  const char* error_message() const { return fields_.error_message; }

  /// Ready for the next request on the same connection.
  void reset();
  /// Bytes of an unfinished request have arrived.
  bool in_progress() const { return state_ != State::kStart || head_length_ > 0; }
  /// The head is complete and the body is arriving.
  bool in_body() const { return state_ == State::kBody; }
  /// Body bytes received so far.
  std::size_t body_received() const { return body_length_; }

 private:
  enum class State : unsigned char { kStart, kHead, kBody, kComplete, kError };

  Status fail(int status, const char* message);
  bool parse_head();

  State state_ = State::kStart;
  char head_[kMaxHeadBytes];
  std::size_t head_length_ = 0;
  std::size_t line_start_ = 0;  ///< where the current head line begins
  char body_[kMaxBodyBytes];
  std::size_t body_length_ = 0;
  HeadFields fields_;
};

}  // namespace rotord::web
