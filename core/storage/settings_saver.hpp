#pragma once
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "hal/storage.hpp"
#include "settings/settings.hpp"
#include "util/time.hpp"

namespace rotord {

/// Persists settings that change outside the REST API: GS-232 O/F
/// calibration and P36/P45, WRC AZOFFSET, Easycomm CW writes, rotctld `C`.
/// Those sessions only change the settings in RAM; the port polls this from
/// its main loop (never from the control tick), and once Settings::revision()
/// has stood still for kQuietMs the settings are written as the same JSON
/// document POST /api/settings saves. A calibration sequence or a burst of
/// CW writes thus becomes one write.
///
/// It also stands between the REST API and the port's storage (it is a
/// hal::Storage itself): a document the API saved, or that was loaded at
/// start-up, is remembered (length and CRC-32), so a change the API already
/// saved is not written twice and an unchanged document is never written
/// again (flash wear). A failed write keeps the settings in RAM, is reported
/// by poll() and retried later, with a growing pause.
///
/// Plain core code: no heap, no OS; the document buffer is the caller's
/// (the Pico reuses its start-up buffer).
class SettingsSaver final : public hal::Storage {
 public:
  /// How long the settings must stay unchanged before they are written.
  static constexpr Millis kQuietMs = 3000;
  /// Pause after the first failed write; doubles up to kMaxRetryMs.
  static constexpr Millis kFirstRetryMs = 5000;
  static constexpr Millis kMaxRetryMs = 300000;

  /// `base`: the defaults below the user's layer (settings_layers.hpp);
  /// only what differs from it is written.
  SettingsSaver(const settings::Settings& settings, const settings::Settings& base,
                hal::Storage& storage, char* buf, std::size_t capacity)
      : settings_(settings), base_(base), storage_(storage), buf_(buf), capacity_(capacity) {}

  /// hal::Storage: the port's storage, remembering what it holds.
  long load(char* buf, std::size_t capacity) override;
  bool save(std::string_view document) override;

  /// Takes the settings as they are now as saved. Call once start-up is done
  /// (loaded, or left on the defaults without overwriting a damaged copy):
  /// only later changes are written.
  void begin();

  enum class Result : std::uint8_t {
    kIdle,       ///< nothing to save
    kWaiting,    ///< a change waits for the quiet time, the rotator or a retry
    kUnchanged,  ///< the change came back to what is stored: nothing written
    kSaved,      ///< written
    kFailed,     ///< the write failed (or the document did not fit); retried later
  };
  /// Call from the main loop. `busy`: the rotator is moving; the write waits
  /// for it to stop (a flash erase stalls the Pico's loop for tens of ms).
  Result poll(Millis now, bool busy = false);
  /// Writes a pending change at once, whatever the quiet time (shutdown,
  /// reboot).
  Result flush(Millis now);

  bool pending() const { return settings_.revision() != clean_revision_; }
  /// Pause before the next attempt after a failure (0: none failed).
  Millis retry_delay_ms() const { return retry_delay_ms_; }
  /// Documents written since start (the REST API's saves and this saver's).
  const std::uint32_t& writes() const { return writes_; }
  /// Writes that failed since start (each retry counts again).
  const std::uint32_t& failures() const { return failures_; }

 private:
  Result write(Millis now);
  void remember_stored(std::string_view document);

  const settings::Settings& settings_;
  const settings::Settings& base_;
  hal::Storage& storage_;
  char* buf_;
  std::size_t capacity_;

  std::uint32_t clean_revision_ = 0;  ///< the revision that is stored (or deliberately not)
  std::uint32_t seen_revision_ = 0;   ///< the revision at the last poll
  Millis changed_at_ = 0;             ///< when seen_revision_ last moved
  Millis retry_at_ = 0;
  Millis retry_delay_ms_ = 0;
  bool have_stored_ = false;  ///< stored_length_/stored_crc_ describe the stored document
  std::size_t stored_length_ = 0;
  std::uint32_t stored_crc_ = 0;
  std::uint32_t writes_ = 0;
  std::uint32_t failures_ = 0;
};

}  // namespace rotord
