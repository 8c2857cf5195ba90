#pragma once
#include <asio.hpp>
#include <atomic>
#include <functional>
#include <string>
#include <thread>

namespace rotord::linux_port {

/// Downloads a TLE file (track.tle_url) with libcurl on a thread of its
/// own, so the control loop never waits on the network, and hands the text
/// to the asio loop. http and https only, 30 s at most, 1 MiB at most.
class TleFetcher {
 public:
  /// ok: the text arrived (HTTP 2xx); else `text` says why not.
  using Done = std::function<void(bool ok, const std::string& text)>;

  explicit TleFetcher(asio::io_context& io);
  ~TleFetcher();
  TleFetcher(const TleFetcher&) = delete;
  TleFetcher& operator=(const TleFetcher&) = delete;

  /// Starts a download unless one is running; `done` runs on the loop.
  bool fetch(const std::string& url, Done done);
  bool busy() const { return busy_; }

 private:
  asio::io_context& io_;
  std::thread thread_;
  std::atomic<bool> busy_{false};
};

}  // namespace rotord::linux_port
