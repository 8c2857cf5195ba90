#pragma once
// What a command answers, as a value (docs/architecture.md, "The command
// layer"): every front end turns it into its own bytes (an HTTP status and
// JSON body, an MQTT result message). No exceptions in the core: a refusal
// is a Status and a message.
#include <cstddef>
#include <string_view>

#include "json/json_writer.hpp"
#include "rotator/place.hpp"
#include "settings/preset.hpp"

namespace rotord::command {

/// Why a command was refused, or kOk. Each maps to one HTTP status
/// (http_status), which the MQTT result message carries as well.
enum class Status : unsigned char {
  kOk,
  kBadRequest,     ///< 400: the arguments cannot be read
  kForbidden,      ///< 403: the caller may not do this
  kNotFound,       ///< 404: no such preset (or command)
  kConflict,       ///< 409: a latched fault, a limit, the emergency stop
  kUnprocessable,  ///< 422: read, but out of range or not possible here
  kLocked,         ///< 423: another operator holds the control lock
  kUnavailable,    ///< 503: failed closed (the access settings are unreadable)
};
int http_status(Status s);
/// The status in the command log's words ("DENIED", "UNPROCESSABLE"), as a
/// line protocol's Error would be.
std::string_view status_word(Status s);

/// What a successful command's reply carries beyond {"ok": true}.
enum class Reply : unsigned char { kOk, kGoto, kPlace, kPreset };

struct Result {
  Status status = Status::kOk;
  Reply reply = Reply::kOk;
  // kGoto: the targets the axes took (null when not asked for).
  bool has_az_target = false;
  bool has_el_target = false;
  float az_target_deg = 0;
  float el_target_deg = 0;
  // kPlace: where, and the bearing (a reply only when reachable). Kept
  // small: a Result lives on the Pico W's 4 KB stack under an lwIP callback.
  PlaceQuery place;
  tracking::Bearing bearing;
  // kPreset: the preset turned to.
  double preset_az_deg = 0;
  char preset_name[settings::kPresetNameMaxBytes + 1] = {};
  /// Why, when refused (a sentence in the API's wording).
  char message[128] = {};

  bool ok() const { return status == Status::kOk; }
};

/// A refusal with `message` (copied, cut to fit).
Result refused(Status status, std::string_view message);
/// A refusal with a printf-formatted message.
Result refusedf(Status status, const char* format, ...) __attribute__((format(printf, 2, 3)));
/// The controller's refusal of a command, in the API's words (one mapping
/// for every command that moves an axis).
Result refused_by(Error e);

/// The reply as the REST body and the MQTT "response": {"error": message}
/// when refused, else {"ok": true, ...}.
void write_result(web::JsonWriter& w, const Result& r);
/// The place's members of a reply (GET /api/place writes them too).
void write_aim(web::JsonWriter& w, const PlaceQuery& q, const PlaceAim& aim);

}  // namespace rotord::command
