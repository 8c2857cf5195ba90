#pragma once
#include <cstddef>
#include <string_view>

namespace rotord::hal {

/// Persistent storage of one settings document. Linux: a file replaced
/// atomically; Pico W: two flash slots with sequence number and CRC.
class Storage {
 public:
  virtual ~Storage() = default;
  /// Copies the stored document into buf. Returns its length, or -1 when
  /// nothing valid is stored, or -2 when it does not fit.
  virtual long load(char* buf, std::size_t capacity) = 0;
  /// Replaces the stored document; a power cut leaves the old or the new one.
  virtual bool save(std::string_view document) = 0;
  /// A person may read the stored document (a file), so it is indented; a
  /// flash slot stores it compact, since every setting row the table gains
  /// eats into the slot (about 4 bytes a key of indentation alone).
  virtual bool human_readable() const { return true; }
};

}  // namespace rotord::hal
