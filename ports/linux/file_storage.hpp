#pragma once
#include <string>

#include "hal/storage.hpp"

namespace rotord::linux_port {

/// hal::Storage as one JSON file, replaced atomically: the new document goes
/// to a temporary file in the same directory, is fsync'ed, renamed over the
/// old one, and the directory is fsync'ed, so a kill or power cut at any
/// instant leaves either the old or the new file, never a torn one.
class FileStorage final : public hal::Storage {
 public:
  explicit FileStorage(std::string path) : path_(std::move(path)) {}

  /// Under systemd's StateDirectory=rotord, $STATE_DIRECTORY/settings.json
  /// (/var/lib/rotord/settings.json); run by hand,
  /// $XDG_CONFIG_HOME/rotord/settings.json, else ~/.config/rotord/settings.json.
  static std::string default_path();
  /// Which of those default_path() took: "$STATE_DIRECTORY (systemd)",
  /// "$XDG_CONFIG_HOME", "$HOME/.config" or "the working directory".
  static const char* default_path_origin();

  /// Why the path cannot hold the settings ("is a FIFO, not a regular
  /// file"); empty when it can (a regular file, or nothing there yet).
  std::string unusable_reason() const;

  long load(char* buf, std::size_t capacity) override;
  bool save(std::string_view document) override;

  /// The next save first keeps the current file as <path>.bad (a corrupt or
  /// invalid file the user may want to repair), instead of replacing it.
  void keep_backup_before_next_save() { backup_pending_ = true; }

  const std::string& path() const { return path_; }
  /// Why the last load or save failed (errno text), for logs.
  const std::string& last_error() const { return last_error_; }

 private:
  std::string path_;
  std::string last_error_;
  bool backup_pending_ = false;
};

}  // namespace rotord::linux_port
