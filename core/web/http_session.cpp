#include "web/http_session.hpp"

#include <cstdio>

#include "protocol/window_sink.hpp"
#include "web/assets.hpp"
#include "web/http_response.hpp"
#include "web/http_stop_only_session.hpp"

namespace rotord::web {

HttpSession::HttpSession(Api& api) : api_(api) {}

HttpSession::~HttpSession() {
  if (pending_) api_.abandon_pending(pending_ticket_);
}

void HttpSession::receive(std::string_view bytes, protocol::ByteSink& out) {
  // A request pipelined behind a long response: the parser still holds that
  // one, so this connection closes after it; the client sends it again on
  // a new one (as HTTP clients do when a server closes a pipeline).
  if (replay_) {
    replay_close_ = true;
    return;
  }
  // An event stream only talks; anything the client sends is ignored.
  if (close_ || events_ || pending_) return;
  while (!bytes.empty() && !close_ && !events_ && !pending_) {
    const auto status = parser_.feed(bytes);
    if (status == HttpRequestParser::Status::kNeedMore) break;
    if (status == HttpRequestParser::Status::kError) {
      send_error(out, parser_.error_status(), parser_.error_message(), {false, false, {}});
      close_ = true;
      break;
    }
    const HttpRequest& request = parser_.request();
    // Over capacity only POST /api/stop is served (net::Admission's
    // kStopOnly); the transport answers anything else with its 503.
    if (!command_arrives(request.method == Method::kPost && request.path == "/api/stop")) {
      close_ = true;
      break;
    }
    // Only the last request of what arrived may go out in windows: the
    // parser must keep it until then. A transport that takes everything
    // (Linux) gets it directly.
    if (bytes.empty() && windowed(request) && out.room() != static_cast<std::size_t>(-1)) {
      const bool closing = close_;
      protocol::WindowSink window(out, 0, static_cast<std::size_t>(-1),
                                  protocol::WindowSink::Cut::kBytes);
      handle(request, window);
      if (window.written() < window.total() && !close_ && !events_ && !pending_) {
        replay_ = true;
        replay_sent_ = window.written();
        replay_hash_ = window.sent_hash();
        close_ = closing;  // a Connection: close applies once it is all out
        return;
      }
    } else {
      handle(request, out);
    }
    request_done(request.keep_alive && !stop_only());
  }
  // What is left is the start of the next request: its deadline begins now.
  if (parser_.in_progress() && !request_timed_) request_timed_ = request_start_pending_ = true;
  if (parser_.in_body() && !body_timed_) body_timed_ = body_start_pending_ = true;
}

void HttpSession::request_done(bool keep_alive) {
  // A pending login answers from poll() and then closes; an event stream
  // runs until the client leaves.
  if (!keep_alive && !pending_ && !events_) close_ = true;
  answered_ = true;
  parser_.reset();
  request_timed_ = request_start_pending_ = false;
  body_timed_ = body_start_pending_ = false;
  idle_restart_pending_ = true;
}

bool HttpSession::windowed(const HttpRequest& request) {
  return request.method == Method::kGet &&
         (request.path.starts_with("/api/") || request.path == "/metrics");
}

void HttpSession::write_more(std::size_t room_bytes, protocol::ByteSink& out) {
  if (!replay_) return;
  const HttpRequest& request = parser_.request();
  const bool closing = close_;
  protocol::WindowSink window(out, replay_sent_, room_bytes, protocol::WindowSink::Cut::kBytes,
                              replay_hash_);
  handle(request, window);
  close_ = closing;
  if (window.total() < replay_sent_ || window.mismatch()) {
    // Not the response whose start went out: it cannot be completed.
    replay_ = false;
    close_ = true;
    return;
  }
  replay_sent_ += window.written();
  replay_hash_ = window.sent_hash();
  if (replay_sent_ < window.total()) return;
  replay_ = false;
  request_done(request.keep_alive && !replay_close_);
}

void HttpSession::handle(const HttpRequest& request, protocol::ByteSink& out) {
  const ResponseOptions options{request.keep_alive, request.method == Method::kHead, {}};
  if (refuse_foreign(request, api_, options, out)) {
    // 421 or 403, as for the stop-only exchange (http_stop_only_session.hpp).
  } else if (request.path == "/metrics" && !api_.page_allowed(request)) {
    // Positions, targets and who connects: a read token or a login when
    // access control is on. /healthz says only ok or why not, and stays open
    // to supervisors.
    send_error(out, 401, "log in or send a read token first", options);
  } else if (request.path == "/metrics") {
    api_.handle_metrics(request, out, options);
  } else if (request.path == "/healthz") {
    api_.handle_health(request, out, options);
  } else if (request.path.starts_with("/api/")) {
    switch (api_.handle(request, out, options, peer())) {
      case Api::Outcome::kPending:
        pending_ = true;
        pending_ticket_ = api_.pending_ticket();
        return;
      case Api::Outcome::kStartEvents:
        events_ = true;
        stream_caller_ = api_.last_caller();
        out.write("retry: 1000\n\n");  // EventSource reconnects after 1 s
        send_event(now_, out);
        return;
      case Api::Outcome::kClose:
        close_ = true;
        return;
      case Api::Outcome::kDone:
        break;
    }
  } else if ((request.method == Method::kGet || request.method == Method::kHead) &&
             !api_.page_allowed(request)) {
    // Access control is on and nobody logged in: pages go to the login page.
    ResponseOptions o = options;
    const bool page = request.path == "/" || request.path.ends_with(".html");
    o.extra_headers = page ? "Location: /login.html\r\n" : "";
    send_error(out, page ? 303 : 401, "log in first", o);
  } else if (request.method == Method::kGet || request.method == Method::kHead) {
    serve_asset(request, options, out);
  } else {
    ResponseOptions o = options;
    o.extra_headers = "Allow: GET, HEAD\r\n";
    send_error(out, 405, "method not allowed here", o);
  }
}

void HttpSession::serve_asset(const HttpRequest& request, const ResponseOptions& options,
                              protocol::ByteSink& out) {
  const Asset* asset = find_asset(request.path);
  if (asset == nullptr) {
    send_error(out, 404, "not found", options);
    return;
  }
  // Always gzip: every browser accepts it, and the Pico has no room for a
  // second, uncompressed copy (curl users add --compressed). no-cache makes
  // the browser revalidate with the ETag, so an update shows at once.
  char headers[160];
  ResponseOptions o = options;
  const bool unchanged = request.if_none_match == asset->etag;
  const int n = std::snprintf(headers, sizeof(headers), "%sCache-Control: no-cache\r\nETag: %s\r\n",
                              unchanged ? "" : "Content-Encoding: gzip\r\n", asset->etag);
  if (n > 0 && static_cast<std::size_t>(n) < sizeof(headers))
    o.extra_headers = std::string_view(headers, static_cast<std::size_t>(n));
  if (unchanged) {
    write_head(out, 304, asset->content_type, -1, o);
    return;
  }
  write_head(out, 200, asset->content_type, static_cast<long>(asset->gzip_size), o);
  if (options.head_only) return;
  out.write(std::string_view(reinterpret_cast<const char*>(asset->gzip_data), asset->gzip_size));
}

void HttpSession::poll(Millis now, protocol::ByteSink& out) {
  if (!polled_ || idle_restart_pending_) idle_since_ = now;
  if (request_start_pending_) request_started_ = now;
  if (body_start_pending_) body_started_ = now;
  polled_ = true;
  idle_restart_pending_ = request_start_pending_ = body_start_pending_ = false;
  now_ = now;
  if (close_) return;
  // A long response going out: the transport paces it (write_more), and a
  // reader that stopped is the admission rule's idle client.
  if (replay_) return;
  if (pending_) {
    if (api_.finish_pending(pending_ticket_, out, {false, false, {}})) {
      pending_ = false;
      close_ = true;
    }
    return;
  }
  if (events_) {
    if (!api_.still_allowed(stream_caller_)) {
      close_ = true;  // logged out, expired, a new password, a revoked token
      return;
    }
    const RotatorStatus s = api_.controller().status();
    const bool changed =
        s.moving() != last_moving_ || s.any_fault() != last_fault_ || s.mode != last_mode_;
    const Millis period = s.moving() ? kEventPeriodMovingMs : kEventPeriodIdleMs;
    if (changed || now - last_event_ >= period) send_event(now, out);
    return;
  }
  if (parser_.in_progress()) {
    check_request_time(now, out);
  } else if (now - idle_since_ > kIdleTimeoutMs) {
    close_ = true;
  }
}

void HttpSession::check_request_time(Millis now, protocol::ByteSink& out) {
  const char* why = nullptr;
  if (now - request_started_ > kRequestDeadlineMs) {
    why = "request not completed in time";
  } else if (parser_.in_body()) {
    const Millis late = now - body_started_ - kBodyGraceMs;
    if (late > 0 &&
        parser_.body_received() * 1000 < static_cast<std::size_t>(late) * kMinBodyBytesPerSecond)
      why = "request body arriving too slowly";
  }
  if (why == nullptr) return;
  send_error(out, 408, why, {false, false, {}});
  close_ = true;
}

void HttpSession::send_event(Millis now, protocol::ByteSink& out) {
  const RotatorStatus s = api_.controller().status();
  last_event_ = now;
  last_moving_ = s.moving();
  last_fault_ = s.any_fault();
  last_mode_ = s.mode;
  out.write("data: ");
  {
    JsonWriter w(out);
    api_.write_status(w);
  }
  out.write("\n\n");
}

}  // namespace rotord::web
