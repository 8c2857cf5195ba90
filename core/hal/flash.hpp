#pragma once
#include <cstddef>
#include <cstdint>

namespace rotord::hal {

/// A region of NOR flash set aside for the core (Pico W: the last sectors of
/// the 2 MB chip). Offsets are relative to the region. NOR semantics: erase
/// sets whole erase blocks to 0xFF; program can only clear bits, in whole
/// aligned pages.
class Flash {
 public:
  virtual ~Flash() = default;
  virtual std::size_t size() const = 0;
  /// Erase granularity (4096 on the RP2040's flash).
  virtual std::size_t erase_size() const = 0;
  /// Program granularity (256 on the RP2040's flash).
  virtual std::size_t program_size() const = 0;
  virtual bool read(std::size_t offset, void* out, std::size_t length) = 0;
  /// offset and length are multiples of erase_size().
  virtual bool erase(std::size_t offset, std::size_t length) = 0;
  /// offset and length are multiples of program_size(); `data` is in RAM.
  virtual bool program(std::size_t offset, const void* data, std::size_t length) = 0;
};

}  // namespace rotord::hal
