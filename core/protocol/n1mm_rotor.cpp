#include "protocol/n1mm_rotor.hpp"

#include <cmath>
#include <optional>

#include "command/typed.hpp"
#include "motion/angles.hpp"
#include "protocol/flat_xml.hpp"
#include "rotator/controller.hpp"
#include "util/text.hpp"

namespace rotord::protocol {
namespace {

using V = N1mmRotor::Value;

// The element table, in the order of docs/protocols/udp.md.
constexpr N1mmRotor::Element kElements[] = {
    {"rotor", V::kName, "rotor: the Rotor Description of the antenna (n1mm.rotor_name)", false},
    {"goazi", V::kBearing, "goazi: the beam heading to turn to, 0..360", true},
    {"offset", V::kOffset, "offset: the antenna points this far clockwise of the rotor", false},
    {"bidirectional", V::kFlag, "bidirectional: 1, either end of the beam will do", false},
    {"freqband", V::kNumber, "freqband: the band in MHz (ignored)", false},
    {"stop", V::kName, "stop: stop that rotor (its name, a flag, or its elements nested)", false},
};

/// The longest rotor name compared or reported; n1mm.rotor_name holds 32.
constexpr std::size_t kMaxName = 64;

/// What one message asks for, checked whole before anything runs.
struct Request {
  std::optional<std::string_view> name;  // from <rotor> or <stop>, escaped
  std::optional<float> goazi_deg;
  float offset_deg = 0.0f;
  bool bidirectional = false;
  bool stop = false;
  /// Something in the message is not as the format says: only a stop in it
  /// is obeyed.
  bool malformed = false;
};

const N1mmRotor::Element* find(std::string_view name) {
  for (const N1mmRotor::Element& e : kElements) {
    if (text::iequals(e.name, name)) return &e;
  }
  return nullptr;
}

bool parse_flag(std::string_view v, bool& out) {
  if (v == "1" || text::iequals(v, "true")) return out = true, true;
  if (v == "0" || text::iequals(v, "false")) return out = false, true;
  return false;
}

bool parse_number(std::string_view v, double lo, double hi, float& out) {
  double d = 0;
  if (!text::parse_double(v, d) || d < lo || d > hi) return false;
  out = static_cast<float>(d);
  return true;
}

bool read_items(std::span<const XmlItem> items, Request& r, bool inside_stop);

/// The rotor's name from one element; false when it disagrees with another.
bool take_name(std::string_view value, Request& r) {
  if (value.size() > kMaxName) return false;
  if (r.name && *r.name != value) return false;  // <rotor> and <stop> disagree
  r.name = value;
  return true;
}

/// `<stop>` in each form it is sent in (docs/protocols/udp.md, "Stop"):
/// the rotor's name (N1MM+'s documented form), a flag (True / False, 1 / 0)
/// or the rotor's elements nested inside.
bool read_stop(const XmlItem& item, Request& r) {
  if (item.nested) {
    FlatXml inner;
    r.stop = true;
    return inner.parse_content(item.value) && read_items(inner.items(), r, true);
  }
  bool flag = false;
  if (parse_flag(item.value, flag)) {
    r.stop = r.stop || flag;
    return true;
  }
  r.stop = true;
  return !item.value.empty() && take_name(item.value, r);
}

/// Fills `r` from the items; false when anything is not as the format says
/// (r.stop may still be set: a stop is obeyed whatever else is wrong).
bool read_items(std::span<const XmlItem> items, Request& r, bool inside_stop) {
  unsigned seen = 0;  // one bit per row: each element at most once
  bool ok = true;
  for (const XmlItem& item : items) {
    const N1mmRotor::Element* e = item.name.empty() ? nullptr : find(item.name);
    if (e == nullptr || (inside_stop && e->name == "stop")) {
      ok = false;
      continue;
    }
    const unsigned bit = 1u << static_cast<unsigned>(e - kElements);
    if ((seen & bit) != 0) ok = false;
    seen |= bit;
    float number = 0.0f;
    bool good = true;
    if (e->name == "stop") {
      good = read_stop(item, r);
    } else if (item.nested) {
      good = false;
    } else {
      switch (e->value) {
        case V::kName:
          good = take_name(item.value, r);
          break;
        case V::kBearing:
          good = parse_number(item.value, 0.0, 360.0, number);
          if (good) r.goazi_deg = number;
          break;
        case V::kOffset:
          good = parse_number(item.value, -360.0, 360.0, r.offset_deg);
          break;
        case V::kFlag:
          good = parse_flag(item.value, r.bidirectional);
          break;
        case V::kNumber:
          good = parse_number(item.value, -1e9, 1e9, number);
          break;
      }
    }
    ok = ok && good;
  }
  return ok;
}

/// Reads the message. A stop wins over a heading in the same message;
/// without a stop, a message must turn.
void read_request(const FlatXml& xml, Request& r) {
  r.malformed = !read_items(xml.items(), r, false);
  if (!r.stop && !r.goazi_deg) r.malformed = true;
}

/// Of a bidirectional antenna's two rotor bearings, the one the rotator
/// reaches with the least turning (within its travel).
float nearer_end(Controller& controller, float bearing_deg) {
  const float other_deg = wrap_360(bearing_deg + 180.0f);
  const float at = controller.status().az.position_deg;
  const std::optional<float> a = controller.resolve_az(bearing_deg, AzTarget::kCompass);
  const std::optional<float> b = controller.resolve_az(other_deg, AzTarget::kCompass);
  if (!a) return other_deg;
  if (!b) return bearing_deg;
  return std::fabs(*b - at) < std::fabs(*a - at) ? other_deg : bearing_deg;
}

}  // namespace

std::span<const N1mmRotor::Element> N1mmRotor::elements() {
  return kElements;
}

DatagramOutcome N1mmRotor::receive(std::string_view datagram, const access::Peer& from,
                                   DatagramReplies& out) {
  if (datagram.size() > kMaxDatagramBytes) return DatagramOutcome::kOversize;
  FlatXml xml;
  Request r;
  if (!xml.parse(datagram, "N1MMRotor", "stop")) return DatagramOutcome::kMalformed;
  read_request(xml, r);
  char name[kMaxName];
  std::size_t name_size = 0;
  if (r.name) {
    name_size = xml_unescape(*r.name, name, sizeof(name));
    if (name_size == std::string_view::npos) {
      // A name that cannot be read is nobody's; a stop without a name is
      // everybody's (below).
      if (!r.stop) return DatagramOutcome::kMalformed;
      r.malformed = true;
      name_size = 0;
    }
  }
  const std::string_view wanted =
      text::trim(controller_.settings().text(settings::Id::kN1mmRotorName));
  // A stop that names no rotor stops every rotator that hears it: stopping
  // one too many is safe, missing one is not.
  const bool named = name_size > 0;
  if (!wanted.empty() && (named || !r.stop) &&
      text::trim(std::string_view(name, name_size)) != wanted)
    return DatagramOutcome::kNotForUs;
  if (r.malformed && !r.stop) return DatagramOutcome::kMalformed;

  DatagramOutcome outcome = DatagramOutcome::kDone;
  if (r.stop) {
    command::stop(controller_, {"n1mm", from});  // whoever sends it
  } else if (!command::may_control(controller_, {"n1mm", from}, "goto")) {
    outcome = DatagramOutcome::kRefused;
  } else {
    // The rotor turns so that the antenna, `offset` clockwise of it, points
    // at goazi.
    float bearing_deg = wrap_360(*r.goazi_deg - r.offset_deg);
    if (r.bidirectional) bearing_deg = nearer_end(controller_, bearing_deg);
    if (command::go_to(controller_, {"n1mm", from}, bearing_deg, std::nullopt, AzTarget::kCompass,
                       source_of(this)) != Error::kOk)
      outcome = DatagramOutcome::kFailed;
  }
  const std::string_view label = wanted.empty() ? std::string_view(name, name_size) : wanted;
  report(label, out);
  // Then every second while it turns, to this sender (IPv4: the address the
  // ports can send to without keeping the message).
  if (from.is_network() && label.size() < sizeof(report_name_)) {
    report_to_ = from;
    reporting_ = true;
    next_report_ms_ = controller_.now() + kReportPeriodMs;
    report_name_size_ = label.size();
    for (std::size_t i = 0; i < label.size(); ++i) report_name_[i] = label[i];
  }
  return outcome;
}

bool N1mmRotor::poll(DatagramReplies& out, access::Peer& to) {
  if (!reporting_ || controller_.now() < next_report_ms_) return false;
  next_report_ms_ = controller_.now() + kReportPeriodMs;
  // The report after the rotator stopped is the last.
  if (!controller_.status().moving()) reporting_ = false;
  report(std::string_view(report_name_, report_name_size_), out);
  to = report_to_;
  return out.count() > 0;
}

void N1mmRotor::report(std::string_view name, DatagramReplies& out) const {
  const int report_port = controller_.settings().i(settings::Id::kN1mmReportPort);
  if (report_port <= 0) return;
  // The rotator's heading as N1MM's rotor program reports it: tenths of a
  // degree, 0..3599, under the name N1MM+ knows the rotor by.
  const float bearing = wrap_360(controller_.status().az.position_deg);
  long tenths = std::lround(static_cast<double>(bearing) * 10.0);
  if (tenths >= 3600) tenths = 0;
  out.add(static_cast<std::uint16_t>(report_port), "%.*s @ %ld", static_cast<int>(name.size()),
          name.data(), tenths);
}

}  // namespace rotord::protocol
