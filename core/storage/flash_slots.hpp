#pragma once
#include <cstddef>
#include <cstdint>
#include <optional>

#include "hal/flash.hpp"
#include "hal/storage.hpp"

namespace rotord {

/// hal::Storage in two flash slots (the Pico W's settings). The region is
/// split in two halves; each holds one document under a header with a
/// sequence number and CRCs:
///
///   page 0:  magic, format, sequence, length, payload CRC-32, header CRC-32
///   page 1+: the document, padded with 0xFF
///
/// A save goes to the slot that does not hold the newest valid document:
/// erase it, program the document, and program the header page last, so the
/// new copy becomes valid only once it is complete. A power cut at any point
/// leaves the previous document as the newest valid one. Load picks the valid
/// slot with the higher sequence number. Saving the document that is already
/// the newest writes nothing (flash wear, and no window for a power cut).
///
/// Pure logic over hal::Flash: no SDK, no heap; unit-tested with a fake
/// flash that can cut the power in the middle of a program or erase.
class FlashSlots final : public hal::Storage {
 public:
  static constexpr std::uint32_t kMagic = 0x54455352;  // "RSET" little-endian
  static constexpr std::uint16_t kFormat = 1;

  /// `slots`: how many slots the region is split into (2 for the settings;
  /// more spread the erases of a record written often, as the wear
  /// odometer's, over more sectors). A save goes to the slot after the
  /// newest, in turn.
  explicit FlashSlots(hal::Flash& flash, int slots = 2)
      : flash_(flash), slots_(slots < 2 ? 2 : slots) {}

  /// The geometry works: two slots of whole erase blocks, each larger than
  /// one page. Save and load fail without touching the flash otherwise.
  bool usable() const;
  /// Largest document a slot holds.
  std::size_t capacity() const;
  bool human_readable() const override { return false; }

  long load(char* buf, std::size_t capacity) override;
  bool save(std::string_view document) override;

  /// Index and sequence number of the newest valid slot, for tests and logs.
  struct Newest {
    int slot = -1;
    std::uint32_t sequence = 0;
  };
  std::optional<Newest> newest();
  /// Bytes programmed by the last save (0 when it found nothing to change).
  std::size_t last_save_programmed() const { return last_programmed_; }

 private:
  struct Header {
    std::uint32_t magic;
    std::uint16_t format;
    std::uint16_t header_bytes;
    std::uint32_t sequence;
    std::uint32_t length;
    std::uint32_t payload_crc;
    std::uint32_t header_crc;  ///< over every field above
  };

  std::size_t slot_size() const;
  std::size_t slot_offset(int slot) const { return static_cast<std::size_t>(slot) * slot_size(); }
  /// The slot's header when the header and the payload check out.
  std::optional<Header> valid_header(int slot);
  bool payload_equals(int slot, const Header& header, std::string_view document);

  hal::Flash& flash_;
  int slots_;
  std::size_t last_programmed_ = 0;
};

}  // namespace rotord
