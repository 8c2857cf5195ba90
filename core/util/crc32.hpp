#pragma once
#include <cstddef>
#include <cstdint>

namespace rotord {

/// CRC-32 (IEEE 802.3, as zlib's crc32), bit by bit: no 1 KB table in flash
/// for a checksum computed once per boot and per settings save. Continue a
/// running CRC by passing the previous result as `crc`.
std::uint32_t crc32(const void* data, std::size_t length, std::uint32_t crc = 0);

}  // namespace rotord
