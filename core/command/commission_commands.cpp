#include "command/commission_commands.hpp"

namespace rotord::command {
namespace {

using settings::Id;

/// A set-up change's end: refused with `r`'s reason, or kept (saved when
/// `store` is given); then its log line.
SetResult kept(Controller& controller, const Origin& from, std::string_view what,
               const settings::Rejection& r, const Store* store) {
  SetResult result;
  if (r.error != Error::kOk) {
    result.status = SetResult::kInvalid;
    result.reason = r.reason;
  } else {
    result = keep_change(controller, store);
  }
  told(controller, from, what.substr(0, what.find(' ')), outcome_word(result), NAN, NAN,
       what.substr(what.find(' ') + 1));
  return result;
}

}  // namespace

Error commission(Controller& controller, const Origin& from, const Commissioning::Request& request,
                 const char** why) {
  static constexpr std::string_view kWords[2][5] = {
      {"az all", "az direction", "az ends", "az speeds", "az bearing"},
      {"el all", "el direction", "el ends", "el speeds", "el bearing"}};
  return told(controller, from, "commission", controller.commission(request, why), NAN, NAN,
              kWords[request.axis == AxisId::kEl][static_cast<std::size_t>(request.step)]);
}

SetResult accept_commissioning(Controller& controller, const Origin& from, const Store* store) {
  if (store != nullptr) store->backup = controller.settings();
  return kept(controller, from, "commission accept", controller.accept_commissioning(), store);
}

SetResult apply_model(Controller& controller, const Origin& from,
                      const settings::RotatorModel& model, const Store* store) {
  if (store != nullptr) store->backup = controller.settings();
  return kept(controller, from, "setup model",
              settings::apply_rotator_model(model, controller.settings()), store);
}

SetResult set_station(Controller& controller, const Origin& from, double lat_deg, double lon_deg) {
  settings::Settings& s = controller.settings();
  const double old_lat_deg = s.get(Id::kStationLatDeg);
  settings::Rejection r = s.set(Id::kStationLatDeg, lat_deg);
  if (r.error == Error::kOk) r = s.set(Id::kStationLonDeg, lon_deg);
  if (r.error != Error::kOk) s.set(Id::kStationLatDeg, old_lat_deg);  // all or nothing
  return kept(controller, from, "setup station", r, nullptr);
}

}  // namespace rotord::command
