#pragma once
#include <array>
#include <cstddef>
#include <string_view>

#include "json/json_writer.hpp"
#include "mqtt/topics.hpp"
#include "util/time.hpp"
#include "web/station_source.hpp"

namespace rotord::mqtt {

/// Every rotord seen on the broker (the station page, GET /api/station):
/// what their retained <prefix>/state, <prefix>/availability and
/// <prefix>/info say, for prefixes of two levels (the default
/// rotord/<hostname>). A fixed table: more rotords than kMaxRotators are
/// not listed.
class Station final : public web::StationSource {
 public:
  static constexpr std::size_t kMaxRotators = 16;
  static constexpr std::size_t kMaxUrlBytes = 96;

  /// A message on a two-level prefix; false when it is not a rotord's.
  bool on_message(std::string_view topic, std::string_view payload);
  /// {"rotators":[{"prefix","name","web","online","mode","az_deg","mech_az_deg","el_deg",
  /// "fault"}...]}: az_deg and el_deg where the beam points, mech_az_deg the
  /// mechanism's azimuth.
  void write_station(web::JsonWriter& w) const override;
  std::size_t size() const;

 private:
  struct Entry {
    bool used = false;
    bool seen_state = false;
    char prefix[kMaxPrefixBytes + 1] = {};
    char name[48] = {};
    char web[kMaxUrlBytes] = {};
    bool online = false;
    char mode[12] = {};
    float az_deg = 0.0f;       ///< the beam's
    float mech_az_deg = 0.0f;  ///< the mechanism's (unwrapped)
    float el_deg = 0.0f;       ///< the beam's
    bool has_el = false;
    bool fault = false;
  };
  Entry* find(std::string_view prefix, bool add);
  std::array<Entry, kMaxRotators> entries_{};
};

}  // namespace rotord::mqtt
