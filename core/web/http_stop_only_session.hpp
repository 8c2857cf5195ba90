#pragma once
#include <cstddef>
#include <string_view>

#include "protocol/session.hpp"
#include "web/http_request.hpp"
#include "web/http_response.hpp"
#include "web/web_api.hpp"

namespace rotord::web {

/// The web port's STOP-only exchange (net::Admission's kStopOnly) in a few
/// hundred bytes: a newcomer to a full web port may still POST /api/stop.
/// A full HttpSession holds a 2 KB head and an 8 KB body buffer, which the
/// Pico W has no RAM for beside its four; this reads one request a line at a
/// time with the same rules (HeadFields, the same limits: 414, 431, 413, ...)
/// and keeps only what the answer needs (the request line, Host, Origin);
/// other header values and the body are read and dropped. What it answers is
/// what HttpSession answers in stop-only mode, byte for byte: POST /api/stop
/// through the same checks and the same Api handler; a malformed head its
/// error; any other request nothing, so the transport sends the port's busy
/// refusal (HttpSession::kTooManyConnections). The transport ends the
/// exchange at its deadline (net::kStopOnlyExchangeMs). Both transports use
/// it: the Pico W's shared stop-only slot and rotord on Linux.
class HttpStopOnlySession final : public protocol::Session {
 public:
  /// The request line whole (longer is 414, as in HttpRequestParser).
  static constexpr std::size_t kRequestLineBytes = HttpRequestParser::kMaxRequestLineBytes;
  /// A header line kept for the rules: longer ones are read to their end,
  /// their name still checked, the value cut (only Host, Origin and
  /// Content-Length matter here; one of them longer refuses the request).
  static constexpr std::size_t kHeaderLineBytes = 160;
  static constexpr std::size_t kHostBytes = kHeaderLineBytes;
  static constexpr std::size_t kOriginBytes = kHeaderLineBytes;

  explicit HttpStopOnlySession(Api& api) : api_(api) { set_stop_only(); }

  void receive(std::string_view bytes, protocol::ByteSink& out) override;
  bool wants_close() const override { return state_ == State::kDone; }

 private:
  enum class State : unsigned char { kStart, kHead, kBody, kDone };

  /// A head line ended (without its line end).
  void line_done();
  /// The empty line: the head is complete.
  void head_done(protocol::ByteSink& out);
  /// The whole request (head and body) is in: STOP, or nothing.
  void request_done(protocol::ByteSink& out);
  void fail(int status, const char* message, protocol::ByteSink& out);
  /// Copies a kept header value out of the line buffer (the next line
  /// overwrites it); false when it does not fit.
  bool keep(std::string_view& value, char* storage, std::size_t size);

  Api& api_;
  State state_ = State::kStart;
  HeadFields fields_;
  bool request_line_done_ = false;
  char request_line_[kRequestLineBytes];
  char line_[kHeaderLineBytes];
  std::size_t line_length_ = 0;
  bool line_cut_ = false;       ///< the line is longer than line_: the rest is dropped
  bool cut_colon_ = false;      ///< ... and its colon was among the dropped bytes
  bool cut_bad_name_ = false;   ///< ... and so was a byte no header name may hold
  std::size_t head_bytes_ = 0;  ///< counted as HttpRequestParser stores them
  std::size_t line_start_ = 0;  ///< head_bytes_ where this line began
  bool unreadable_ = false;     ///< a Host, Origin or Content-Length too long to keep
  char host_[kHostBytes];
  char origin_[kOriginBytes];
  std::size_t body_left_ = 0;
};

/// DNS rebinding and cross-site requests, as every HTTP request is checked
/// before its route: answers 421 or 403 and returns true when refused.
bool refuse_foreign(const HttpRequest& request, Api& api, const ResponseOptions& options,
                    protocol::ByteSink& out);

}  // namespace rotord::web
