#include "web/http_stop_only_session.hpp"

#include <cstring>

#include "util/text.hpp"
#include "web/host_check.hpp"

namespace rotord::web {
namespace {

bool is_token_char(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
         (c != '\0' && std::strchr("!#$%&'*+-.^_`|~", c) != nullptr);
}

bool points_into(std::string_view value, const char* buffer, std::size_t size) {
  return !value.empty() && value.data() >= buffer && value.data() < buffer + size;
}

}  // namespace

bool refuse_foreign(const HttpRequest& request, Api& api, const ResponseOptions& options,
                    protocol::ByteSink& out) {
  // DNS rebinding: a foreign page whose name now points here still sends
  // its own name as Host. 421: this server is not the one that name means.
  if (!host_allowed(request.host, api.settings(), api.host_name())) {
    send_error(out, 421,
               "this controller is not known by that host name; add it to web.allowed_hosts",
               options);
    return true;
  }
  if (request.method != Method::kGet && request.method != Method::kHead &&
      !origin_allowed(request.origin, request.host, api.settings())) {
    // A cross-site request: another site's page in the operator's browser.
    send_error(out, 403, "cross-site request refused (Origin is not this controller)", options);
    return true;
  }
  return false;
}

void HttpStopOnlySession::receive(std::string_view bytes, protocol::ByteSink& out) {
  // One byte at a time with HttpRequestParser's rules and limits, so both
  // refuse the same heads with the same status at the same byte.
  for (std::size_t i = 0; i < bytes.size() && state_ != State::kDone; ++i) {
    const char c = bytes[i];
    switch (state_) {
      case State::kStart:
        // RFC 9112 2.2: empty lines before the request line are ignored.
        if (c == '\r' || c == '\n') continue;
        state_ = State::kHead;
        [[fallthrough]];
      case State::kHead:
        if (c == '\r') continue;  // CR LF and bare LF both end a line
        if (c == '\n') {
          if (head_bytes_ == line_start_) {
            head_done(out);
          } else {
            line_done();
            line_start_ = ++head_bytes_;
          }
          continue;
        }
        if (line_start_ == 0 && head_bytes_ >= HttpRequestParser::kMaxRequestLineBytes) {
          fail(414, "request line too long", out);
          continue;
        }
        if (head_bytes_ >= HttpRequestParser::kMaxHeadBytes - 1) {
          fail(431, "request headers too large", out);
          continue;
        }
        ++head_bytes_;
        if (!request_line_done_) {
          request_line_[line_length_++] = c;  // within the 414 limit above
        } else if (line_length_ < sizeof line_) {
          line_[line_length_++] = c;
        } else {
          // Past what is kept: only whether the name ends here matters.
          if (!line_cut_) cut_colon_ = std::memchr(line_, ':', sizeof line_) != nullptr;
          line_cut_ = true;
          if (!cut_colon_) {
            if (c == ':')
              cut_colon_ = true;
            else if (!is_token_char(c))
              cut_bad_name_ = true;
          }
        }
        continue;
      case State::kBody:
        // The body is read and dropped: STOP takes any body (web_api.cpp).
        if (--body_left_ == 0) request_done(out);
        continue;
      case State::kDone:
        break;
    }
  }
}

void HttpStopOnlySession::line_done() {
  const std::size_t length = line_length_;
  const bool cut = line_cut_, cut_colon = cut_colon_;
  bool bad_name = cut_bad_name_;
  line_length_ = 0;
  line_cut_ = cut_colon_ = cut_bad_name_ = false;
  // The first refusal stands; later lines are only counted, as the parser
  // checks the head once it is complete.
  if (fields_.error_status != 0) return;
  if (!request_line_done_) {
    request_line_done_ = true;
    fields_.request_line(std::string_view(request_line_, length));
    return;
  }
  const std::string_view field(line_, length);
  if (cut) {
    const std::size_t colon = field.find(':');
    if (colon == std::string_view::npos && cut_colon) {
      // A name longer than what is kept: no header this reads, so ignored
      // (as the parser ignores unknown names) once it is checked.
      if (field.front() == ' ' || field.front() == '\t') {
        fields_.fail(400, "folded header lines are not allowed");
      } else {
        for (char ch : field) bad_name = bad_name || !is_token_char(ch);
        if (bad_name) fields_.fail(400, "malformed header name");
      }
      return;
    }
    // A value this needs whole, cut: the request is refused (the busy
    // answer). Counted as present, so a second Host is still a 400.
    const std::string_view name = field.substr(0, colon);
    if (colon != std::string_view::npos &&
        (text::iequals(name, "Host") || text::iequals(name, "Origin") ||
         text::iequals(name, "Content-Length"))) {
      unreadable_ = true;
      if (text::iequals(name, "Host")) fields_.has_host = true;
      return;
    }
  }
  if (!fields_.header_line(field)) return;
  // Kept out of the line buffer, which the next line overwrites; the other
  // values are not needed (STOP is for anyone: no cookie or token).
  HttpRequest& r = fields_.request;
  if (points_into(r.host, line_, sizeof line_) && !keep(r.host, host_, sizeof host_))
    unreadable_ = true;
  if (points_into(r.origin, line_, sizeof line_) && !keep(r.origin, origin_, sizeof origin_))
    unreadable_ = true;
  r.cookie = r.authorization = r.if_none_match = {};
}

bool HttpStopOnlySession::keep(std::string_view& value, char* storage, std::size_t size) {
  if (value.size() > size) return false;
  std::memcpy(storage, value.data(), value.size());
  value = std::string_view(storage, value.size());
  return true;
}

void HttpStopOnlySession::head_done(protocol::ByteSink& out) {
  if (fields_.error_status == 0) fields_.head_done(HttpRequestParser::kMaxBodyBytes);
  if (fields_.error_status != 0) {
    fail(fields_.error_status, fields_.error_message, out);
    return;
  }
  body_left_ = fields_.content_length;
  if (body_left_ == 0) {
    request_done(out);
  } else {
    state_ = State::kBody;
  }
}

void HttpStopOnlySession::request_done(protocol::ByteSink& out) {
  state_ = State::kDone;
  const HttpRequest& r = fields_.request;
  // As HttpSession in stop-only mode: anything but POST /api/stop is refused
  // (the transport sends its busy answer), and so is a STOP this could not
  // read whole.
  if (!command_arrives(!unreadable_ && r.method == Method::kPost && r.path == "/api/stop")) return;
  const ResponseOptions options{r.keep_alive, false, {}};
  if (refuse_foreign(r, api_, options, out)) return;
  // STOP answers from the route table at once (never kPending or a stream).
  api_.handle(r, out, options, peer());
}

void HttpStopOnlySession::fail(int status, const char* message, protocol::ByteSink& out) {
  // A framing error: its status, then the close (as HttpSession answers it).
  send_error(out, status, message, {false, false, {}});
  state_ = State::kDone;
}

}  // namespace rotord::web
