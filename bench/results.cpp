#include "results.hpp"

#include <cmath>

namespace rotord::bench {
namespace {

void write_object(std::FILE* out, const std::vector<std::pair<std::string, double>>& kv) {
  std::fputc('{', out);
  for (std::size_t i = 0; i < kv.size(); ++i) {
    if (i > 0) std::fputs(", ", out);
    if (std::isfinite(kv[i].second)) {
      std::fprintf(out, "\"%s\": %.6g", kv[i].first.c_str(), kv[i].second);
    } else {
      std::fprintf(out, "\"%s\": null", kv[i].first.c_str());
    }
  }
  std::fputc('}', out);
}

}  // namespace

void write_json(std::FILE* out, const std::vector<Result>& results) {
  std::fputs("[\n", out);
  for (std::size_t i = 0; i < results.size(); ++i) {
    std::fprintf(out, "  {\"name\": \"%s\", \"inputs\": ", results[i].name.c_str());
    write_object(out, results[i].inputs);
    std::fputs(", \"metrics\": ", out);
    write_object(out, results[i].metrics);
    std::fputs(i + 1 < results.size() ? "},\n" : "}\n", out);
  }
  std::fputs("]\n", out);
}

}  // namespace rotord::bench
