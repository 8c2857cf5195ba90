#pragma once
#include <string_view>

#include "protocol/session.hpp"
#include "rotator/controller.hpp"
#include "web/http_request.hpp"
#include "web/web_api.hpp"

namespace rotord::web {

/// HTTP/1.1 over a byte session: the web UI's files, the REST API and the
/// live event stream (Server-Sent Events), on the same transports as the
/// other protocols. Keep-alive and pipelining are supported; a framing error
/// answers with its status and closes, because the stream cannot be resynced.
class HttpSession final : public protocol::Session {
 public:
  /// A request must be complete within this from its first byte: a total,
  /// not restarted by each byte, or a client trickling a byte every few
  /// seconds would hold its connection slot forever (issue 12). 408 after.
  static constexpr Millis kRequestDeadlineMs = 10000;
  /// A body must arrive at this average rate, counted from the end of the
  /// head after a grace time: a large Content-Length sent a byte at a time is
  /// cut off in seconds, while any real client (an 8 KB settings import
  /// arrives in one go) is far faster. 408 after.
  static constexpr std::size_t kMinBodyBytesPerSecond = 512;
  static constexpr Millis kBodyGraceMs = 2000;
  /// A keep-alive connection with no request for this long is closed:
  /// browsers keep several idle connections per page, and slots are few.
  /// Counted from the end of the last request (or the connection's start);
  /// stray line ends between requests do not restart it.
  static constexpr Millis kIdleTimeoutMs = 5000;
  /// Event stream: an update every 100 ms while an axis moves (10/s), every
  /// second otherwise, and at once when moving, faults or mode change.
  static constexpr Millis kEventPeriodMovingMs = 100;
  static constexpr Millis kEventPeriodIdleMs = 1000;
  /// What a transport sends to a client over its connection limit.
  static constexpr std::string_view kTooManyConnections =
      "HTTP/1.1 503 Service Unavailable\r\nContent-Type: application/json\r\n"
      "Content-Length: 32\r\nConnection: close\r\nRetry-After: 2\r\n\r\n"
      "{\"error\":\"too many connections\"}";

  explicit HttpSession(Api& api);
  /// A pending login's hash still completes (Api::abandon_pending).
  ~HttpSession() override;

  void receive(std::string_view bytes, protocol::ByteSink& out) override;
  void poll(Millis now, protocol::ByteSink& out) override;
  bool wants_close() const override { return close_; }
  bool streaming_events() const { return events_; }
  bool is_event_stream() const override { return events_; }
  bool between_requests() const override {
    return answered_ && !events_ && !pending_ && !close_ && !replay_ && !parser_.in_progress();
  }
  /// A GET response longer than the transport takes at once (the 41 KB
  /// settings schema through the Pico's 11.7 KB lwIP send buffer): the rest
  /// goes out as the transport makes room, the response written again each
  /// time and only its next bytes let through (protocol::WindowSink). If it
  /// came out different (the state changed meanwhile), the connection closes:
  /// the client sees a short body and asks again.
  bool output_pending() const override { return replay_; }
  void write_more(std::size_t room_bytes, protocol::ByteSink& out) override;

 private:
  void handle(const HttpRequest& request, protocol::ByteSink& out);
  /// Whether `request`'s response may go out in windows: GETs of the API and
  /// /metrics (the web UI's files are sent from flash by reference).
  static bool windowed(const HttpRequest& request);
  /// The request has been answered in full: ready for the next one.
  void request_done(bool keep_alive);
  void serve_asset(const HttpRequest& request, const ResponseOptions& options,
                   protocol::ByteSink& out);
  void send_event(Millis now, protocol::ByteSink& out);

  Api& api_;
  HttpRequestParser parser_;
  bool close_ = false;
  bool events_ = false;
  /// Closes with 408 when the request in progress is over its deadline or
  /// its body too slow.
  void check_request_time(Millis now, protocol::ByteSink& out);

  // A login or a new password being hashed (Api::Outcome::kPending): the
  // response goes out from poll(), the connection closes after it, and
  // bytes that arrive meanwhile are dropped (no pipelining behind a login).
  bool answered_ = false;  ///< a request has been answered on this connection
  // A response going out in windows (output_pending): the request stays in
  // the parser until it is done.
  bool replay_ = false;
  bool replay_close_ = false;  ///< bytes arrived meanwhile (pipelining): close after it
  std::size_t replay_sent_ = 0;
  std::uint32_t replay_hash_ = 0;  ///< of the bytes sent so far
  bool pending_ = false;
  std::uint32_t pending_ticket_ = 0;
  // Who opened the event stream: it ends when that login or token does.
  Caller stream_caller_;
  // Timeouts and event periods run on the transport's clock, the `now` of
  // poll(), not on controller time: under `rotord --speedup N` a client must
  // still get its 5 s. Events seen in receive() are stamped at the next poll
  // (a tick later): receive() has no clock.
  Millis now_ = 0;
  bool polled_ = false;
  bool request_timed_ = false;  ///< the request in progress has a start (pending or stamped)
  bool request_start_pending_ = false;
  Millis request_started_ = 0;  ///< its first byte
  bool body_timed_ = false;
  bool body_start_pending_ = false;
  Millis body_started_ = 0;  ///< the end of its head
  bool idle_restart_pending_ = false;
  Millis idle_since_ = 0;  ///< the end of the last request, or the first poll
  Millis last_event_ = 0;
  bool last_moving_ = false;
  bool last_fault_ = false;
  Mode last_mode_ = Mode::kIdle;
};

}  // namespace rotord::web
