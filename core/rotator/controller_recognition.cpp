// The Controller's recognition of what a client's go-to stream follows
// (docs/tracking.md, "Trackers through the protocols"): kept apart from
// controller.cpp, which holds the commands themselves.
#include "rotator/controller.hpp"

#include <cstring>

namespace rotord {

using settings::Id;

void Controller::consider_recognition(float az_deg, float el_deg, const GotoStream::Step& step,
                                      CommandSource source) {
  // A zig-zag, a jump, another client or a pause starts the comparison over.
  if (!step.same_stream || step.zigzag) matcher_.restart();
  if (step.zigzag || source == kNoSource || !has_el_ || !settings_.b(Id::kTrackRecognise) ||
      !station_set())
    return;
  const std::optional<std::int64_t> utc = utc_ms();
  if (!utc || (!utc_clock_->synchronized() && !settings_.b(Id::kTimeTrustClock))) return;
  GotoMatcher::sky_direction(az_deg, el_deg);
  const tracking::Observer here = observer();
  const GotoMatcher::Verdict v =
      matcher_.consider(az_deg, el_deg, *utc, here, catalog_, recognise_budget_);
  if (!v.recognised) return;
  // Below track.min_el_deg the tracking mode would refuse the pass: wait.
  if (el_deg < settings_.f(Id::kTrackMinElDeg)) return;
  const int stored = catalog_ != nullptr ? static_cast<int>(catalog_->size()) : 0;
  TrackRequest request;
  request.when = TrackWhen::kNow;
  if (v.candidate < stored) {
    request.kind = tracking::TargetKind::kSatellite;
    if (!tracking::TleCatalog::elements(catalog_->entry(static_cast<std::size_t>(v.candidate)),
                                        request.tle))
      return;
  } else {
    request.kind = v.candidate == stored ? tracking::TargetKind::kSun : tracking::TargetKind::kMoon;
  }
  // The tracking mode's own follower, from where the antenna is: its plan
  // chooses the wrap and the flip for the rest of the pass. Until it has
  // planned, the client's go-to (already obeyed) points.
  if (tracker_.start(request, *utc, here, settings_, az_, &el_) != TrackError::kOk) {
    tracker_.cancel();
    return;
  }
  if (!matcher_.hold(v.candidate, catalog_)) {
    tracker_.cancel();
    return;
  }
  const std::uint32_t begun = recognition_.begun + 1;
  const std::uint32_t endings = recognition_.endings;
  recognition_ = Recognition{};
  recognition_.active = true;
  recognition_.source = source;
  recognition_.kind = request.kind;
  std::memcpy(recognition_.name, tracker_.status().name, sizeof(recognition_.name));
  recognition_.name[sizeof(recognition_.name) - 1] = '\0';
  recognition_.catalog = tracker_.status().catalog;
  recognition_.began_utc_ms = *utc;
  recognition_.gotos = 1;
  recognition_.begun = begun;
  recognition_.endings = endings;
  last_goto_recognised_ = true;
  mode_ = Mode::kTrack;
}

bool Controller::on_recognised(float az_deg, float el_deg) {
  const std::optional<std::int64_t> utc = utc_ms();
  if (!utc) return false;
  GotoMatcher::sky_direction(az_deg, el_deg);
  return matcher_.follows(az_deg, el_deg, *utc, observer());
}

void Controller::end_recognition(RecognitionEnd why) {
  if (!recognition_.active) return;
  recognition_.active = false;
  recognition_.ended = why;
  recognition_.ended_utc_ms = utc_ms().value_or(0);
  ++recognition_.endings;
  matcher_.restart();
  // The next go-to is literal: whatever follows is a new stream.
  stream_.interrupt();
  end_track();
}

}  // namespace rotord
