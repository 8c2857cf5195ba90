#pragma once
// The whole text of a file, for tests that look at what the daemon wrote
// (its settings file, its log); empty when the file is missing.
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace rotord::testing {

inline std::string read_file(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

}  // namespace rotord::testing
