#include "command/commission_commands.hpp"

namespace rotord::command {
namespace {

using settings::Id;

/// A set-up change's end: refused with `r`'s reason, or kept (saved when
/// `store` is given); then its log line.
SetResult kept(Controller& controller, const Origin& from, const char* what, const char* args,
               const settings::Rejection& r, const Store* store) {
  const SetResult result = keep_change(controller, store, r);
  told_words(controller, from, what, outcome_word(result), args);
  return result;
}

}  // namespace

Error commission(Controller& controller, const Origin& from, const Commissioning::Request& request,
                 const char** why) {
  static constexpr const char* kSteps[] = {"all", "direction", "ends", "speeds", "bearing"};
  const Error e = controller.commission(request, why);
  told_words(controller, from, request.axis == AxisId::kEl ? "commission el" : "commission az",
             error_name(e), kSteps[static_cast<std::size_t>(request.step)]);
  return e;
}

SetResult accept_commissioning(Controller& controller, const Origin& from, const Store* store) {
  if (store != nullptr) store->backup = controller.settings();
  return kept(controller, from, "commission", "accept", controller.accept_commissioning(), store);
}

SetResult apply_model(Controller& controller, const Origin& from,
                      const settings::RotatorModel& model, const Store* store) {
  if (store != nullptr) store->backup = controller.settings();
  return kept(controller, from, "setup", "model",
              settings::apply_rotator_model(model, controller.settings()), store);
}

SetResult set_station(Controller& controller, const Origin& from, double lat_deg, double lon_deg) {
  settings::Settings& s = controller.settings();
  const double old_lat_deg = s.get(Id::kStationLatDeg);
  settings::Rejection r = s.set(Id::kStationLatDeg, lat_deg);
  if (r.error == Error::kOk) r = s.set(Id::kStationLonDeg, lon_deg);
  if (r.error != Error::kOk) s.set(Id::kStationLatDeg, old_lat_deg);  // all or nothing
  return kept(controller, from, "setup", "station", r, nullptr);
}

}  // namespace rotord::command
