#pragma once
// `rotord --print-config`: the settings rotord would run with, each with
// the layer it comes from (the table's default, the --sim profile, the
// settings file), and the command-line options with whether they were given
// (under systemd: /etc/rotord/rotord.conf's ROTORD_OPTS) or defaulted.
// Reads the settings file the daemon would read and changes nothing.
#include <cstdio>
#include <set>
#include <string>

#include "file_storage.hpp"
#include "json/settings_json.hpp"
#include "options.hpp"
#include "settings/settings.hpp"
#include "simulator.hpp"

namespace rotord::linux_port {

/// The settings file rotord uses: --config, else (under systemd's
/// StateDirectory=) $STATE_DIRECTORY/settings.json, else
/// $XDG_CONFIG_HOME/rotord/settings.json (FileStorage::default_path()).
std::string settings_path(const Options& options);
/// Where settings_path() came from, for messages: "--config",
/// "$STATE_DIRECTORY (systemd)", "$XDG_CONFIG_HOME", "$HOME/.config".
const char* settings_path_origin(const Options& options);

/// Puts `profile`'s values over `settings` (the simulator's geometry); false
/// and `error` when the profile sets an invalid value (a bug in sim/).
bool apply_profile(const sim::Profile& profile, settings::Settings& settings, std::string& error);

/// Reads the settings file the daemon would read into `out` (which holds the
/// base: the table's defaults and the profile, if any) the way the daemon
/// does: a damaged file keeps its valid values, an unreadable one leaves
/// `out` at the base; `report` (if given) names what was dropped.
/// `storage_error` says why the file is unusable ("is a FIFO..."): nothing
/// is read then.
web::LoadOutcome load_file_settings(FileStorage& storage, const sim::Profile* profile,
                                    const settings::Settings& base, settings::Settings& out,
                                    std::string& storage_error, web::LoadReport* report = nullptr);

/// Writes the report to `out`. `given`: the long names of the options given
/// on the command line ("--hw"). Returns the exit code: 0, 1 when the file
/// is invalid (the daemon would run on the defaults), 2 when it cannot be
/// used at all or the options are wrong.
int print_config(const Options& options, const std::set<std::string>& given, std::FILE* out);

}  // namespace rotord::linux_port
