#pragma once
#include <cstddef>
#include <cstdint>

#include "care/odometer.hpp"
#include "hal/storage.hpp"
#include "util/time.hpp"

namespace rotord::care {

/// Keeps the odometer across restarts and power cuts (docs/care.md): reads
/// it back at start-up and writes it once a save interval when it changed,
/// so a power cut loses at most one interval of counting. Called from the
/// port's main loop, never from the control tick (a flash erase stalls the
/// Pico's loop for tens of ms). No heap: the document buffer is the
/// caller's (the Pico lends its start-up buffer, as to the settings saver).
class OdometerSaver {
 public:
  /// `interval_ms`: the save interval (Linux 60 s; the Pico W 10 min, for
  /// the flash's endurance: docs/care.md computes it).
  OdometerSaver(Odometer& odometer, hal::Storage& storage, char* buf, std::size_t capacity,
                Millis interval_ms)
      : odometer_(odometer),
        storage_(storage),
        buf_(buf),
        capacity_(capacity),
        interval_ms_(interval_ms) {}

  enum class Load : std::uint8_t {
    kNothingStored,  ///< the first start: counting from zero
    kLoaded,
    kDamaged,  ///< the record was unreadable: counting from zero (reason in why())
  };
  /// Reads the record into the odometer. Never fails the start: a damaged
  /// record leaves the odometer at zero, and the next save replaces it.
  Load load(Millis now);
  /// Why the record was damaged (a static string), after load().
  const char* why() const { return why_; }

  enum class Result : std::uint8_t { kIdle, kWaiting, kSaved, kFailed };
  /// Call from the main loop. A reset of the counts (Odometer::reset, by
  /// the REST API or the console) is written at once. Otherwise it writes when the counts changed
  /// and the interval since the last write has passed: at rest from nine tenths of it on, while
  /// `busy` (the rotator moves) at the whole of it, so an erase rarely falls in a move and never
  /// waits past the interval. A failure is retried after another interval.
  Result poll(Millis now, bool busy = false);
  /// Writes a change at once (shutdown, reboot, a reset of the counts).
  Result flush(Millis now);

  Millis interval_ms() const { return interval_ms_; }
  /// Records written since start, and writes that failed (GET /metrics:
  /// on the Pico W, each is a flash sector erased).
  const std::uint32_t& writes() const { return writes_; }
  const std::uint32_t& failures() const { return failures_; }

 private:
  Result write(Millis now);

  Odometer& odometer_;
  hal::Storage& storage_;
  char* buf_;
  std::size_t capacity_;
  Millis interval_ms_;
  std::uint32_t saved_revision_ = 0;
  std::uint32_t saved_resets_ = 0;
  Millis last_write_at_ = 0;
  const char* why_ = "";
  std::uint32_t writes_ = 0;
  std::uint32_t failures_ = 0;
};

}  // namespace rotord::care
