#pragma once
#include <cstddef>
#include <cstdint>

namespace rotord {
namespace protocol {

/// The line protocols, listed with their rows (protocol_registry.hpp).
enum class Personality : std::uint8_t;

}  // namespace protocol

namespace metrics {

/// What a port counts under in GET /metrics (the `protocol` label): HTTP,
/// then each line protocol in the order of Personality, labelled with its
/// row's key. It lives with the protocols, not in util, which lists no
/// protocol; the metrics layer, above this one, counts under it. Its names
/// stay `metrics::`, as they were when it sat in util.
/// kProtocolCount (metrics/registry.hpp) counts them.
enum class Protocol : std::uint8_t { kHttp };

/// The counters of a line protocol.
constexpr Protocol line_metric(protocol::Personality p) {
  return static_cast<Protocol>(1 + static_cast<std::size_t>(p));
}

}  // namespace metrics
}  // namespace rotord
