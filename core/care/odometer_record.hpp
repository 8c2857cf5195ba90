#pragma once
#include <cstddef>
#include <string_view>

#include "care/odometer.hpp"
#include "json/json_writer.hpp"

namespace rotord::care {

/// The odometer's own record in storage (a file beside the settings on
/// Linux, flash slots of its own on the Pico W): one flat JSON object, so
/// the settings' JSON reader reads it and a person can too:
///
///   {"format":1,"reset_unix_s":0,"az.starts":12,"az.reversals":3,...,
///    "az.faults.stall":0,...,"el.starts":0,...}
///
/// Kept apart from the settings: a damaged counter record costs the counts,
/// never a setting, and the counts change far more often than settings do.
inline constexpr int kRecordFormat = 1;

/// Writes the record into buf; its length, or 0 when it does not fit.
std::size_t encode_record(const Odometer& odometer, char* buf, std::size_t capacity);

/// Reads a record into `az`, `el` and `reset_unix_s`. False, with the
/// reason in `why` (a static string), for anything but a whole valid record:
/// bad JSON, another format, a count missing, negative, fractional or too
/// large, an unknown key. The outputs are then unspecified.
bool decode_record(std::string_view text, AxisWear& az, AxisWear& el, std::int64_t& reset_unix_s,
                   const char*& why);

/// One axis's wear as a JSON object (GET /api/status, the MQTT state):
/// {"starts", "reversals", "run_s", "turned_deg", "brake_cycles",
///  "relay_switchings", "faults": {"stall": n, ...}, "faults_total"}.
void write_wear(web::JsonWriter& w, const AxisWear& wear);

/// The lower-case name of a fault kind as the record and the API spell it
/// ("stall", "sensor_stuck").
const char* fault_key(AxisFault kind);

}  // namespace rotord::care
