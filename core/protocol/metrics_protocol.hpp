#pragma once
#include <cstddef>
#include <cstdint>

namespace rotord::metrics {

/// The protocols a port serves: the `protocol` label of GET /metrics. It
/// lives with the protocols, beside their registry (protocol_registry.cpp
/// names each row's label), not in util, which lists no protocol; the
/// metrics layer, above this one, counts under it. Its names stay
/// `metrics::`, as they were when it sat in util.
enum class Protocol : std::uint8_t {
  kHttp,
  kWrc,
  kRotctld,
  kGs232,
  kEasycomm,
  kSeed,
  kConsole,
  kCount
};
inline constexpr std::size_t kProtocolCount = static_cast<std::size_t>(Protocol::kCount);

}  // namespace rotord::metrics
