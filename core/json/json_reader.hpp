#pragma once
#include <cstddef>
#include <string_view>

// The JSON codec layer (core/json, docs/architecture.md): below web and storage,
// which both read and write JSON. Its names stayed in rotord::web, where the
// codec began, so the web API, the ports and the tests spell them as before.
namespace rotord::web {

enum class JsonType : unsigned char { kNull, kBool, kNumber, kString, kObject, kArray };

const char* json_type_name(JsonType type);

/// One member value of a flat object. Strings are unescaped into the reader's
/// scratch buffer and stay valid until the next call to next().
struct JsonValue {
  JsonType type = JsonType::kNull;
  bool boolean = false;
  double number = 0.0;
  std::string_view text;   ///< kString only
  bool truncated = false;  ///< the string did not fit the scratch buffer
};

/// Reads one JSON object whose members are what the REST API and the settings
/// document use: scalars, with nested values recognised (and skipped) so the
/// caller can refuse them by type. Hand-written rather than nlohmann-json:
/// it runs on the Pico without heap or exceptions, strictly per RFC 8259
/// (no trailing commas, no comments, no NaN), with a nesting limit so a hostile
/// body cannot exhaust the stack.
class JsonObjectReader {
 public:
  static constexpr std::size_t kMaxKeyBytes = 64;
  static constexpr std::size_t kMaxStringBytes = 96;
  static constexpr int kMaxDepth = 8;

  /// Checks the whole document first, so nothing is acted on before a syntax
  /// error near the end is found.
  explicit JsonObjectReader(std::string_view json);

  bool valid() const { return error_ == nullptr; }
  /// Why the document is not a JSON object, e.g. "expected ':' at byte 12".
  const char* error() const { return error_; }
  std::size_t error_offset() const { return error_at_; }

  /// The next member; false at the end (or when the document is invalid).
  bool next(std::string_view& key, JsonValue& value);

 private:
  void skip_ws();
  bool fail(const char* message);
  bool parse_value(JsonValue* value, int depth);
  bool parse_string(char* buf, std::size_t cap, std::string_view* out, bool* truncated);
  bool parse_number(double* out);
  bool parse_literal(std::string_view word);
  bool parse_container(char open, int depth);

  std::string_view json_;
  std::size_t pos_ = 0;
  const char* error_ = nullptr;
  std::size_t error_at_ = 0;
  bool started_ = false;
  bool done_ = false;
  char key_buf_[kMaxKeyBytes];
  char str_buf_[kMaxStringBytes];
};

}  // namespace rotord::web
