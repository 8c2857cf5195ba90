#pragma once
// Running the real client programs (rotctl, socat) from interop tests.
#include <string>
#include <vector>

namespace rotord::testing {

struct CommandOutput {
  int rc = -1;      ///< exit status, -1 when the command could not run or was killed
  std::string out;  ///< stdout and stderr together
};

/// Runs a shell command to completion.
CommandOutput run_command(const std::string& command);

/// One `rotctl -m MODEL -r WHERE COMMANDS` (Debian's Hamlib, a connection of
/// its own), for at most 20 s.
CommandOutput rotctl_once(int model, const std::string& where, const std::string& commands);
/// The position through rotctl_once's `p`: {az, el}, or empty on failure.
std::vector<double> rotctl_position(int model, const std::string& where);

/// The words of `text` that are whole numbers, in order ("42.5\n-3\n" -> 42.5, -3).
std::vector<double> numbers_in(const std::string& text);

/// curl -s -i with `args`, for at most 20 s: the whole response, head
/// included (or curl's complaint).
std::string curl(const std::string& args);
/// The status of a response as curl -i prints it; 0 when there is none.
int status_of(const std::string& response);
/// The body of such a response ("" without one).
std::string body_of(const std::string& response);

/// A new private directory under /tmp (for pty links and files); the caller removes it.
std::string make_temp_dir(const std::string& prefix);

}  // namespace rotord::testing
