// The set-up endpoints (docs/web_api.md, docs/commissioning.md): the rotator
// model list, filling the settings from a model, and self-commissioning
// (start, follow with its evidence, accept).
#include <cmath>
#include <cstdio>

#include "command/commission_commands.hpp"
#include "json/json_reader.hpp"
#include "json/settings_json.hpp"
#include "settings/rotator_models.hpp"
#include "settings/settings_layers.hpp"
#include "web/web_api.hpp"

namespace rotord::web {
namespace {

using settings::Id;

void write_figure(JsonWriter& w, const settings::ModelSetting& row) {
  w.begin_object().member("key", settings::def(row.id).key);
  if (row.figure->known()) {
    w.key("value");
    write_setting_value(row.id, row.figure->value, w);
    w.member("source", row.figure->source);
  } else {
    // No maker's figure: the setting is kept and commissioning measures it.
    w.key("value").null().key("source").null();
  }
  w.end_object();
}

}  // namespace

Api::Outcome Api::get_setup(const Call& call) {
  // "configured": some setting differs from the board's defaults, i.e. the
  // owner saved something; the control page offers the set-up page when not.
  settings::Settings& values = ctx_.controller.settings();
  if (ctx_.defaults == nullptr) scratch_.reset_to_defaults();
  const settings::Settings& base = ctx_.defaults != nullptr ? *ctx_.defaults : scratch_;
  const settings::KeySet saved = settings::user_layer(values, base);
  send_json(call.out, 200, call.options, [&](JsonWriter& w) {
    w.begin_object().member("configured", saved.any());
    // The station step: whether the clock tracking points from is kept, in
    // words (NTP on Linux, SNTP on the Pico W).
    if (ctx_.wall_clock != nullptr) w.member("clock_synchronized", ctx_.wall_clock->synchronized());
    if (ctx_.clock_sync != nullptr) {
      char words[256];
      const std::size_t n = ctx_.clock_sync->describe(words, sizeof words);
      w.member("clock", std::string_view(words, n < sizeof words ? n : sizeof words - 1));
    }
    w.end_object();
  });
  return Outcome::kDone;
}

Api::Outcome Api::get_models(const Call& call) {
  send_json(call.out, 200, call.options, [](JsonWriter& w) {
    w.begin_object().key("models").begin_array();
    for (const settings::RotatorModel& m : settings::rotator_models()) {
      w.begin_object().member("id", m.id).member("name", m.name).member("note", m.note);
      w.key("figures").begin_array();
      settings::ModelSetting rows[settings::kModelSettingCount];
      const std::size_t n = settings::model_settings(m, rows, settings::kModelSettingCount);
      for (std::size_t k = 0; k < n; ++k) write_figure(w, rows[k]);
      w.end_array().end_object();
    }
    w.end_array().end_object();
  });
  return Outcome::kDone;
}

Api::Outcome Api::post_model(const Call& call) {
  JsonObjectReader reader(call.request.body);
  std::string_view key;
  JsonValue value;
  std::string_view id;
  while (reader.valid() && reader.next(key, value)) {
    if (key == "model" && value.type == JsonType::kString) id = value.text;
  }
  if (!reader.valid()) {
    send_error(call.out, 400, reader.error(), call.options);
    return Outcome::kDone;
  }
  const settings::RotatorModel* model = settings::find_rotator_model(id);
  if (model == nullptr) {
    send_error(call.out, 422, "give model: one of the ids GET /api/models lists", call.options);
    return Outcome::kDone;
  }
  const command::Store saved = store();
  return send_set(call, command::apply_model(ctx_.controller, {"rest", call.peer}, *model, &saved),
                  422);
}

Api::Outcome Api::post_commission(const Call& call) {
  Controller& c = ctx_.controller;
  const settings::Settings& s = c.settings();
  Commissioning::Request request;
  bool el = false;
  bool have_ccw = false;
  bool have_cw = false;
  bool have_bearing = false;
  JsonObjectReader reader(call.request.body);
  std::string_view key;
  JsonValue value;
  const char* bad = nullptr;
  while (reader.valid() && reader.next(key, value)) {
    if (key == "axis") {
      el = value.type == JsonType::kString && value.text == "el";
      if (value.type != JsonType::kString || (value.text != "az" && value.text != "el"))
        bad = "axis is \"az\" or \"el\"";
    } else if (key == "step") {
      if (value.type != JsonType::kString ||
          !parse_commissioning_step(value.text.data(), value.text.size(), request.step))
        bad = "step is one of \"all\", \"direction\", \"ends\", \"speeds\", \"bearing\"";
    } else if (key == "bearing_deg") {
      have_bearing = true;
      // Not a number: refused with the range's reason (NaN is out of it).
      request.bearing_deg =
          value.type == JsonType::kNumber ? static_cast<float>(value.number) : NAN;
    } else if (key == "ccw_deg" || key == "cw_deg") {
      if (value.type != JsonType::kNumber) {
        bad = "ccw_deg and cw_deg are numbers (degrees)";
      } else if (key == "ccw_deg") {
        request.ccw_stop_deg = static_cast<float>(value.number);
        have_ccw = true;
      } else {
        request.cw_stop_deg = static_cast<float>(value.number);
        have_cw = true;
      }
    } else {
      bad = "unknown member (axis, step, ccw_deg, cw_deg, bearing_deg)";
    }
  }
  if (!reader.valid()) bad = reader.error();
  if (bad != nullptr) {
    send_error(call.out, 400, bad, call.options);
    return Outcome::kDone;
  }
  request.axis = el ? AxisId::kEl : AxisId::kAz;
  // The ends default to the travel in force (the model's, once chosen).
  if (!have_ccw) request.ccw_stop_deg = s.f(el ? Id::kElMinDeg : Id::kAzMinDeg);
  if (!have_cw) request.cw_stop_deg = s.f(el ? Id::kElMaxDeg : Id::kAzMaxDeg);
  // A bearing without "step":"bearing" would start a run that moves: refused.
  const char* why = "bearing_deg needs \"step\":\"bearing\"";
  const Error e = have_bearing && request.step != Commissioning::Step::kBearing
                      ? Error::kInvalidArgument
                      : command::commission(c, {"rest", call.peer}, request, &why);
  if (e != Error::kOk) {
    send_error(call.out, e == Error::kBusy || e == Error::kFaulted ? 409 : 422, why, call.options);
    return Outcome::kDone;
  }
  return get_commission(call);
}

Api::Outcome Api::get_commission(const Call& call) {
  Controller& c = ctx_.controller;
  const Commissioning& k = c.commissioning();
  const Commissioning::Measured& m = k.measured();
  send_json(call.out, 200, call.options, [&](JsonWriter& w) {
    w.begin_object()
        .member("axis", k.axis() == AxisId::kEl ? "el" : "az")
        .member("state", commissioning_state_name(k.state()))
        .member("step", k.phase_name())
        .member("reason", k.reason());
    w.key("measured").begin_object();
    if (m.direction_known) w.member("swapped", m.swapped);
    if (m.ends_known)
      w.member("ccw_reading", m.ccw_reading)
          .member("cw_reading", m.cw_reading)
          .member("noise_deg", m.noise_deg);
    if (m.speeds_known) {
      w.member("creep_deg_s", m.creep_deg_s)
          .member("fast_deg_s", m.fast_deg_s)
          .member("coast_s", m.coast_s)
          .member("backlash_deg", m.backlash_deg);
      if (m.dead_band >= 0.0f) w.member("dead_band", m.dead_band);
    }
    w.end_object();
    w.member("swap_outputs", k.proposes_swap());
    w.key("proposal").begin_array();
    for (std::size_t n = 0; n < k.proposal_count(); ++n) {
      const Commissioning::Proposal& p = k.proposal(n);
      // Values as the settings document writes them (numbers, enum names).
      w.begin_object().member("key", settings::def(p.id).key).key("value");
      write_setting_value(p.id, p.value, w);
      w.key("now");
      write_setting(c.settings(), p.id, w);
      w.end_object();
    }
    w.end_array();
    // The evidence: [t_s, deg, deg/s] rows, oldest first.
    w.key("samples").begin_array();
    for (std::size_t n = 0; n < k.sample_count(); ++n) {
      w.begin_array()
          .number(static_cast<double>(k.sample(n).t_ms) / 1000.0)
          .number(static_cast<double>(k.sample_deg(n)))
          .number(static_cast<double>(k.sample_speed_deg_s(n)))
          .end_array();
    }
    w.end_array().end_object();
  });
  return Outcome::kDone;
}

Api::Outcome Api::post_commission_accept(const Call& call) {
  const command::Store saved = store();
  return send_set(call, command::accept_commissioning(ctx_.controller, {"rest", call.peer}, &saved),
                  409);
}

}  // namespace rotord::web
