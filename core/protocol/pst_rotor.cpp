#include "protocol/pst_rotor.hpp"

#include <cmath>
#include <optional>

#include "command/typed.hpp"
#include "motion/angles.hpp"
#include "protocol/flat_xml.hpp"
#include "rotator/controller.hpp"
#include "tracking/places.hpp"
#include "util/slice.hpp"
#include "util/text.hpp"

namespace rotord::protocol {
namespace {

using A = PstRotor::Arg;
using Do = PstRotor::Action;

// The command table, in the order of docs/protocols/udp.md.
constexpr PstRotor::Command kCommands[] = {
    {"AZIMUTH", A::kNumber, Do::kAzimuth, "AZIMUTH: turn to this azimuth (compass 0..360)", true},
    {"ELEVATION", A::kNumber, Do::kElevation, "ELEVATION: turn to this elevation", true},
    {"STOP", A::kSwitch, Do::kStop, "STOP: 1 stops both axes", false},
    {"PARK", A::kSwitch, Do::kPark, "PARK: 1 goes to the park position", true},
    {"QRA", A::kLocator, Do::kQra, "QRA: turn to the bearing of this locator", true},
    {"TRACK", A::kSwitch, Do::kTrack, "TRACK: PstRotator's tracking switch (ignored)", false},
    {"AZ?", A::kQuery, Do::kAzQuery, "AZ?: answered AZ:<azimuth> to port + 1", false},
    {"EL?", A::kQuery, Do::kElQuery, "EL?: answered EL:<elevation> to port + 1", false},
};

/// What one message asks for, checked whole before anything runs.
struct Request {
  std::optional<float> az_deg;
  std::optional<float> el_deg;
  std::optional<float> qra_az_deg;
  bool stop = false;
  bool park = false;
  bool query_az = false;
  bool query_el = false;
};

const PstRotor::Command* find(const XmlItem& item) {
  for (const PstRotor::Command& c : kCommands) {
    // Queries are bare text; the others elements.
    if ((c.arg == A::kQuery) == item.name.empty() &&
        text::iequals(c.name, c.arg == A::kQuery ? item.value : item.name))
      return &c;
  }
  return nullptr;
}

/// A number of degrees, or Hamlib 4.6's pstrotator model's "%f.2" mistake:
/// six decimals and a literal ".2" ("85.000000.2"), read as 85.
bool parse_degrees(std::string_view v, float& out) {
  double d = 0;
  if (!text::parse_double(v, d)) {
    const std::size_t dot = v.find('.');
    if (dot == std::string_view::npos || v.size() != dot + 9 || text::slice(v, dot + 7) != ".2" ||
        !text::parse_double(text::slice(v, 0, dot + 7), d))
      return false;
  }
  if (d < -360.0 || d > 720.0) return false;
  out = static_cast<float>(d);
  return true;
}

bool read_request(const FlatXml& xml, const tracking::LatLon& station, Request& r) {
  for (const XmlItem& item : xml.items()) {
    const PstRotor::Command* c = find(item);
    if (c == nullptr) return false;
    bool on = false;
    switch (c->arg) {
      case A::kNumber: {
        float deg = 0.0f;
        if (!parse_degrees(item.value, deg)) return false;
        (c->action == Do::kAzimuth ? r.az_deg : r.el_deg) = deg;
        break;
      }
      case A::kSwitch:
        if (item.value != "0" && item.value != "1") return false;
        on = item.value == "1";
        if (c->action == Do::kStop) r.stop = r.stop || on;
        if (c->action == Do::kPark) r.park = r.park || on;
        break;
      case A::kLocator: {
        tracking::LatLon to;
        if (!tracking::maidenhead_centre(item.value, to)) return false;
        r.qra_az_deg = static_cast<float>(tracking::great_circle(station, to).azimuth_deg);
        break;
      }
      case A::kQuery:
        (c->action == Do::kAzQuery ? r.query_az : r.query_el) = true;
        break;
    }
  }
  return true;
}

/// A reading as PstRotator writes it: whole degrees (Minos, one of its
/// clients, accepts nothing else), the azimuth as a compass bearing.
long whole_degrees(float deg) {
  return std::lround(static_cast<double>(deg));
}

}  // namespace

std::span<const PstRotor::Command> PstRotor::commands() {
  return kCommands;
}

DatagramOutcome PstRotor::receive(std::string_view datagram, const access::Peer& from,
                                  DatagramReplies& out) {
  if (datagram.size() > kMaxDatagramBytes) return DatagramOutcome::kOversize;
  FlatXml xml;
  Request r;
  const tracking::LatLon station{controller_.settings().get(settings::Id::kStationLatDeg),
                                 controller_.settings().get(settings::Id::kStationLonDeg)};
  if (!xml.parse(datagram, "PST") || xml.items().empty() || !read_request(xml, station, r))
    return DatagramOutcome::kMalformed;

  DatagramOutcome outcome = DatagramOutcome::kDone;
  // In the manual's order: <STOP>1</STOP><AZIMUTH>85</AZIMUTH> stops, then turns.
  if (r.stop) command::stop(controller_, {"pst", from});
  const bool moves = r.park || r.az_deg || r.el_deg || r.qra_az_deg;
  if (moves && !command::may_control(controller_, {"pst", from}, "goto")) {
    outcome = DatagramOutcome::kRefused;
  } else if (moves) {
    Error e = Error::kOk;
    if (r.park) e = command::park(controller_, {"pst", from});
    std::optional<float> az = r.qra_az_deg ? r.qra_az_deg : r.az_deg;
    std::optional<float> el = r.el_deg;
    // An azimuth-only rotator ignores the elevation (Hamlib sends one).
    if (!controller_.has_el()) el.reset();
    if (e == Error::kOk && (az || el))
      e = command::go_to(controller_, {"pst", from}, az, el, AzTarget::kCompass, source_of(this));
    if (e != Error::kOk) outcome = DatagramOutcome::kFailed;
  }
  // Answers go to port + 1 of the port this protocol listens on.
  const auto reply_port =
      static_cast<std::uint16_t>(controller_.settings().i(settings::Id::kPstPort) + 1);
  const RotatorStatus s = controller_.status();
  if (r.query_az) {
    long az = whole_degrees(wrap_360(s.az.position_deg));
    if (az >= 360) az = 0;
    out.add(reply_port, "AZ:%ld\r", az);
  }
  if (r.query_el)
    out.add(reply_port, "EL:%ld\r", s.el.present ? whole_degrees(s.el.position_deg) : 0L);
  return outcome;
}

}  // namespace rotord::protocol
