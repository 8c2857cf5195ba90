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

  const HttpRequest& request() const { return request_; }
  /// kError: the status to answer with (400, 413, 414, 431, 501, 505) and why.
  int error_status() const { return error_status_; }
  const char* error_message() const { return error_message_; }

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
  bool parse_request_line(std::string_view line);
  bool parse_header_lines(std::string_view headers);
  bool parse_header(std::string_view name, std::string_view value);

  State state_ = State::kStart;
  char head_[kMaxHeadBytes];
  std::size_t head_length_ = 0;
  std::size_t line_start_ = 0;  ///< where the current head line begins
  char body_[kMaxBodyBytes];
  std::size_t body_length_ = 0;
  std::size_t content_length_ = 0;
  bool has_content_length_ = false;
  bool has_host_ = false;
  bool has_cookie_ = false;
  bool has_authorization_ = false;
  HttpRequest request_;
  int error_status_ = 0;
  const char* error_message_ = "";
};

}  // namespace rotord::web
