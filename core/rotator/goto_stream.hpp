#pragma once
#include <cstdint>

#include "util/time.hpp"

namespace rotord {

/// Who sent a go-to: one protocol session (its address), the REST API or
/// MQTT from one address. The continuity rule follows one stream per source.
using CommandSource = std::uint64_t;
/// rotord's own go-tos (park, a track's return) and callers that do not say
/// who they are: never part of a stream, always literal.
inline constexpr CommandSource kNoSource = 0;
/// An object (a session, a UDP protocol) as a source: unique while it lives.
inline CommandSource source_of(const void* object) {
  return reinterpret_cast<std::uintptr_t>(object);
}

/// The continuity rule (docs/tracking.md, "Trackers through the protocols").
/// Gpredict, the SatNOGS client and SatDump send compass azimuths 0..360
/// while tracking, so after 359 comes 0.5; taken literally, a 450 deg or a
/// -180..540 rotator would turn the long way round in the middle of the
/// pass. A stream of go-tos that moves like a tracker (one source, no long
/// pause, steps small against the travel, no zig-zag) is resolved onto the
/// turn continuous with it instead. This class only judges the stream; the
/// Controller decides the target and keeps it inside the travel.
class GotoStream {
 public:
  /// The longest pause between two go-tos of one stream: a low pass moves a
  /// client's 5 deg threshold in half a minute or more, and with the lead
  /// rule (stream_lead.hpp) the antenna waits for about twice that.
  static constexpr Millis kMaxGapMs = 150000;
  /// The largest step of a stream (and at most a quarter of the travel):
  /// near the zenith a client's azimuth steps by tens of degrees.
  static constexpr float kMaxStepDeg = 90.0f;
  /// A reversal this few steps after the last one makes the stream a
  /// zig-zag, taken literally until it runs steady this long again. One
  /// reversal after a steady run is a tracker too (the SatNOGS client's
  /// flip mirrors the pass at culmination).
  static constexpr int kSteadySteps = 3;
  /// Go-tos a stream must have had before the rule resolves one: two go-tos
  /// are no stream yet, and a single one means what the client sent.
  static constexpr int kMinGotos = 2;

  /// How the next go-to relates to the stream.
  struct Step {
    bool continues = false;    ///< tracker-like: resolve it continuous with the stream
    bool same_stream = false;  ///< same source, soon enough, a small step
    int sign = 0;              ///< direction of the azimuth step (0: unchanged)
    bool zigzag = false;       ///< reversed too soon after the last reversal
  };

  /// Judges a go-to to compass-or-unwrapped `az_deg` from `source` at `now`
  /// on a travel `travel_deg` wide. Changes nothing: accept() does.
  Step judge(float az_deg, CommandSource source, Millis now, float travel_deg) const;
  /// The go-to judged as `step` was obeyed: `az_deg` as sent, `target_deg`
  /// where the axis goes.
  void accept(const Step& step, float az_deg, float target_deg, CommandSource source, Millis now);
  /// STOP, a jog, a park, a track or a go-to without a source: the next
  /// go-to starts a new stream (and is literal).
  void interrupt() { source_ = kNoSource; }
  /// The unwrapped target of the last go-to of the stream.
  float last_target_deg() const { return last_target_; }
  /// How many go-tos the rule has put on another turn than the literal one.
  std::uint32_t resolved_count() const { return resolved_; }
  void count_resolved() { ++resolved_; }

 private:
  CommandSource source_ = kNoSource;
  Millis last_ms_ = 0;
  float last_az_ = 0.0f;
  float last_target_ = 0.0f;
  int gotos_ = 0;           // go-tos in the stream so far
  bool unwrapped_ = false;  // the client sent an azimuth outside 0..360: it knows the turns
  int dir_ = 0;             // sign of the last step that moved
  int run_ = 0;             // steps since the direction last reversed
  bool literal_ = false;    // zig-zagged: literal until steady again
  std::uint32_t resolved_ = 0;
};

}  // namespace rotord
