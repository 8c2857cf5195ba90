#pragma once
// Settings writes in the command layer (docs/architecture.md, "The command
// layer"): who may write which key, once for every front end; a setting from
// text (the console's `set`, rotctld's `C`, Easycomm's `CW`, a REST preset), a JSON document of
// them (POST /api/settings, the console's `import`), the defaults back (POST /api/settings/reset).
// Each writes its one log line (docs/logging.md), naming the keys and never a value, so a password
// never reaches the log:
//   command set az.offset_deg from console (USB): OK
//   command set access.control_networks from rest (192.168.1.20): DENIED
// The front ends keep only their bytes: the key's spelling, the reply.
#include <string_view>

#include "command/command_log.hpp"
#include "json/settings_json.hpp"

namespace rotord::command {

/// Who writes, as the one access rule tells writers apart (docs/security.md).
enum class Writer : unsigned char {
  kLogin,    ///< the web login, or REST with access control off: any key
  kToken,    ///< a REST bearer token: not the access rules, not a secret
  kNetwork,  ///< the console over the network, or a line protocol (rotctld `C`,
             ///< Easycomm `CW`) over any line: not the access rules, not a secret
  kLine,     ///< the console over USB or serial: secrets too, not the access rules
};
/// The console's writer: kLine on a local line (USB, serial), else kNetwork.
inline Writer line_writer(const access::Peer& peer) {
  return peer.kind == access::Peer::Kind::kLine ? Writer::kLine : Writer::kNetwork;
}

/// Why a writer may not write a key.
enum class Refusal : unsigned char {
  kNone,      ///< it may
  kWebOnly,   ///< an access rule or a credential: written through the web only
  kPassword,  ///< a secret: over USB or serial, never the network
  kLogin,     ///< a token asked for what needs the web login
};
/// The one rule of who may write which setting: a client must not widen its
/// own rights, and a password never crosses the network in a line protocol.
Refusal may_write(settings::Id id, Writer writer);

/// Stores a REST change before the request is answered (the console's
/// changes are stored by the port's settings saver).
struct Store {
  settings::Settings& backup;  ///< set to the settings before the change
  bool (*save)(void* context);
  void* context;
};

/// What a settings write came to.
struct SetResult {
  enum Status : unsigned char { kOk, kRefused, kBadJson, kInvalid, kNotSaved } status = kOk;
  Refusal refusal = Refusal::kNone;  ///< kRefused: why
  settings::Id key{};                ///< set_settings, kRefused: the key refused
  const char* reason = "";           ///< kBadJson, kInvalid: why
  bool listed = false;               ///< kInvalid: the Scratch's errors name the keys
  web::SettingSet changed;           ///< kOk with a Store: the values that changed
};

/// One setting from text, with every check of the table and the rules
/// across settings (a value that breaks one is undone); saved through
/// `store` when given (REST's presets, preset_api.cpp).
SetResult set_setting(Controller& controller, const Origin& from, Writer writer, settings::Id id,
                      std::string_view text, const Store* store = nullptr);

/// A document's work space: where its ~600 bytes live is the caller's choice.
struct Scratch {
  settings::Settings& settings;
  web::SettingErrors& errors;
};
/// A JSON document of settings, all or nothing: a key `writer` may not write
/// refuses the whole document before anything changes.
SetResult set_settings(Controller& controller, const Origin& from, Writer writer,
                       std::string_view json, const Scratch& scratch, const Store* store);

/// Every setting back to `defaults` but the credentials (the web password
/// and the tokens): a reset must not open the controller to everyone.
SetResult reset_settings(Controller& controller, const Origin& from,
                         const settings::Settings& defaults, const Store& store);

/// The end of a change already made in the settings (`store`'s backup holds
/// them from before it): saved, the changed values listed; or, when saving
/// fails, undone. Without a store: kOk, nothing listed. A change refused
/// (`refused`, nothing changed): kInvalid with its reason.
SetResult keep_change(Controller& controller, const Store* store,
                      const settings::Rejection& refused = {});

/// The log line's words for a write that came to `result`: "OK", "DENIED"...
const char* outcome_word(const SetResult& result);
/// The log line of a settings, set-up or calibration command: `what`
/// (static: the log keeps it; a per-axis command's names its axis, "cal az"),
/// then `args`, then the outcome.
void told_words(Controller& controller, const Origin& from, const char* what, const char* outcome,
                const char* args);

}  // namespace rotord::command
