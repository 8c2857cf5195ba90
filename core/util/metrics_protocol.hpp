#pragma once
#include <cstddef>
#include <cstdint>

namespace rotord::metrics {

/// The protocols a port serves: the `protocol` label of GET /metrics. A
/// shared id low in the layers, like AxisId: the protocol registry names each
/// row's label, the metrics layer counts under it.
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
