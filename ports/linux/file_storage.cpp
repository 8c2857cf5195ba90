#include "file_storage.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>

namespace rotord::linux_port {
namespace {

std::string parent_dir(const std::string& path) {
  const auto slash = path.rfind('/');
  if (slash == std::string::npos) return ".";
  if (slash == 0) return "/";
  return path.substr(0, slash);
}

/// mkdir -p, for the first save into ~/.config/rotord.
bool make_dirs(const std::string& dir) {
  if (dir.empty() || dir == "/" || dir == ".") return true;
  struct stat st {};
  if (::stat(dir.c_str(), &st) == 0) return S_ISDIR(st.st_mode);
  if (!make_dirs(parent_dir(dir))) return false;
  return ::mkdir(dir.c_str(), 0755) == 0 || errno == EEXIST;
}

bool write_all(int fd, std::string_view data) {
  while (!data.empty()) {
    const ssize_t n = ::write(fd, data.data(), data.size());
    if (n < 0) {
      if (errno == EINTR) continue;
      return false;
    }
    data.remove_prefix(static_cast<std::size_t>(n));
  }
  return true;
}

}  // namespace

namespace {

/// The first directory of $STATE_DIRECTORY (systemd lists one per
/// StateDirectory= entry, separated by colons), or "" outside a service.
std::string state_directory() {
  const char* dirs = std::getenv("STATE_DIRECTORY");
  if (dirs == nullptr || dirs[0] != '/') return {};
  const std::string all = dirs;
  return all.substr(0, all.find(':'));
}

}  // namespace

const char* FileStorage::default_path_origin() {
  if (!state_directory().empty()) return "$STATE_DIRECTORY (systemd)";
  if (const char* xdg = std::getenv("XDG_CONFIG_HOME"); xdg != nullptr && xdg[0] == '/')
    return "$XDG_CONFIG_HOME";
  if (const char* home = std::getenv("HOME"); home != nullptr && home[0] != '\0')
    return "$HOME/.config";
  return "the working directory";
}

std::string FileStorage::default_path() {
  // The service's own directory first: systemd sets it only for the unit, so
  // rotord run by hand keeps using the user's file.
  if (const std::string state = state_directory(); !state.empty()) return state + "/settings.json";
  if (const char* xdg = std::getenv("XDG_CONFIG_HOME"); xdg != nullptr && xdg[0] == '/')
    return std::string(xdg) + "/rotord/settings.json";
  if (const char* home = std::getenv("HOME"); home != nullptr && home[0] != '\0')
    return std::string(home) + "/.config/rotord/settings.json";
  return "rotord-settings.json";
}

std::string FileStorage::unusable_reason() const {
  struct stat st {};
  if (::stat(path_.c_str(), &st) != 0) return {};  // nothing yet, or load() says why
  if (S_ISREG(st.st_mode)) return {};
  if (S_ISFIFO(st.st_mode)) return "is a FIFO, not a regular file";
  if (S_ISDIR(st.st_mode)) return "is a directory, not a regular file";
  if (S_ISCHR(st.st_mode) || S_ISBLK(st.st_mode)) return "is a device, not a regular file";
  if (S_ISSOCK(st.st_mode)) return "is a socket, not a regular file";
  return "is not a regular file";
}

long FileStorage::load(char* buf, std::size_t capacity) {
  // O_NONBLOCK: a FIFO put in place after the start-up check must not hang.
  const int fd = ::open(path_.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK);
  if (fd < 0) {
    if (errno == ENOENT) return -1;  // nothing stored yet
    last_error_ = std::strerror(errno);
    return -2;
  }
  if (struct stat st{}; ::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
    last_error_ = "not a regular file";
    ::close(fd);
    return -2;
  }
  last_error_.clear();
  std::size_t length = 0;
  for (;;) {
    if (length == capacity) {
      char extra = 0;
      const ssize_t more = ::read(fd, &extra, 1);
      ::close(fd);
      if (more != 0) {
        last_error_ = "file larger than the settings buffer";
        return -2;
      }
      return static_cast<long>(length);
    }
    const ssize_t n = ::read(fd, buf + length, capacity - length);
    if (n < 0) {
      if (errno == EINTR) continue;
      last_error_ = std::strerror(errno);
      ::close(fd);
      return -2;
    }
    if (n == 0) break;
    length += static_cast<std::size_t>(n);
  }
  ::close(fd);
  return static_cast<long>(length);
}

bool FileStorage::save(std::string_view document) {
  const std::string dir = parent_dir(path_);
  if (!make_dirs(dir)) {
    last_error_ = "cannot create " + dir + ": " + std::strerror(errno);
    return false;
  }
  if (backup_pending_) {
    // Keep the file we could not load as a hard link, so the settings file
    // itself is never missing, not even for an instant.
    const std::string bad = path_ + ".bad";
    ::unlink(bad.c_str());
    if (::link(path_.c_str(), bad.c_str()) == 0 || errno == ENOENT) backup_pending_ = false;
  }
  const std::string temp = path_ + ".tmp";
  // 0600: the file holds secrets (the Wi-Fi password); the rename gives an
  // older 0644 file this mode too.
  const int fd = ::open(temp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0600);
  if (fd < 0 || ::fchmod(fd, 0600) != 0) {  // a left-over temp file keeps its mode
    last_error_ = "cannot write " + temp + ": " + std::strerror(errno);
    if (fd >= 0) ::close(fd);
    return false;
  }
  const bool written = write_all(fd, document) && ::fsync(fd) == 0;
  const int saved_errno = errno;
  ::close(fd);
  if (!written) {
    last_error_ = std::string("cannot write ") + temp + ": " + std::strerror(saved_errno);
    ::unlink(temp.c_str());
    return false;
  }
  if (::rename(temp.c_str(), path_.c_str()) != 0) {
    last_error_ = "cannot replace " + path_ + ": " + std::strerror(errno);
    ::unlink(temp.c_str());
    return false;
  }
  // The rename is durable only once the directory entry is on disk.
  if (const int dfd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC); dfd >= 0) {
    ::fsync(dfd);
    ::close(dfd);
  }
  return true;
}

}  // namespace rotord::linux_port
