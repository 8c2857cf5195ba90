// rotctl's locator and angle helpers (rotctl_parse.c, Hamlib 4.5.4): the
// arithmetic is rotctld_locator.cpp's; here the arguments and the replies.
#include "protocol/rotctld_locator.hpp"
#include "protocol/rotctld_number.hpp"
#include "protocol/rotctld_session.hpp"

namespace rotord::protocol {

using rotctld::HamlibError;
using rotctld::Op;

HamlibError RotctldSession::locator_helper(Op op) {
  // rotctl's helpers read their numbers with a plain sscanf ("%lf"/"%d").
  double d[4] = {};
  long n[4] = {};
  auto real = [&](std::size_t i) { return rotctld::scan_float(arg(i), d[i], false); };
  auto integer = [&](std::size_t i) { return rotctld::scan_int(arg(i), n[i]); };
  switch (op) {
    case Op::kLonLat2Loc: {
      if (!real(0) || !real(1) || !integer(2)) return HamlibError::kInvalid;
      char locator[16];
      if (!rotctld::lonlat_to_locator(d[0], d[1], static_cast<int>(n[2] / 2), locator,
                                      sizeof(locator)))
        return HamlibError::kInvalid;
      value("Locator", "%s", locator);
      return HamlibError::kOk;
    }
    case Op::kLoc2LonLat: {
      const std::optional<rotctld::LonLat> p = rotctld::locator_to_lonlat(arg(0));
      if (!p) return HamlibError::kInvalid;
      value("Longitude", "%f", p->lon_deg);
      value("Latitude", "%f", p->lat_deg);
      return HamlibError::kOk;
    }
    case Op::kQrb: {
      if (!real(0) || !real(1) || !real(2) || !real(3)) return HamlibError::kInvalid;
      const std::optional<rotctld::Qrb> q = rotctld::qrb(d[0], d[1], d[2], d[3]);
      if (!q) return HamlibError::kInvalid;
      value("QRB Distance", "%f", q->distance_km);
      value("QRB Azimuth", "%f", q->azimuth_deg);
      return HamlibError::kOk;
    }
    case Op::kAzSp2AzLp: {
      if (!real(0)) return HamlibError::kInvalid;
      const std::optional<double> lp = rotctld::long_path_azimuth(d[0]);
      if (!lp) return HamlibError::kInvalid;
      value("Long Path Deg", "%f", *lp);
      return HamlibError::kOk;
    }
    case Op::kDistSp2DistLp:
      if (!real(0)) return HamlibError::kInvalid;
      value("Long Path km", "%f", rotctld::long_path_km(d[0]));
      return HamlibError::kOk;
    default:
      return angle_helper(op);
  }
}

HamlibError RotctldSession::angle_helper(Op op) {
  double d[4] = {};
  long n[4] = {};
  auto real = [&](std::size_t i) { return rotctld::scan_float(arg(i), d[i], false); };
  auto integer = [&](std::size_t i) { return rotctld::scan_int(arg(i), n[i]); };
  switch (op) {
    case Op::kDms2Dec:
      if (!integer(0) || !integer(1) || !real(2) || !integer(3)) return HamlibError::kInvalid;
      value("Dec Degrees", "%f",
            rotctld::dms_to_decimal(static_cast<int>(n[0]), static_cast<int>(n[1]), d[2],
                                    static_cast<int>(n[3])));
      return HamlibError::kOk;
    case Op::kDec2Dms: {
      if (!real(0)) return HamlibError::kInvalid;
      const rotctld::Dms r = rotctld::decimal_to_dms(d[0]);
      value("Degrees", "%d", r.degrees);
      value("Minutes", "%d", r.minutes);
      value("Seconds", "%f", r.seconds);
      value("S/W", "%d", r.south_west);
      return HamlibError::kOk;
    }
    case Op::kDmmm2Dec:
      if (!integer(0) || !real(1) || !integer(2)) return HamlibError::kInvalid;
      value("Dec Deg", "%f",
            rotctld::dmmm_to_decimal(static_cast<int>(n[0]), d[1], static_cast<int>(n[2])));
      return HamlibError::kOk;
    case Op::kDec2Dmmm: {
      if (!real(0)) return HamlibError::kInvalid;
      const rotctld::Dms r = rotctld::decimal_to_dms(d[0]);
      value("Degrees", "%d", r.degrees);
      value("Dec Minutes", "%f", r.minutes + r.seconds / 60.0);
      value("S/W", "%d", r.south_west);
      return HamlibError::kOk;
    }
    default:
      return HamlibError::kNotImplemented;
  }
}

}  // namespace rotord::protocol
