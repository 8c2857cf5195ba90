#include "web/http_request.hpp"

#include <cstring>

#include "util/slice.hpp"
#include "util/text.hpp"

namespace rotord::web {
namespace {

std::string_view trim_ows(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
  return s;
}

/// Case-insensitive search for a token in a header value list ("keep-alive, Upgrade").
bool contains_token(std::string_view list, std::string_view token) {
  while (!list.empty()) {
    const std::size_t comma = list.find(',');
    std::string_view item = trim_ows(text::slice(list, 0, comma));
    const std::size_t semi = item.find(';');
    if (text::iequals(trim_ows(text::slice(item, 0, semi)), token)) return true;
    if (comma == std::string_view::npos) break;
    list.remove_prefix(comma + 1);
  }
  return false;
}

bool is_token_char(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
         (c != '\0' && std::strchr("!#$%&'*+-.^_`|~", c) != nullptr);
}

}  // namespace

void HttpRequestParser::reset() {
  state_ = State::kStart;
  head_length_ = 0;
  line_start_ = 0;
  body_length_ = 0;
  fields_ = HeadFields{};
}

HttpRequestParser::Status HttpRequestParser::fail(int status, const char* message) {
  state_ = State::kError;
  fields_.error_status = status;
  fields_.error_message = message;
  return Status::kError;
}

HttpRequestParser::Status HttpRequestParser::feed(std::string_view& in) {
  while (!in.empty()) {
    switch (state_) {
      case State::kComplete:
        return Status::kComplete;
      case State::kError:
        return Status::kError;
      case State::kStart:
        // RFC 9112 2.2: ignore empty lines before a request line (keep-alive
        // clients sometimes send a stray CRLF after a body).
        if (in.front() == '\r' || in.front() == '\n') {
          in.remove_prefix(1);
          continue;
        }
        state_ = State::kHead;
        continue;
      case State::kHead: {
        const char c = in.front();
        in.remove_prefix(1);
        if (c == '\r') continue;  // CR LF and bare LF both end a line (RFC 9112 2.2)
        if (c == '\n') {
          if (head_length_ == line_start_) {  // empty line: end of the head
            if (!parse_head()) return Status::kError;
            if (fields_.content_length > 0) {
              state_ = State::kBody;
              continue;
            }
            state_ = State::kComplete;
            return Status::kComplete;
          }
          head_[head_length_++] = '\n';  // room kept by the check below
          line_start_ = head_length_;
          continue;
        }
        if (line_start_ == 0 && head_length_ >= kMaxRequestLineBytes)
          return fail(414, "request line too long");
        if (head_length_ >= kMaxHeadBytes - 1) return fail(431, "request headers too large");
        head_[head_length_++] = c;
        continue;
      }
      case State::kBody: {
        std::size_t take = fields_.content_length - body_length_;
        if (take > in.size()) take = in.size();
        std::memcpy(body_ + body_length_, in.data(), take);
        body_length_ += take;
        in.remove_prefix(take);
        if (body_length_ == fields_.content_length) {
          fields_.request.body = std::string_view(body_, body_length_);
          state_ = State::kComplete;
          return Status::kComplete;
        }
        continue;
      }
    }
  }
  if (state_ == State::kComplete) return Status::kComplete;
  if (state_ == State::kError) return Status::kError;
  return Status::kNeedMore;
}

bool HttpRequestParser::parse_head() {
  std::string_view head(head_, head_length_);
  const std::size_t eol = head.find('\n');
  bool ok = fields_.request_line(text::slice(head, 0, eol));
  std::string_view headers =
      eol == std::string_view::npos ? std::string_view{} : text::slice(head, eol + 1);
  while (ok && !headers.empty()) {
    const std::size_t nl = headers.find('\n');
    ok = fields_.header_line(text::slice(headers, 0, nl));
    headers = nl == std::string_view::npos ? std::string_view{} : text::slice(headers, nl + 1);
  }
  ok = ok && fields_.head_done(kMaxBodyBytes);
  if (!ok) state_ = State::kError;
  return ok;
}

bool HeadFields::fail(int status, const char* message) {
  error_status = status;
  error_message = message;
  return false;
}

bool HeadFields::head_done(std::size_t max_body_bytes) {
  if (content_length > max_body_bytes) return fail(413, "request body too large");
  return true;
}

bool HeadFields::request_line(std::string_view line) {
  // Request line: METHOD SP request-target SP HTTP-version
  const std::size_t sp1 = line.find(' ');
  const std::size_t sp2 = sp1 == std::string_view::npos ? sp1 : line.find(' ', sp1 + 1);
  if (sp1 == 0 || sp2 == std::string_view::npos ||
      line.find(' ', sp2 + 1) != std::string_view::npos) {
    fail(400, "malformed request line");
    return false;
  }
  const std::string_view method = text::slice(line, 0, sp1);
  const std::string_view target = text::slice(line, sp1 + 1, sp2 - sp1 - 1);
  const std::string_view version = text::slice(line, sp2 + 1);
  for (char c : method) {
    if (!is_token_char(c)) {
      fail(400, "malformed request line");
      return false;
    }
  }
  if (!version.starts_with("HTTP/")) {
    fail(400, "malformed request line");
    return false;
  }
  if (version != "HTTP/1.1" && version != "HTTP/1.0") {
    fail(505, "only HTTP/1.0 and HTTP/1.1 are supported");
    return false;
  }
  if (target.empty() || target.front() != '/') {
    fail(400, "the request target must be a path");
    return false;
  }
  request.method_text = method;
  request.method = method == "GET"      ? Method::kGet
                   : method == "HEAD"   ? Method::kHead
                   : method == "POST"   ? Method::kPost
                   : method == "PUT"    ? Method::kPut
                   : method == "DELETE" ? Method::kDelete
                                        : Method::kOther;
  const std::size_t question = target.find('?');
  request.path = text::slice(target, 0, question);
  request.query = question == std::string_view::npos
                      ? std::string_view{}
                      : text::slice(target, question + 1, std::string_view::npos);
  request.keep_alive = version == "HTTP/1.1";
  return true;
}

bool HeadFields::header_line(std::string_view field) {
  if (field.empty()) return fail(400, "malformed header line");
  if (field.front() == ' ' || field.front() == '\t')
    return fail(400, "folded header lines are not allowed");
  const std::size_t colon = field.find(':');
  if (colon == std::string_view::npos || colon == 0) return fail(400, "malformed header line");
  const std::string_view name = text::slice(field, 0, colon);
  for (char c : name) {
    if (!is_token_char(c)) return fail(400, "malformed header name");
  }
  return header(name, trim_ows(text::slice(field, colon + 1)));
}

bool HeadFields::header(std::string_view name, std::string_view value) {
  if (text::iequals(name, "Content-Length")) {
    // Digits only (no sign); a second, different Content-Length is smuggling.
    std::size_t n = 0;
    for (char c : value) {
      if (c < '0' || c > '9') {
        fail(400, "invalid Content-Length");
        return false;
      }
      // Saturate: anything past the body limit is refused with 413 anyway.
      if (n <= HttpRequestParser::kMaxBodyBytes) n = n * 10 + static_cast<std::size_t>(c - '0');
    }
    if (value.empty()) {
      fail(400, "invalid Content-Length");
      return false;
    }
    if (has_content_length && n != content_length) {
      fail(400, "conflicting Content-Length headers");
      return false;
    }
    has_content_length = true;
    content_length = n;
  } else if (text::iequals(name, "Transfer-Encoding")) {
    fail(501, "chunked request bodies are not supported; send a Content-Length");
    return false;
  } else if (text::iequals(name, "Connection")) {
    if (contains_token(value, "close")) request.keep_alive = false;
    if (contains_token(value, "keep-alive")) request.keep_alive = true;
  } else if (text::iequals(name, "Content-Type")) {
    const std::string_view media = trim_ows(text::slice(value, 0, value.find(';')));
    request.json_body = text::iequals(media, "application/json");
  } else if (text::iequals(name, "If-None-Match")) {
    request.if_none_match = value;
  } else if (text::iequals(name, "Host")) {
    // Two Host headers are a request smuggling attempt (RFC 9112 3.2).
    if (has_host) {
      fail(400, "more than one Host header");
      return false;
    }
    has_host = true;
    request.host = value;
  } else if (text::iequals(name, "Origin")) {
    request.origin = value;
  } else if (text::iequals(name, "Cookie")) {
    // HTTP/1.1 browsers send one Cookie header; a second is ignored.
    if (!has_cookie) request.cookie = value;
    has_cookie = true;
  } else if (text::iequals(name, "Authorization")) {
    // Two credentials would leave it open which one counts.
    if (has_authorization) {
      fail(400, "more than one Authorization header");
      return false;
    }
    has_authorization = true;
    request.authorization = value;
  }
  return true;
}

}  // namespace rotord::web
