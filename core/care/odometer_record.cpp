#include "care/odometer_record.hpp"

#include <cmath>
#include <cstdio>
#include <cstring>

#include "json/json_reader.hpp"
#include "util/fixed_sink.hpp"
#include "util/slice.hpp"

namespace rotord::care {
namespace {

using web::JsonObjectReader;
using web::JsonType;
using web::JsonValue;
using web::JsonWriter;

constexpr const char* kFaultKeys[kAxisFaultKinds] = {
    "none",    "stall",     "sensor_lost",  "sensor_range", "sensor_jump",
    "timeout", "no_sensor", "sensor_stuck", "slip",         "estop"};

/// The counters of a wear record by name, for the writer and the reader
/// alike (one list, so the two cannot drift apart).
struct Field {
  const char* name;
  std::uint32_t AxisWear::*u32;
};
constexpr Field kFields[] = {{"starts", &AxisWear::starts},
                             {"reversals", &AxisWear::reversals},
                             {"turned_deg", &AxisWear::turned_deg},
                             {"brake_cycles", &AxisWear::brake_cycles},
                             {"relay_switchings", &AxisWear::relay_switchings}};
constexpr std::size_t kFieldCount = sizeof kFields / sizeof kFields[0];
/// Every key an axis has: the fields, run_ms, and a fault count per kind.
constexpr std::size_t kKeysPerAxis = kFieldCount + 1 + (kAxisFaultKinds - 1);

void write_axis_flat(JsonWriter& w, const char* prefix, const AxisWear& wear) {
  char key[40];
  for (const Field& f : kFields) {
    std::snprintf(key, sizeof key, "%s.%s", prefix, f.name);
    w.member(key, wear.*f.u32);
  }
  std::snprintf(key, sizeof key, "%s.run_ms", prefix);
  w.member(key, static_cast<long long>(wear.run_ms));
  for (std::size_t n = 1; n < kAxisFaultKinds; ++n) {
    std::snprintf(key, sizeof key, "%s.faults.%s", prefix, kFaultKeys[n]);
    w.member(key, wear.faults[n]);
  }
}

/// A whole number in [0, max]: a count can be nothing else.
bool count_value(const JsonValue& v, double max, double& out) {
  if (v.type != JsonType::kNumber || !std::isfinite(v.number) || v.number < 0.0 || v.number > max ||
      std::floor(v.number) != v.number)
    return false;
  out = v.number;
  return true;
}

/// Stores one "az.x" / "el.x" member; false when the key is not a counter.
bool store(AxisWear& wear, std::string_view name, double value, bool& big_ok) {
  for (const Field& f : kFields) {
    if (name == f.name) {
      wear.*f.u32 = static_cast<std::uint32_t>(value);
      return true;
    }
  }
  if (name == "run_ms") {
    big_ok = true;
    wear.run_ms = static_cast<std::uint64_t>(value);
    return true;
  }
  constexpr std::string_view kFaults = "faults.";
  if (text::slice(name, 0, kFaults.size()) == kFaults) {
    const std::string_view kind = text::slice(name, kFaults.size());
    for (std::size_t n = 1; n < kAxisFaultKinds; ++n) {
      if (kind == kFaultKeys[n]) {
        wear.faults[n] = static_cast<std::uint32_t>(value);
        return true;
      }
    }
  }
  return false;
}

}  // namespace

const char* fault_key(AxisFault kind) {
  const auto n = static_cast<std::size_t>(kind);
  return n < kAxisFaultKinds ? kFaultKeys[n] : "?";
}

std::size_t encode_record(const Odometer& odometer, char* buf, std::size_t capacity) {
  FixedSink sink(buf, capacity);
  {
    JsonWriter w(sink);
    w.begin_object()
        .member("format", kRecordFormat)
        .member("reset_unix_s", static_cast<long long>(odometer.reset_unix_s()));
    write_axis_flat(w, "az", odometer.axis(AxisId::kAz).wear());
    write_axis_flat(w, "el", odometer.axis(AxisId::kEl).wear());
    w.end_object();
  }
  return sink.overflowed() ? 0 : sink.view().size();
}

bool decode_record(std::string_view text, AxisWear& az, AxisWear& el, std::int64_t& reset_unix_s,
                   const char*& why) {
  JsonObjectReader reader(text);
  if (!reader.valid()) {
    why = "not a JSON object";
    return false;
  }
  az = {};
  el = {};
  reset_unix_s = 0;
  bool format_seen = false;
  std::size_t counts_seen = 0;
  std::string_view key;
  JsonValue value;
  while (reader.next(key, value)) {
    if (key == "format") {
      if (value.type != JsonType::kNumber || value.number != kRecordFormat) {
        why = "a format this rotord does not know";
        return false;
      }
      format_seen = true;
      continue;
    }
    double number = 0.0;
    if (key == "reset_unix_s") {
      if (!count_value(value, 9.0e15, number)) {
        why = "reset_unix_s is not a date";
        return false;
      }
      reset_unix_s = static_cast<std::int64_t>(number);
      continue;
    }
    AxisWear* wear = text::slice(key, 0, 3) == "az."   ? &az
                     : text::slice(key, 0, 3) == "el." ? &el
                                                       : nullptr;
    if (wear == nullptr) {
      why = "an unknown key";
      return false;
    }
    // run_ms may pass 2^32 (50 days of running); every other count may not.
    if (!count_value(value, 9.0e15, number)) {
      why = "a count that is negative, fractional or not a number";
      return false;
    }
    bool big_ok = false;
    if (!store(*wear, text::slice(key, 3), number, big_ok)) {
      why = "an unknown key";
      return false;
    }
    if (!big_ok && number > 4294967295.0) {
      why = "a count beyond 32 bits";
      return false;
    }
    ++counts_seen;
  }
  if (!format_seen) {
    why = "no format";
    return false;
  }
  if (counts_seen != 2 * kKeysPerAxis) {
    why = "counts missing";
    return false;
  }
  return true;
}

void write_wear(JsonWriter& w, const AxisWear& wear) {
  w.begin_object();
  for (const Field& f : kFields) w.member(f.name, wear.*f.u32);
  w.member("run_s", static_cast<long long>(wear.run_ms / 1000));
  w.key("faults").begin_object();
  for (std::size_t n = 1; n < kAxisFaultKinds; ++n) w.member(kFaultKeys[n], wear.faults[n]);
  w.end_object();
  w.member("faults_total", wear.faults_total());
  w.end_object();
}

}  // namespace rotord::care
