#include "care/odometer_saver.hpp"

#include "care/odometer_record.hpp"

namespace rotord::care {

OdometerSaver::Load OdometerSaver::load(Millis now) {
  last_write_at_ = now;
  saved_revision_ = odometer_.revision();
  saved_resets_ = odometer_.resets();
  const long n = storage_.load(buf_, capacity_);
  if (n == -1) {
    // FileStorage and FlashSlots say -1 for "nothing stored" and for a
    // record that failed its CRC alike; either way the count starts at zero.
    return Load::kNothingStored;
  }
  if (n < 0) {
    why_ = "unreadable, or larger than a record can be";
    return Load::kDamaged;
  }
  AxisWear az;
  AxisWear el;
  std::int64_t reset_unix_s = 0;
  if (!decode_record({buf_, static_cast<std::size_t>(n)}, az, el, reset_unix_s, why_)) {
    // The next save replaces it: the counts start again from zero.
    odometer_.touch();
    return Load::kDamaged;
  }
  odometer_.restore(az, el, reset_unix_s);
  saved_revision_ = odometer_.revision();
  return Load::kLoaded;
}

OdometerSaver::Result OdometerSaver::poll(Millis now, bool busy) {
  if (odometer_.revision() == saved_revision_) return Result::kIdle;
  if (odometer_.resets() != saved_resets_) return write(now);
  const Millis since = now - last_write_at_;
  if (since < interval_ms_ - (busy ? 0 : interval_ms_ / 10)) {
    // Not yet; or, in the last tenth of the interval, only while it stands.
    return Result::kWaiting;
  }
  return write(now);
}

OdometerSaver::Result OdometerSaver::flush(Millis now) {
  if (odometer_.revision() == saved_revision_) return Result::kIdle;
  return write(now);
}

OdometerSaver::Result OdometerSaver::write(Millis now) {
  last_write_at_ = now;  // a failure waits an interval too (flash wear, log lines)
  saved_resets_ = odometer_.resets();
  const std::size_t n = encode_record(odometer_, buf_, capacity_);
  if (n == 0 || !storage_.save({buf_, n})) {
    ++failures_;
    return Result::kFailed;
  }
  ++writes_;
  saved_revision_ = odometer_.revision();
  return Result::kSaved;
}

}  // namespace rotord::care
