#pragma once
#include <cstdint>

#include "tracking/observer.hpp"
#include "tracking/sky_target.hpp"
#include "tracking/tle_catalog.hpp"

namespace rotord {

/// Recognises what a tracker's go-to stream points at (docs/tracking.md,
/// "Trackers through the protocols"): a stored satellite, the Sun or the
/// Moon. Each go-to of the stream is compared with where each candidate was
/// recently; a candidate that misses once is out for the stream, one that
/// matched kMinHits go-tos in a row, or two in step with it (kInStep...),
/// while every other candidate is out is recognised. Two that keep matching
/// (docked objects, the same object twice in the store, the Sun beside the
/// Moon) are ambiguous: nothing is recognised.
///
/// Cost: work is done only when a go-to arrives, never in the control tick,
/// and at most `budget` candidates are evaluated per go-to (one SGP4 set-up
/// and one look each). The Pico W evaluates a satellite in about 3 ms and
/// the Sun or the Moon in about 10 ms; its loop may not stall for the
/// catalogue's 24 entries and two bodies at once (a quarter of a second),
/// so the port sets a small budget and the sweep spreads over a few go-tos.
/// No heap: one SkyTarget (1.2 KB) and a byte per candidate.
class GotoMatcher {
 public:
  /// The catalogue, then the Sun and the Moon.
  static constexpr int kMaxCandidates = static_cast<int>(tracking::TleCatalog::kCapacity) + 2;
  /// How far a go-to may be from the object's recent path and still match:
  /// a client's predictor and rotord's agree to a fraction of a degree on the
  /// same elements; elements a day apart move the ISS by about a degree.
  static constexpr float kToleranceDeg = 3.0f;
  /// The path a go-to is compared with reaches this far back (Gpredict and
  /// the SatNOGS client send the position they computed at their last
  /// cycle, and a slow object keeps a stale go-to near)...
  static constexpr float kLookBackS = 30.0f;
  /// ... but no more than this arc (a client's 4-5 deg threshold and its
  /// cycle): longer, the straight line leaves the curved path.
  static constexpr float kLookBackMaxDeg = 8.0f;
  /// And this far ahead (a client clock a little ahead of rotord's).
  static constexpr float kLookAheadS = 3.0f;
  /// Matched go-tos in a row before an object is recognised: one or two
  /// points near an object may be chance, three in step with it are not.
  static constexpr int kMinHits = 3;
  /// ... or two, when the step between them is the object's own motion over
  /// the time between them, in direction and rate: within
  /// kInStepToleranceDeg plus kInStepOfMotion of that motion (a client's lag
  /// varies by up to its cycle; a constant lag, a clock offset or elements a
  /// day old shift both go-tos alike and cancel), and the motion at least
  /// kInStepMinDeg (a step smaller than the tolerances says nothing: the
  /// Sun, the Moon and a fast client's 1 s steps still need three) and at
  /// most kLookBackMaxDeg (the straight path holds that far). Chance does not
  /// put two go-tos within the tolerance of an object's path AND a step
  /// apart that matches its motion; a threshold client (Gpredict 5 deg, the
  /// SatNOGS client 4) sends its third go-to a minute or more after its
  /// first, which the third hit cost in pointing.
  static constexpr float kInStepMinDeg = 2.0f;
  static constexpr float kInStepToleranceDeg = 1.0f;
  static constexpr float kInStepOfMotion = 0.25f;

  /// What a go-to told.
  struct Verdict {
    bool recognised = false;  ///< `candidate` is the one object the stream follows
    int candidate = -1;       ///< < catalog size: an entry; then the Sun, the Moon
    bool ambiguous = false;   ///< more than one candidate still matches every go-to
    int evaluated = 0;        ///< candidates evaluated for this go-to
  };

  /// Forgets every candidate: the next go-to starts a new comparison.
  void restart() { started_ = false; }
  /// Compares a go-to pointing at the sky direction `az_deg`, `el_deg`
  /// (sky_direction(): the flip frame already undone) at `utc_ms` with the
  /// candidates, evaluating at most `budget` of them.
  Verdict consider(float az_deg, float el_deg, std::int64_t utc_ms,
                   const tracking::Observer& observer, const tracking::TleCatalog* catalog,
                   int budget);

  /// Keeps the recognised candidate for follows() (the comparison is over
  /// until restart()); false when it cannot be computed.
  bool hold(int candidate, const tracking::TleCatalog* catalog) {
    return load(candidate, catalog, scratch_);
  }
  /// Whether a go-to still points at the held object.
  bool follows(float az_deg, float el_deg, std::int64_t utc_ms,
               const tracking::Observer& observer) {
    return near(scratch_, az_deg, el_deg, utc_ms, observer);
  }

  /// Loads candidate `n` into `target`; false when it cannot be computed.
  static bool load(int candidate, const tracking::TleCatalog* catalog, tracking::SkyTarget& target);
  /// A go-to as the matcher keeps it: its sky direction and when it came.
  struct Pointing {
    float az_deg = 0.0f, el_deg = 0.0f;
    std::int64_t utc_ms = 0;
  };
  /// Whether a go-to at `az_deg`, `el_deg` (sky direction) at `utc_ms` is
  /// within kToleranceDeg of `target`'s recent path. With `before` (an
  /// earlier go-to) and `in_step`: whether the step from `before` to this
  /// go-to is also the object's motion over that time (kInStep...).
  static bool near(tracking::SkyTarget& target, float az_deg, float el_deg, std::int64_t utc_ms,
                   const tracking::Observer& observer, const Pointing* before = nullptr,
                   bool* in_step = nullptr);
  /// The sky direction a go-to points at: a flip frame (el above 90, as
  /// Gpredict with max el 180 and the SatNOGS client's mirrored pass send
  /// it: az +/- 180, 180 - el) is the same direction as az, el below 90.
  static void sky_direction(float& az_deg, float& el_deg);

 private:
  void start(const tracking::TleCatalog* catalog);
  bool catalog_changed(const tracking::TleCatalog* catalog) const;

  // Per candidate: kUnchecked, kOut, or the matched go-tos in a row (1..;
  // kMinHits at once for a pair in step).
  static constexpr std::uint8_t kUnchecked = 0xff;
  static constexpr std::uint8_t kOut = 0;
  std::uint8_t hits_[kMaxCandidates] = {};
  // The last go-to, and which candidates it hit: the step from it is judged
  // only for those (a small budget may skip a candidate for a go-to).
  Pointing last_;
  std::uint32_t hit_last_ = 0;
  static_assert(kMaxCandidates <= 32, "one bit per candidate");
  std::uint32_t catalog_ids_[tracking::TleCatalog::kCapacity] = {};
  int count_ = 0;   // candidates in this comparison
  int cursor_ = 0;  // where the sweep of unchecked candidates goes on
  bool started_ = false;
  tracking::SkyTarget scratch_;
};

}  // namespace rotord
