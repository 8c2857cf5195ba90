#include "shell.hpp"

#include <stdlib.h>
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <cstdlib>
#include <sstream>

namespace rotord::testing {

CommandOutput run_command(const std::string& command) {
  CommandOutput r;
  FILE* p = ::popen((command + " 2>&1").c_str(), "r");
  if (p == nullptr) return r;
  std::array<char, 512> buf{};
  std::size_t n = 0;
  while ((n = std::fread(buf.data(), 1, buf.size(), p)) > 0) r.out.append(buf.data(), n);
  const int status = ::pclose(p);
  r.rc = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

std::string curl(const std::string& args) {
  return run_command("timeout 20 curl -s -i " + args + " 2>&1").out;
}

int status_of(const std::string& response) {
  return response.rfind("HTTP/1.1 ", 0) == 0 ? std::stoi(response.substr(9, 3)) : 0;
}

std::string body_of(const std::string& response) {
  const auto at = response.find("\r\n\r\n");
  return at == std::string::npos ? "" : response.substr(at + 4);
}

CommandOutput rotctl_once(int model, const std::string& where, const std::string& commands) {
  return run_command("timeout 20 rotctl -m " + std::to_string(model) + " -r " + where + " " +
                     commands);
}

std::vector<double> rotctl_position(int model, const std::string& where) {
  const CommandOutput r = rotctl_once(model, where, "p");
  const std::vector<double> v = numbers_in(r.out);
  if (r.rc != 0 || v.size() != 2) return {};
  return v;
}

std::vector<double> numbers_in(const std::string& text) {
  std::vector<double> v;
  std::istringstream in(text);
  std::string word;
  while (in >> word) {
    char* end = nullptr;
    const double d = std::strtod(word.c_str(), &end);
    if (end != word.c_str() && *end == '\0') v.push_back(d);
  }
  return v;
}

std::string make_temp_dir(const std::string& prefix) {
  std::string path = "/tmp/" + prefix + "-XXXXXX";
  return ::mkdtemp(path.data()) != nullptr ? path : "/tmp";
}

}  // namespace rotord::testing
