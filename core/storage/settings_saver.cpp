#include "storage/settings_saver.hpp"

#include "json/settings_json.hpp"
#include "util/crc32.hpp"

namespace rotord {
namespace {

/// Keeps the document web::save_settings serialises instead of storing it:
/// the saver compares before it writes, with the very writer the REST API
/// saves with.
class Capture final : public hal::Storage {
 public:
  std::string_view document;
  long load(char* /*buf*/, std::size_t /*capacity*/) override { return -1; }
  bool save(std::string_view d) override {
    document = d;
    return true;
  }
};

}  // namespace

long SettingsSaver::load(char* buf, std::size_t capacity) {
  const long n = storage_.load(buf, capacity);
  if (n >= 0 && static_cast<std::size_t>(n) <= capacity)
    remember_stored(std::string_view(buf, static_cast<std::size_t>(n)));
  return n;
}

bool SettingsSaver::save(std::string_view document) {
  if (!storage_.save(document)) {
    ++failures_;
    return false;
  }
  // The REST API saves the settings as they are now: that revision is stored.
  remember_stored(document);
  clean_revision_ = seen_revision_ = settings_.revision();
  retry_at_ = retry_delay_ms_ = 0;
  ++writes_;
  return true;
}

void SettingsSaver::remember_stored(std::string_view document) {
  have_stored_ = true;
  stored_length_ = document.size();
  stored_crc_ = crc32(document.data(), document.size());
}

void SettingsSaver::begin() {
  clean_revision_ = seen_revision_ = settings_.revision();
}

SettingsSaver::Result SettingsSaver::poll(Millis now, bool busy) {
  const std::uint32_t revision = settings_.revision();
  if (revision != seen_revision_) {
    // Every change restarts the quiet time: a burst of writes is saved once.
    seen_revision_ = revision;
    changed_at_ = now;
  }
  if (revision == clean_revision_) return Result::kIdle;
  if (now - changed_at_ < kQuietMs || busy) return Result::kWaiting;
  if (retry_delay_ms_ != 0 && now < retry_at_) return Result::kWaiting;
  return write(now);
}

SettingsSaver::Result SettingsSaver::flush(Millis now) {
  if (!pending()) return Result::kIdle;
  return write(now);
}

SettingsSaver::Result SettingsSaver::write(Millis now) {
  const std::uint32_t revision = settings_.revision();
  Capture capture;
  if (web::save_settings(capture, settings_, base_, buf_, capacity_)) {
    const std::string_view document = capture.document;
    // A change and its undo (or a value set to what it was) leave the stored
    // document as it is: no write, no flash wear.
    if (have_stored_ && document.size() == stored_length_ &&
        crc32(document.data(), document.size()) == stored_crc_) {
      clean_revision_ = seen_revision_ = revision;
      retry_at_ = retry_delay_ms_ = 0;
      return Result::kUnchanged;
    }
    if (storage_.save(document)) {
      remember_stored(document);
      clean_revision_ = seen_revision_ = revision;
      retry_at_ = retry_delay_ms_ = 0;
      ++writes_;
      return Result::kSaved;
    }
  }
  // The settings stay in RAM and in force; try again later, less often.
  ++failures_;
  retry_delay_ms_ = retry_delay_ms_ == 0 ? kFirstRetryMs : retry_delay_ms_ * 2;
  if (retry_delay_ms_ > kMaxRetryMs) retry_delay_ms_ = kMaxRetryMs;
  retry_at_ = now + retry_delay_ms_;
  return Result::kFailed;
}

}  // namespace rotord
