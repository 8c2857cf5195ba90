#pragma once
#include <signal.h>
#include <sys/types.h>

#include <string>
#include <vector>

namespace rotord::testing {

/// Finds a TCP port on 127.0.0.1 that is free right now.
int free_port();

/// Runs build/rotord as a child process on free loopback ports and waits until
/// it says it listens. Stops it with SIGTERM on destruction.
class DaemonProcess {
 public:
  struct Ports {
    int wrc = 0;
    int rotctld = 0;
    int web = 0;
    int gs232 = 0;
    int easycomm = 0;
  };

  /// `extra_args` go after the port options, e.g. {"--sim", "spid", "--speedup", "20"}.
  explicit DaemonProcess(std::vector<std::string> extra_args = {});
  ~DaemonProcess();
  DaemonProcess(const DaemonProcess&) = delete;
  DaemonProcess& operator=(const DaemonProcess&) = delete;

  bool ready() const { return ready_; }
  const Ports& ports() const { return ports_; }
  /// Everything the daemon printed so far.
  const std::string& output() const { return output_; }
  /// Reads the daemon's output until `text` appears in it (bounded by
  /// timeout_ms, for liveness only); true when it did.
  bool wait_for_output(const std::string& text, int timeout_ms = 10000);
  /// With `--clock manual` among the arguments: runs `ms` of controller time
  /// in the daemon and waits (bounded) until it has; returns the controller
  /// time after it, or -1.
  long long advance_ms(long long ms);
  /// Sends SIGTERM and waits; returns the exit status (or -1).
  int terminate() { return stop_with(SIGTERM); }
  /// Sends `signal` and waits (bounded) for the process to end; returns its
  /// exit status, 128 + the signal that killed it, or -1 when it did not end.
  int stop_with(int signal);
  /// Closes the reading end of the daemon's output: it now writes into a
  /// pipe nobody reads (a dropped SSH session's terminal).
  void close_output();
  pid_t pid() const { return pid_; }

 private:
  /// Starts the daemon on newly found ports; false when it did not get ready.
  bool spawn(const std::vector<std::string>& extra_args);
  void read_output(int timeout_ms);

  Ports ports_;
  pid_t pid_ = -1;
  int out_fd_ = -1;
  int in_fd_ = -1;              ///< the daemon's standard input: the manual clock's commands
  std::size_t clock_seen_ = 0;  ///< output_ up to here holds no unread clock reply
  bool ready_ = false;
  std::string output_;
  std::string config_home_;  ///< XDG_CONFIG_HOME of the child
};

/// Whether this machine has the IPv6 loopback (::1): IPv6 tests skip without.
bool ipv6_loopback();

/// A blocking loopback TCP client with timeouts, for protocol tests.
class TcpClient {
 public:
  explicit TcpClient(int port);
  /// From another loopback address (e.g. "127.0.0.2"): another host, as the
  /// per-address limits and the allow-list see it. An IPv6 source ("::1")
  /// connects to [::1].
  TcpClient(int port, const std::string& source);
  ~TcpClient();
  TcpClient(const TcpClient&) = delete;
  TcpClient& operator=(const TcpClient&) = delete;

  bool connected() const { return fd_ >= 0; }
  bool send(const std::string& bytes);
  /// Reads one line ending in LF (the LF and a CR before it are removed).
  /// Returns false on timeout or close.
  bool read_line(std::string& line, int timeout_ms = 3000);
  /// Reads whatever arrives within timeout_ms (one recv after poll), for
  /// atomicity checks.
  std::string recv_once(int timeout_ms = 3000);
  /// Reads until the peer closes or timeout_ms passes; true if it closed.
  bool wait_closed(int timeout_ms = 3000);
  /// Reads what has arrived, without waiting; true if the peer has closed.
  bool closed_now();
  /// Sends `command` and returns the next line.
  std::string ask(const std::string& command, int timeout_ms = 3000);
  int fd() const { return fd_; }

 private:
  void connect_ipv6(int port, const std::string& source);
  enum class Received { bytes, closed, timeout };
  /// Waits at most `timeout_ms` for bytes and appends them to buffer_ (a
  /// failed read counts as closed).
  Received receive(long long timeout_ms);

  int fd_ = -1;
  std::string buffer_;
};

}  // namespace rotord::testing
