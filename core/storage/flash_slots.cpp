#include "storage/flash_slots.hpp"

#include <array>
#include <cstring>

#include "util/crc32.hpp"

namespace rotord {
namespace {

// The page buffer lives on the stack; the RP2040's flash programs 256-byte pages.
constexpr std::size_t kMaxProgramSize = 256;
constexpr std::size_t kHeaderBytes = 24;
constexpr std::size_t kHeaderCrcOffset = 20;

void put16(std::uint8_t* p, std::uint16_t v) {
  p[0] = static_cast<std::uint8_t>(v);
  p[1] = static_cast<std::uint8_t>(v >> 8);
}
void put32(std::uint8_t* p, std::uint32_t v) {
  for (int n = 0; n < 4; ++n) p[n] = static_cast<std::uint8_t>(v >> (8 * n));
}
std::uint16_t get16(const std::uint8_t* p) {
  return static_cast<std::uint16_t>(p[0] | (p[1] << 8));
}
std::uint32_t get32(const std::uint8_t* p) {
  std::uint32_t v = 0;
  for (int n = 3; n >= 0; --n) v = (v << 8) | p[n];
  return v;
}

/// a is newer than b, with wrap-around (serial number arithmetic).
bool newer(std::uint32_t a, std::uint32_t b) {
  return static_cast<std::int32_t>(a - b) > 0;
}

}  // namespace

std::size_t FlashSlots::slot_size() const {
  const std::size_t erase = flash_.erase_size();
  if (erase == 0) return 0;
  return flash_.size() / static_cast<std::size_t>(slots_) / erase * erase;
}

bool FlashSlots::usable() const {
  const std::size_t page = flash_.program_size();
  const std::size_t erase = flash_.erase_size();
  return page >= kHeaderBytes && page <= kMaxProgramSize && erase >= page && erase % page == 0 &&
         slot_size() >= erase && slot_size() > page;
}

std::size_t FlashSlots::capacity() const {
  return usable() ? slot_size() - flash_.program_size() : 0;
}

std::optional<FlashSlots::Header> FlashSlots::valid_header(int slot) {
  std::uint8_t raw[kHeaderBytes];
  if (!flash_.read(slot_offset(slot), raw, sizeof raw)) return std::nullopt;
  Header h{get32(raw),      get16(raw + 4),  get16(raw + 6), get32(raw + 8),
           get32(raw + 12), get32(raw + 16), get32(raw + 20)};
  if (h.magic != kMagic || h.format != kFormat || h.header_bytes != kHeaderBytes)
    return std::nullopt;
  if (crc32(raw, kHeaderCrcOffset) != h.header_crc) return std::nullopt;
  if (h.length > capacity()) return std::nullopt;
  // The payload CRC, read in small chunks (no slot-sized buffer in RAM).
  std::uint8_t chunk[64];
  std::uint32_t crc = 0;
  const std::size_t base = slot_offset(slot) + flash_.program_size();
  for (std::size_t done = 0; done < h.length;) {
    const std::size_t n = h.length - done < sizeof chunk ? h.length - done : sizeof chunk;
    if (!flash_.read(base + done, chunk, n)) return std::nullopt;
    crc = crc32(chunk, n, crc);
    done += n;
  }
  if (crc != h.payload_crc) return std::nullopt;
  return h;
}

std::optional<FlashSlots::Newest> FlashSlots::newest() {
  if (!usable()) return std::nullopt;
  std::optional<Newest> best;
  for (int slot = 0; slot < slots_; ++slot) {
    const auto h = valid_header(slot);
    if (!h) continue;
    if (!best || newer(h->sequence, best->sequence)) best = Newest{slot, h->sequence};
  }
  return best;
}

bool FlashSlots::payload_equals(int slot, const Header& header, std::string_view document) {
  if (header.length != document.size()) return false;
  if (crc32(document.data(), document.size()) != header.payload_crc) return false;
  std::uint8_t chunk[64];
  const std::size_t base = slot_offset(slot) + flash_.program_size();
  for (std::size_t done = 0; done < document.size();) {
    const std::size_t n =
        document.size() - done < sizeof chunk ? document.size() - done : sizeof chunk;
    if (!flash_.read(base + done, chunk, n)) return false;
    if (std::memcmp(chunk, document.data() + done, n) != 0) return false;
    done += n;
  }
  return true;
}

long FlashSlots::load(char* buf, std::size_t capacity) {
  const auto n = newest();
  if (!n) return -1;
  const auto h = valid_header(n->slot);
  if (!h) return -1;
  if (h->length > capacity) return -2;
  if (!flash_.read(slot_offset(n->slot) + flash_.program_size(), buf, h->length)) return -1;
  // The flash was checked above; check what arrived in RAM too.
  if (crc32(buf, h->length) != h->payload_crc) return -1;
  return static_cast<long>(h->length);
}

bool FlashSlots::save(std::string_view document) {
  last_programmed_ = 0;
  if (!usable() || document.size() > capacity()) return false;
  const auto current = newest();
  if (current) {
    const auto h = valid_header(current->slot);
    if (h && payload_equals(current->slot, *h, document)) return true;  // nothing changed
  }
  const int target = current ? (current->slot + 1) % slots_ : 0;
  const std::uint32_t sequence = current ? current->sequence + 1 : 1;
  const std::size_t page = flash_.program_size();
  const std::size_t base = slot_offset(target);

  if (!flash_.erase(base, slot_size())) return false;
  std::array<std::uint8_t, kMaxProgramSize> buf{};
  for (std::size_t done = 0; done < document.size(); done += page) {
    const std::size_t n = document.size() - done < page ? document.size() - done : page;
    std::memset(buf.data(), 0xFF, page);
    std::memcpy(buf.data(), document.data() + done, n);
    if (!flash_.program(base + page + done, buf.data(), page)) return false;
    last_programmed_ += page;
  }
  // The header last: until it is complete the slot is invalid.
  std::memset(buf.data(), 0xFF, page);
  put32(buf.data(), kMagic);
  put16(buf.data() + 4, kFormat);
  put16(buf.data() + 6, static_cast<std::uint16_t>(kHeaderBytes));
  put32(buf.data() + 8, sequence);
  put32(buf.data() + 12, static_cast<std::uint32_t>(document.size()));
  put32(buf.data() + 16, crc32(document.data(), document.size()));
  put32(buf.data() + 20, crc32(buf.data(), kHeaderCrcOffset));
  if (!flash_.program(base, buf.data(), page)) return false;
  last_programmed_ += page;
  const auto written = valid_header(target);
  return written && written->sequence == sequence;
}

}  // namespace rotord
