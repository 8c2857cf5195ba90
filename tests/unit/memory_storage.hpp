#pragma once
// The settings document in memory, where a port keeps it in a file or flash:
// counts the writes and can be told to fail them.
#include <string>
#include <string_view>

#include "hal/storage.hpp"

namespace rotord::testing {

class MemoryStorage final : public hal::Storage {
 public:
  std::string document;
  bool has_document = false;
  bool fail = false;  ///< save() fails, as a full disk or a worn flash sector
  int saves = 0;      ///< successful writes
  int attempts = 0;   ///< every call of save()

  long load(char* buf, std::size_t capacity) override {
    if (!has_document) return -1;
    if (document.size() > capacity) return -2;
    document.copy(buf, document.size());
    return static_cast<long>(document.size());
  }
  bool save(std::string_view doc) override {
    ++attempts;
    if (fail) return false;
    document = std::string(doc);
    has_document = true;
    ++saves;
    return true;
  }
};

}  // namespace rotord::testing
