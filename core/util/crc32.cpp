#include "util/crc32.hpp"

namespace rotord {

std::uint32_t crc32(const void* data, std::size_t length, std::uint32_t crc) {
  const auto* p = static_cast<const std::uint8_t*>(data);
  crc = ~crc;
  for (std::size_t n = 0; n < length; ++n) {
    crc ^= p[n];
    for (int bit = 0; bit < 8; ++bit) crc = (crc >> 1) ^ (0xEDB88320u & (0u - (crc & 1u)));
  }
  return ~crc;
}

}  // namespace rotord
