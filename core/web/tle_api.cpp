// The stored TLEs over REST (docs/web_api.md#tracking): GET, PUT and
// DELETE /api/tle; handle_track (track_api.cpp) tells the methods apart.
// Storing and removing are the command layer's (command/care_commands.hpp).
#include "command/care_commands.hpp"
#include "tracking/julian.hpp"
#include "web/query.hpp"
#include "web/track_json.hpp"
#include "web/web_api.hpp"

namespace rotord::web {

void Api::get_tles(protocol::ByteSink& out, const ResponseOptions& options) {
  if (ctx_.tles == nullptr) return send_error(out, 501, "this port keeps no TLEs", options);
  const std::optional<std::int64_t> utc = ctx_.controller.utc_ms();
  send_json(out, 200, options, [&](JsonWriter& w) {
    w.begin_object().member("capacity", static_cast<int>(tracking::TleCatalog::kCapacity));
    w.key("objects").begin_array();
    for (std::size_t n = 0; n < ctx_.tles->size(); ++n) {
      const tracking::TleCatalog::Entry& e = ctx_.tles->entry(n);
      tracking::Tle tle;
      tracking::TleCatalog::elements(e, tle);
      const double epoch_ms = tracking::tle_epoch_unix_ms(tle.epoch_year, tle.epoch_day);
      w.begin_object().member("name", e.name).member("catalog", e.catalog);
      write_utc(w, "epoch_utc", static_cast<std::int64_t>(epoch_ms));
      w.key("age_days");
      if (utc) {
        w.number((static_cast<double>(*utc) - epoch_ms) / 86400000.0);
      } else {
        w.null();
      }
      w.member("line1", e.line1).member("line2", e.line2).end_object();
    }
    w.end_array().end_object();
  });
}

void Api::put_tles(const HttpRequest& request, protocol::ByteSink& out,
                   const ResponseOptions& options, const access::Peer& peer) {
  if (ctx_.tles == nullptr) return send_error(out, 501, "this port keeps no TLEs", options);
  tracking::TleCheck check;
  const Error e = command::put_tles(ctx_.controller, {"rest", peer}, *ctx_.tles, request.body,
                                    ctx_.tle_storage, document_, check);
  if (!check.ok()) {
    char message[160];
    check.describe(message, sizeof message);
    return send_error(out, e == Error::kBusy ? 507 : 422, message, options);
  }
  if (e != Error::kOk)
    return send_error(out, 500, "the TLEs are stored in RAM but could not be saved", options);
  send_json(out, 200, options, [&](JsonWriter& w) {
    w.begin_object()
        .member("ok", true)
        .member("added", static_cast<int>(check.added))
        .member("replaced", static_cast<int>(check.replaced))
        .member("count", static_cast<int>(ctx_.tles->size()))
        .member("saved", ctx_.tle_storage != nullptr)
        .end_object();
  });
}

void Api::delete_tle(const HttpRequest& request, protocol::ByteSink& out,
                     const ResponseOptions& options, const access::Peer& peer) {
  if (ctx_.tles == nullptr) return send_error(out, 501, "this port keeps no TLEs", options);
  char object[40];
  if (!query_value(request.query, "object", object, sizeof object))
    return send_error(out, 400, "name the object: DELETE /api/tle?object=NAME_OR_NUMBER", options);
  const Error e = command::delete_tle(ctx_.controller, {"rest", peer}, *ctx_.tles, object,
                                      ctx_.tle_storage, document_);
  if (e == Error::kNotFound) return send_error(out, 404, "no such object stored", options);
  if (e != Error::kOk)
    return send_error(out, 500, "removed in RAM but could not be saved", options);
  send_json(out, 200, options, [&](JsonWriter& w) {
    w.begin_object()
        .member("ok", true)
        .member("count", static_cast<int>(ctx_.tles->size()))
        .end_object();
  });
}

}  // namespace rotord::web
