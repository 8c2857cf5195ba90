#pragma once
#include "json/settings_json.hpp"
#include "simulator.hpp"

namespace rotord::linux_port {

/// Which simulator profile a version-1 settings file was written under.
/// Those files hold every setting, the profile's geometry included, so
/// without this a file saved under `--sim ham4` would impose 0..360 and no
/// elevation on `--sim g5500` forever (issue 10 item 7). A file is taken as
/// written under a profile when it holds every value that profile sets; the
/// profile in use wins a tie. No match: the table's defaults (a file written
/// under --hw gpiod, or by hand), so every value it changed is kept.
class LegacyProfileGuess final : public web::LegacyBaseGuess {
 public:
  explicit LegacyProfileGuess(const sim::Profile& current) : current_(current) {}
  const settings::Settings& base_of(const settings::Settings& file_values) override;
  /// The profile recognised by the last base_of(); null: none.
  const sim::Profile* recognised() const { return recognised_; }

 private:
  const sim::Profile& current_;
  const sim::Profile* recognised_ = nullptr;
  settings::Settings base_;
};

}  // namespace rotord::linux_port
