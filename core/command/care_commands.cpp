#include "command/care_commands.hpp"

#include <cstdio>

namespace rotord::command {

TrackError track(Controller& controller, const Origin& from, const TrackRequest& request) {
  const TrackError e = controller.track(request);
  // The words: "start ISS (ZARYA)" (a TLE without a title line: its
  // catalog number), "start sun", "start moon", or "start" and the az/el.
  using tracking::TargetKind;
  const bool fixed = request.kind == TargetKind::kNone;
  char words[40] = "start";
  if (request.kind == TargetKind::kSatellite && request.tle.name[0] == '\0') {
    std::snprintf(words, sizeof words, "start %lu",
                  static_cast<unsigned long>(request.tle.catalog));
  } else if (!fixed) {
    std::snprintf(words, sizeof words, "start %s",
                  request.kind == TargetKind::kSun    ? "sun"
                  : request.kind == TargetKind::kMoon ? "moon"
                                                      : request.tle.name);
  }
  told(controller, from, "track",
       e == TrackError::kOk ? std::string_view("OK") : status_word(track_refusal(e)),
       fixed ? request.az_deg : NAN, fixed ? request.el_deg : NAN, words);
  return e;
}

Status track_refusal(TrackError e) {
  switch (e) {
    case TrackError::kNoClock:
    case TrackError::kClockUnsynced:
    case TrackError::kNoStation:
    case TrackError::kFaulted:
    case TrackError::kStowed:
    case TrackError::kBelowHorizon:
      return Status::kConflict;
    default:
      return Status::kUnprocessable;
  }
}

void end_track(Controller& controller, const Origin& from) {
  controller.stop();
  told(controller, from, "track", Error::kOk, NAN, NAN, "stop");
}

Error put_tles(Controller& controller, const Origin& from, tracking::TleCatalog& tles,
               std::string_view text, hal::Storage* storage, std::span<char> document,
               tracking::TleCheck& check) {
  check = tles.put(text, controller.utc_ms().value_or(0));
  Error e = Error::kOk;
  char words[24] = "";
  if (!check.ok()) {
    e = check.problem == tracking::TleCheck::Problem::kFull ? Error::kBusy
                                                            : Error::kInvalidArgument;
  } else {
    const std::size_t n = check.added + check.replaced;
    std::snprintf(words, sizeof words, "%u object%s", static_cast<unsigned>(n), n == 1 ? "" : "s");
    if (storage != nullptr && !tles.save(*storage, document.data(), document.size()))
      e = Error::kStorage;
  }
  return told(controller, from, "tle", e, NAN, NAN, words);
}

Error delete_tle(Controller& controller, const Origin& from, tracking::TleCatalog& tles,
                 const char* object, hal::Storage* storage, std::span<char> document) {
  Error e = Error::kNotFound;
  if (const tracking::TleCatalog::Entry* entry = tles.find(object)) {
    tles.remove(entry->catalog);
    e = storage == nullptr || tles.save(*storage, document.data(), document.size())
            ? Error::kOk
            : Error::kStorage;
  }
  return told(controller, from, "tle delete", e, NAN, NAN, object);
}

void reset_odometer(Controller& controller, const Origin& from) {
  const std::optional<std::int64_t> utc_ms = controller.utc_ms();
  controller.odometer().reset(utc_ms ? *utc_ms / 1000 : 0);
  // One word-pair as the console's refusal names it ("odometer reset"), so a
  // repeat's summary line names it whole too.
  told(controller, from, "odometer reset", Error::kOk);
}

Error wind_override(Controller& controller, const Origin& from, int minutes) {
  char words[24] = "override";
  if (minutes > 0) std::snprintf(words, sizeof words, "override %d", minutes);
  return told(controller, from, "wind", controller.wind_override(minutes), NAN, NAN, words);
}

Error end_wind_override(Controller& controller, const Origin& from) {
  Error e = Error::kNotFound;
  if (controller.wind().state() == care::WindState::kOverride) {
    controller.end_wind_override();
    e = Error::kOk;
  }
  return told(controller, from, "wind", e, NAN, NAN, "stow");
}

}  // namespace rotord::command
