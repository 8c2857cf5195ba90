#pragma once
// Debian's `rotctl -m 2` (Hamlib's NET rotctl backend) in its interactive
// mode on one connection, as Gpredict, the SatNOGS client and SatDump keep
// one: commands go to its standard input, its answers land in a file. The
// interop tests drive the daemon's manual clock between commands, so reads
// poll the file on the wall clock while the daemon's time stands still.
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

namespace rotord::testing {

class RotctlSession {
 public:
  /// Connects to `where` (host:port); rotctl gives up after `timeout_s`.
  explicit RotctlSession(const std::string& where, int timeout_s = 300);
  ~RotctlSession();
  RotctlSession(const RotctlSession&) = delete;
  RotctlSession& operator=(const RotctlSession&) = delete;

  bool ok() const { return pipe_ != nullptr; }
  void send(const std::string& line);
  /// Sends `p`; false when no answer came.
  bool read(double& az_deg, double& el_deg);
  /// Sends `p` and returns the azimuth rotctl prints (NAN when none came).
  double read_az();
  /// Everything rotctl printed so far (for failure messages).
  std::string text() const;

 private:
  std::vector<std::pair<double, double>> positions() const;

  std::string dir_;
  std::string out_path_;
  FILE* pipe_ = nullptr;
};

}  // namespace rotord::testing
