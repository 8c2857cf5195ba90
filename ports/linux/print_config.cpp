#include "print_config.hpp"

#include <cstdlib>
#include <memory>
#include <vector>

#include "file_storage.hpp"
#include "json/settings_json.hpp"
#include "legacy_profile_guess.hpp"
#include "settings/settings_layers.hpp"
#include "web/web_api.hpp"

namespace rotord::linux_port {
namespace {

struct OptionRow {
  std::string name;
  std::string value;
};

std::vector<OptionRow> option_rows(const Options& o) {
  auto list = [](const std::vector<std::string>& items) {
    std::string text;
    for (const auto& item : items) text += (text.empty() ? "" : " ") + item;
    return text;
  };
  std::vector<OptionRow> rows{
      {"--hw", o.hw},
      {"--sim", o.hw == "sim" ? o.sim_profile : "(not used under --hw " + o.hw + ")"},
      {"--bind", o.bind},
      {"--web-port", std::to_string(o.web_port)}};
  // Every line protocol's --KEY-port, from the protocol registry.
  for (const protocol::ProtocolInfo& p : protocol::protocols())
    rows.push_back({"--" + std::string(p.key) + "-port",
                    std::to_string(o.line_ports[static_cast<std::size_t>(p.personality)])});
  rows.insert(rows.end(), {{"--pty", list(o.ptys)},
                           {"--serial", list(o.serials)},
                           {"--log-level", o.log_level},
                           {"--log-format", o.log_format},
                           {"--avahi", o.avahi}});
  return rows;
}

}  // namespace

std::string settings_path(const Options& options) {
  return options.config_path.empty() ? FileStorage::default_path() : options.config_path;
}

const char* settings_path_origin(const Options& options) {
  if (!options.config_path.empty()) return "--config";
  return FileStorage::default_path_origin();
}

bool apply_profile(const sim::Profile& profile, settings::Settings& settings, std::string& error) {
  for (const auto& o : profile.overrides) {
    const auto id = settings::find(o.key);
    if (!id || settings.set(*id, o.value).error != Error::kOk) {
      error = std::string("profile ") + profile.name + " sets an invalid " + o.key;
      return false;
    }
  }
  return true;
}

web::LoadOutcome load_file_settings(FileStorage& storage, const sim::Profile* profile,
                                    const settings::Settings& base, settings::Settings& out,
                                    std::string& storage_error, web::LoadReport* report) {
  out = base;
  storage_error = storage.unusable_reason();
  if (!storage_error.empty()) return {};
  auto scratch = std::make_unique<settings::Settings>();
  std::vector<char> buf(web::Api::kMaxDocumentBytes);
  std::unique_ptr<LegacyProfileGuess> guess;
  if (profile != nullptr) guess = std::make_unique<LegacyProfileGuess>(*profile);
  return web::load_settings(storage, base, guess.get(), out, *scratch, buf.data(), buf.size(),
                            report);
}

int print_config(const Options& options, const std::set<std::string>& given, std::FILE* out) {
  // Heap is fine: a one-shot command, not the daemon.
  auto table = std::make_unique<settings::Settings>();  // the table's defaults
  auto base = std::make_unique<settings::Settings>();   // + the profile
  const sim::Profile* profile = nullptr;
  if (options.hw == "sim") {
    profile = sim::find_profile(options.sim_profile);
    if (profile == nullptr) {
      std::fprintf(stderr, "rotord: unknown simulator profile '%s' (try g5500, ham4, spid)\n",
                   options.sim_profile.c_str());
      return 2;
    }
    std::string error;
    if (!apply_profile(*profile, *base, error)) {
      std::fprintf(stderr, "rotord: %s\n", error.c_str());
      return 2;
    }
  }
  std::fprintf(out, "# rotord %s: the settings it runs with, and where each comes from\n",
               ROTORD_VERSION);
  std::fprintf(out,
               "#\n# options (\"given\": on the command line; under systemd that is\n"
               "# ROTORD_OPTS in /etc/rotord/rotord.conf)\n");
  for (const auto& row : option_rows(options)) {
    std::fprintf(out, "%-34s %-24s # %s\n", row.name.c_str(), row.value.c_str(),
                 given.count(row.name) != 0 ? "given" : "default");
  }

  FileStorage storage(settings_path(options));
  std::fprintf(out, "#\n# settings file %s (from %s): ", storage.path().c_str(),
               settings_path_origin(options));
  auto effective = std::make_unique<settings::Settings>();
  std::string why;
  web::LoadReport report;
  const web::LoadOutcome r = load_file_settings(storage, profile, *base, *effective, why, &report);
  if (!why.empty()) {
    std::fprintf(out, "%s; rotord refuses to start\n", why.c_str());
    return 2;
  }
  int code = 0;
  switch (r.status) {
    case web::LoadOutcome::kNothingStored:
      std::fprintf(out, "not there yet (the first change made through rotord creates it)\n");
      break;
    case web::LoadOutcome::kLoaded:
      std::fprintf(out, "loaded%s\n",
                   r.migrated ? " (an old file holding every setting: read as changes)" : "");
      break;
    case web::LoadOutcome::kRepaired:
      std::fprintf(out, "DAMAGED: rotord runs on its valid values and drops these:\n");
      for (std::size_t n = 0; n < report.size(); ++n)
        std::fprintf(out, "#   %s%s%s\n", report[n].key, report[n].key[0] != '\0' ? ": " : "",
                     report[n].reason);
      if (report.more() > 0) std::fprintf(out, "#   and %zu more\n", report.more());
      code = 1;
      break;
    case web::LoadOutcome::kCorrupt:
      std::fprintf(out, "INVALID (%s%s%s%s%s): rotord runs on the defaults\n", r.key,
                   r.key[0] != '\0' ? ": " : "", r.reason, storage.last_error().empty() ? "" : ": ",
                   storage.last_error().c_str());
      code = 1;
      break;
  }
  if (r.access_unreadable)
    std::fprintf(out,
                 "# the access settings cannot be read: every port obeys only STOP and answers "
                 "status until the file is fixed (docs/security.md)\n");
  const settings::KeySet from_file = settings::user_layer(*effective, *base);
  const settings::KeySet from_profile = settings::user_layer(*base, *table);
  const std::string profile_label =
      profile != nullptr ? std::string("profile ") + profile->name : "";
  std::fprintf(out, "#\n# settings (secrets shown as %s when set)\n", settings::kSecretMask);
  for (std::size_t n = 0; n < settings::kCount; ++n) {
    const auto id = static_cast<settings::Id>(n);
    char value[settings::kValueTextCapacity];
    effective->format_value(id, value, sizeof value);
    std::string shown = value;
    if (settings::is_text(id)) shown = "\"" + shown + "\"";
    const char* source = from_file.test(n)      ? "file"
                         : from_profile.test(n) ? profile_label.c_str()
                                                : "default";
    std::fprintf(out, "%-34s %-24s # %s\n", settings::def(id).key, shown.c_str(), source);
  }
  return code;
}

}  // namespace rotord::linux_port
