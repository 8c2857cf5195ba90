// The console's listings (list, export): written in windows as the
// transport has room (Session::write_more), while what the client types
// meanwhile waits in its hold.
#include <cstring>

#include "command/settings_commands.hpp"
#include "json/json_writer.hpp"
#include "json/settings_json.hpp"
#include "protocol/console_reply.hpp"
#include "protocol/console_session.hpp"
#include "protocol/window_sink.hpp"
#include "rotator/controller.hpp"
#include "settings/settings_layers.hpp"

namespace rotord::protocol {

using console::Echo;
using console::error;
using console::send;
using console::Value;
using settings::Id;

const settings::Settings* ConsoleSession::export_base() const {
  if (port_ == nullptr) return nullptr;
  if (port_->defaults != nullptr) return port_->defaults;
  if (port_->scratch == nullptr) return nullptr;
  port_->scratch->reset_to_defaults();
  return port_->scratch;
}

void ConsoleSession::start_listing(Listing listing, std::string_view prefix, ByteSink&) {
  listing_ = listing;
  listing_sent_ = 0;
  listing_revision_ = controller_.settings().revision();
  const std::size_t n = std::min(prefix.size(), sizeof list_prefix_ - 1);
  if (n > 0) std::memcpy(list_prefix_, prefix.data(), n);  // an empty view's data() may be null
  list_prefix_[n] = '\0';
}

void ConsoleSession::write_listing(ByteSink& out) const {
  const settings::Settings& values = controller_.settings();
  int count = 0;
  if (listing_ == Listing::kExport) {
    const settings::Settings* base = export_base();
    const settings::KeySet keys = settings::user_layer(values, *base);
    {
      web::JsonWriter w(out);
      w.begin_object().member(settings::kVersionKey, settings::kStoredVersion);
      for (std::size_t n = 0; n < settings::kCount; ++n) {
        const auto id = static_cast<Id>(n);
        // Passwords are masked in any export, so they carry nothing.
        if (!keys[n] || command::may_write(id, command::Writer::kLine) != command::Refusal::kNone ||
            (settings::def(id).flags & settings::kSecret) != 0)
          continue;
        w.key(settings::def(id).key);
        web::write_setting(values, id, w);
        ++count;
      }
      w.end_object();
    }
    out.write("\r\n");
    send(out, "ok %d settings differ from the defaults", count);
    return;
  }
  const std::string_view prefix(list_prefix_);
  for (std::size_t n = 0; n < settings::kCount; ++n) {
    const auto id = static_cast<Id>(n);
    const char* key = settings::def(id).key;
    // Not the stored hashes and tokens, which the web's form hides too.
    if ((settings::def(id).flags & settings::kHidden) != 0) continue;
    if (!std::string_view(key).starts_with(prefix)) continue;
    const Value value(values, id);
    send(out, "%s=%s", key, value.text);
    ++count;
  }
  if (count == 0) {
    const Echo echo(prefix);
    return send(out, "error: no setting starts with '%s'", echo.text);
  }
  send(out, "ok %d settings", count);
}

void ConsoleSession::write_more(std::size_t room_bytes, ByteSink& out) {
  if (listing_ == Listing::kNone) return;
  if (listing_ != Listing::kHeld && controller_.settings().revision() != listing_revision_) {
    // Its windows would no longer join up.
    if (listing_sent_ > 0) out.write("\r\n");
    error(out, "the settings changed during the listing: ask again");
  } else if (listing_ != Listing::kHeld) {
    WindowSink window(out, listing_sent_, room_bytes, WindowSink::Cut::kWhole);
    write_listing(window);
    listing_sent_ += window.written();
    if (listing_sent_ < window.total()) return;
    if (window.written() > 0 && (held_ > 0 || hold_dropped_ > 0)) {
      listing_ = Listing::kHeld;  // this window had its room
      return;
    }
  }
  listing_ = Listing::kNone;
  // What was typed meanwhile, in order.
  std::array<char, kHoldBytes> held{};
  const std::size_t n = held_;
  std::memcpy(held.data(), hold_.data(), n);
  held_ = 0;
  if (hold_dropped_ > 0) {
    send(out, "error: %u bytes typed during the listing were dropped",
         static_cast<unsigned>(hold_dropped_));
    hold_dropped_ = 0;
  }
  feed(std::string_view(held.data(), n), out);
}

}  // namespace rotord::protocol
