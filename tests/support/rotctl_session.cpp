#include "rotctl_session.hpp"

#include <unistd.h>

#include <chrono>
#include <cmath>
#include <fstream>
#include <regex>
#include <sstream>
#include <thread>

#include "shell.hpp"

namespace rotord::testing {

RotctlSession::RotctlSession(const std::string& where, int timeout_s)
    : dir_(make_temp_dir("rotctl-session")) {
  out_path_ = dir_ + "/out.txt";
  pipe_ = ::popen(("timeout " + std::to_string(timeout_s) + " rotctl -m 2 -r " + where + " > " +
                   out_path_ + " 2>&1")
                      .c_str(),
                  "w");
}

RotctlSession::~RotctlSession() {
  if (pipe_ != nullptr) {
    std::fputs("q\n", pipe_);
    ::pclose(pipe_);
  }
  std::remove(out_path_.c_str());
  ::rmdir(dir_.c_str());
}

void RotctlSession::send(const std::string& line) {
  std::fputs(line.c_str(), pipe_);
  std::fflush(pipe_);
}

bool RotctlSession::read(double& az_deg, double& el_deg) {
  const std::size_t before = positions().size();
  send("p\n");
  // Wall-clock poll for the bytes to cross the socket and rotctl's stdout:
  // the daemon's clock stands still meanwhile. The condition ends the wait;
  // the bound (10 s) only keeps a dead rotctl from hanging the test, and is
  // wide for a loaded 2-core machine (1.5 s was seen to be too short there).
  for (int i = 0; i < 2000; ++i) {
    const std::vector<std::pair<double, double>> v = positions();
    if (v.size() > before) {
      az_deg = v.back().first;
      el_deg = v.back().second;
      return true;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  return false;
}

double RotctlSession::read_az() {
  double az = NAN, el = NAN;
  return read(az, el) ? az : NAN;
}

std::string RotctlSession::text() const {
  std::ifstream in(out_path_);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

std::vector<std::pair<double, double>> RotctlSession::positions() const {
  static const std::regex kPos("Azimuth: (-?[0-9.]+)\\s+Elevation: (-?[0-9.]+)");
  std::vector<std::pair<double, double>> v;
  const std::string t = text();
  for (auto it = std::sregex_iterator(t.begin(), t.end(), kPos); it != std::sregex_iterator(); ++it)
    v.emplace_back(std::stod((*it)[1]), std::stod((*it)[2]));
  return v;
}

}  // namespace rotord::testing
