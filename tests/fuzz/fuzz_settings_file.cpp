// libFuzzer target: arbitrary bytes as the stored settings file (Linux) or
// flash slot payload (Pico W), read by web::load_settings over a base. A
// damaged, hand-edited or hostile file must never crash the loader, never
// leave settings that break a rule, and when refused must leave exactly the
// base (the caller then keeps the file aside instead of overwriting it).
// Then the loaded values are saved and read back: they must come back the
// same (a document rotord writes is one it reads).
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <string>
#include <string_view>

#include "json/settings_json.hpp"
#include "settings/settings.hpp"

namespace {

class BytesStorage final : public rotord::hal::Storage {
 public:
  std::string stored;
  long load(char* buf, std::size_t capacity) override {
    if (stored.size() > capacity) return -1;
    std::memcpy(buf, stored.data(), stored.size());
    return static_cast<long>(stored.size());
  }
  bool save(std::string_view document) override {
    stored.assign(document);
    return true;
  }
};

bool same_everywhere(const rotord::settings::Settings& a, const rotord::settings::Settings& b) {
  for (std::size_t n = 0; n < rotord::settings::kCount; ++n)
    if (!a.same_value(static_cast<rotord::settings::Id>(n), b)) return false;
  return true;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using rotord::web::LoadOutcome;
  static char buf[16384];
  BytesStorage storage;
  storage.stored.assign(reinterpret_cast<const char*>(data), size);
  const rotord::settings::Settings base;
  rotord::settings::Settings target;
  rotord::settings::Settings scratch;
  const LoadOutcome first =
      rotord::web::load_settings(storage, base, nullptr, target, scratch, buf, sizeof buf);
  if (target.check_consistency().error != rotord::Error::kOk) std::abort();
  if (first.status == LoadOutcome::kNothingStored) return 0;
  if (first.status == LoadOutcome::kCorrupt) {
    // Nothing read: the base, untouched, and failed closed.
    if (!same_everywhere(target, base) || !target.access_unreadable()) std::abort();
    return 0;
  }
  // What was accepted survives a save and a load unchanged.
  if (!rotord::web::save_settings(storage, target, base, buf, sizeof buf)) return 0;
  rotord::settings::Settings again;
  const LoadOutcome second =
      rotord::web::load_settings(storage, base, nullptr, again, scratch, buf, sizeof buf);
  // (kRepaired too: what was kept is a clean document of its own.)
  if (second.status != LoadOutcome::kLoaded || !same_everywhere(again, target)) std::abort();
  return 0;
}
