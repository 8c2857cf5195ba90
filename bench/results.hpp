#pragma once
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

namespace rotord::bench {

/// One benchmark row of build/bench/results.json: a name, the inputs that
/// define it and the measured metrics, numbers only, so two runs can be
/// compared key by key (bench/compare.py).
struct Result {
  std::string name;
  std::vector<std::pair<std::string, double>> inputs;
  std::vector<std::pair<std::string, double>> metrics;
};

/// Writes the rows as a JSON list (non-finite numbers become null).
void write_json(std::FILE* out, const std::vector<Result>& results);

}  // namespace rotord::bench
