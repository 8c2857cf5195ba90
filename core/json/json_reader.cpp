#include "json/json_reader.hpp"

#include "util/slice.hpp"
#include "util/text.hpp"

namespace rotord::web {
namespace {

bool is_digit(char c) {
  return c >= '0' && c <= '9';
}

int hex_value(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

}  // namespace

const char* json_type_name(JsonType type) {
  switch (type) {
    case JsonType::kNull:
      return "null";
    case JsonType::kBool:
      return "boolean";
    case JsonType::kNumber:
      return "number";
    case JsonType::kString:
      return "string";
    case JsonType::kObject:
      return "object";
    case JsonType::kArray:
      return "array";
  }
  return "?";
}

JsonObjectReader::JsonObjectReader(std::string_view json) : json_(json) {
  // Validation pass: parse the whole object, discarding the values.
  skip_ws();
  if (pos_ >= json_.size() || json_[pos_] != '{') {
    fail(pos_ >= json_.size() ? "empty body, expected a JSON object" : "expected a JSON object");
    return;
  }
  if (!parse_container('{', 1)) return;
  skip_ws();
  if (pos_ != json_.size()) {
    fail("unexpected text after the JSON object");
    return;
  }
  pos_ = 0;
}

bool JsonObjectReader::fail(const char* message) {
  if (error_ == nullptr) {
    error_ = message;
    error_at_ = pos_;
  }
  return false;
}

void JsonObjectReader::skip_ws() {
  while (pos_ < json_.size() &&
         (json_[pos_] == ' ' || json_[pos_] == '\t' || json_[pos_] == '\n' || json_[pos_] == '\r'))
    ++pos_;
}

bool JsonObjectReader::parse_container(char open, int depth) {
  if (depth > kMaxDepth) return fail("JSON nested too deeply");
  const char close = open == '{' ? '}' : ']';
  ++pos_;  // the opening bracket
  skip_ws();
  if (pos_ < json_.size() && json_[pos_] == close) {
    ++pos_;
    return true;
  }
  for (;;) {
    skip_ws();
    if (open == '{') {
      if (pos_ >= json_.size() || json_[pos_] != '"') return fail("expected a member name");
      std::string_view ignored;
      bool truncated = false;
      // Nested member names go to the value scratch: key_buf_ holds the
      // top-level key next() has returned.
      if (!parse_string(str_buf_, sizeof(str_buf_), &ignored, &truncated)) return false;
      skip_ws();
      if (pos_ >= json_.size() || json_[pos_] != ':') return fail("expected ':'");
      ++pos_;
    }
    JsonValue value;
    if (!parse_value(&value, depth)) return false;
    skip_ws();
    if (pos_ >= json_.size()) return fail("unterminated JSON object or array");
    if (json_[pos_] == ',') {
      ++pos_;
      continue;
    }
    if (json_[pos_] == close) {
      ++pos_;
      return true;
    }
    return fail(open == '{' ? "expected ',' or '}'" : "expected ',' or ']'");
  }
}

bool JsonObjectReader::parse_value(JsonValue* value, int depth) {
  skip_ws();
  if (pos_ >= json_.size()) return fail("expected a value");
  const char c = json_[pos_];
  *value = JsonValue{};
  switch (c) {
    case '{':
      value->type = JsonType::kObject;
      return parse_container('{', depth + 1);
    case '[':
      value->type = JsonType::kArray;
      return parse_container('[', depth + 1);
    case '"':
      value->type = JsonType::kString;
      return parse_string(str_buf_, sizeof(str_buf_), &value->text, &value->truncated);
    case 't':
      value->type = JsonType::kBool;
      value->boolean = true;
      return parse_literal("true");
    case 'f':
      value->type = JsonType::kBool;
      return parse_literal("false");
    case 'n':
      value->type = JsonType::kNull;
      return parse_literal("null");
    default:
      value->type = JsonType::kNumber;
      return parse_number(&value->number);
  }
}

bool JsonObjectReader::parse_literal(std::string_view word) {
  if (text::slice(json_, pos_, word.size()) != word) return fail("invalid JSON value");
  pos_ += word.size();
  return true;
}

bool JsonObjectReader::parse_number(double* out) {
  // RFC 8259 grammar: -?(0|[1-9][0-9]*)(.[0-9]+)?([eE][+-]?[0-9]+)?
  const std::size_t start = pos_;
  auto digits = [&] {
    const std::size_t from = pos_;
    while (pos_ < json_.size() && is_digit(json_[pos_])) ++pos_;
    return pos_ - from;
  };
  if (pos_ < json_.size() && json_[pos_] == '-') ++pos_;
  if (pos_ >= json_.size() || !is_digit(json_[pos_])) return fail("invalid JSON value");
  if (json_[pos_] == '0') {
    ++pos_;
  } else {
    digits();
  }
  if (pos_ < json_.size() && json_[pos_] == '.') {
    ++pos_;
    if (digits() == 0) return fail("invalid number");
  }
  if (pos_ < json_.size() && (json_[pos_] == 'e' || json_[pos_] == 'E')) {
    ++pos_;
    if (pos_ < json_.size() && (json_[pos_] == '+' || json_[pos_] == '-')) ++pos_;
    if (digits() == 0) return fail("invalid number");
  }
  if (!text::parse_double(text::slice(json_, start, pos_ - start), *out))
    return fail("number too long or out of range");
  return true;
}

bool JsonObjectReader::parse_string(char* buf, std::size_t cap, std::string_view* out,
                                    bool* truncated) {
  ++pos_;  // the opening quote
  std::size_t n = 0;
  *truncated = false;
  auto emit = [&](char c) {
    if (n < cap) {
      buf[n++] = c;
    } else {
      *truncated = true;
    }
  };
  while (pos_ < json_.size()) {
    const char c = json_[pos_++];
    if (c == '"') {
      *out = std::string_view(buf, n);
      return true;
    }
    if (static_cast<unsigned char>(c) < 0x20) return fail("control character in a JSON string");
    if (c != '\\') {
      emit(c);
      continue;
    }
    if (pos_ >= json_.size()) break;
    const char e = json_[pos_++];
    switch (e) {
      case '"':
      case '\\':
      case '/':
        emit(e);
        break;
      case 'b':
        emit('\b');
        break;
      case 'f':
        emit('\f');
        break;
      case 'n':
        emit('\n');
        break;
      case 'r':
        emit('\r');
        break;
      case 't':
        emit('\t');
        break;
      case 'u': {
        if (pos_ + 4 > json_.size()) return fail("invalid \\u escape");
        unsigned code = 0;
        for (int k = 0; k < 4; ++k) {
          const int h = hex_value(json_[pos_++]);
          if (h < 0) return fail("invalid \\u escape");
          code = code * 16 + static_cast<unsigned>(h);
        }
        // UTF-8; a surrogate half becomes U+FFFD (no setting needs astral text).
        if (code >= 0xD800 && code <= 0xDFFF) code = 0xFFFD;
        if (code < 0x80) {
          emit(static_cast<char>(code));
        } else if (code < 0x800) {
          emit(static_cast<char>(0xC0 | (code >> 6)));
          emit(static_cast<char>(0x80 | (code & 0x3F)));
        } else {
          emit(static_cast<char>(0xE0 | (code >> 12)));
          emit(static_cast<char>(0x80 | ((code >> 6) & 0x3F)));
          emit(static_cast<char>(0x80 | (code & 0x3F)));
        }
        break;
      }
      default:
        return fail("invalid escape in a JSON string");
    }
  }
  return fail("unterminated JSON string");
}

bool JsonObjectReader::next(std::string_view& key, JsonValue& value) {
  if (error_ != nullptr || done_) return false;
  skip_ws();
  if (!started_) {
    started_ = true;
    ++pos_;  // '{'
    skip_ws();
    if (json_[pos_] == '}') {
      done_ = true;
      return false;
    }
  } else {
    if (json_[pos_] == '}') {
      done_ = true;
      return false;
    }
    ++pos_;  // ','
    skip_ws();
  }
  bool truncated = false;
  if (!parse_string(key_buf_, sizeof(key_buf_), &key, &truncated)) return false;
  if (truncated) key = std::string_view(key_buf_, 0);  // never a known key
  skip_ws();
  ++pos_;  // ':'
  if (!parse_value(&value, 1)) return false;
  skip_ws();
  return true;
}

}  // namespace rotord::web
