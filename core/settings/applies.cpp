#include "settings/applies.hpp"

#include "util/slice.hpp"

namespace rotord::settings {
namespace {

constexpr std::string_view kPlatformKey = "platform";

/// The next piece of `rest` up to `separator` (removed with it).
std::string_view take(std::string_view& rest, char separator) {
  const std::size_t at = rest.find(separator);
  const std::string_view piece = text::slice(rest, 0, at);
  rest.remove_prefix(at == std::string_view::npos ? rest.size() : at + 1);
  return piece;
}

/// Whether `name` is one of `choices` ("a|b|c").
bool one_of(std::string_view name, std::string_view choices) {
  while (!choices.empty())
    if (take(choices, '|') == name) return true;
  return false;
}

/// Whether one term holds; `error` says why it cannot be read.
bool term_holds(std::string_view term, const Settings& values, Platform platform,
                const char*& error) {
  std::string_view choices = term;
  const std::string_view key = take(choices, '=');
  const bool has_choices = key.size() < term.size();
  if (key == kPlatformKey) {
    if (!has_choices) error = "platform needs =pico_w, =gpiod or =sim";
    for (std::string_view c = choices; !c.empty();) {
      const std::string_view name = take(c, '|');
      if (name != "pico_w" && name != "gpiod" && name != "sim") error = "unknown platform";
    }
    return platform == Platform::kUnknown || one_of(platform_name(platform), choices);
  }
  const auto id = find(key);
  if (!id) {
    error = "unknown key in a condition";
    return true;
  }
  if (!has_choices) return is_text(*id) ? !values.text(*id).empty() : values.get(*id) != 0.0;
  if (def(*id).type != Type::kEnum) {
    error = "=choice needs an enum setting";
    return true;
  }
  for (std::string_view c = choices; !c.empty();) {
    const std::string_view name = take(c, '|');
    bool known = false;
    for (int n = 0; n < choice_count(*id); ++n) known = known || choice_name(*id, n) == name;
    if (!known) error = "a choice the setting does not have";
  }
  return one_of(choice_name(*id, values.i(*id)), choices);
}

/// Whether the condition holds (true when it is empty or cannot be read).
bool holds(std::string_view condition, const Settings& values, Platform platform,
           const char*& error) {
  if (condition.empty()) return true;
  bool any = false;
  for (bool more = true; more;) {
    more = condition.find(';') != std::string_view::npos;
    std::string_view alternative = take(condition, ';');
    bool all = true;
    for (bool more_terms = true; more_terms;) {
      more_terms = alternative.find('&') != std::string_view::npos;
      const std::string_view term = take(alternative, '&');
      if (term.empty()) {
        error = "an empty term";
        continue;
      }
      all = term_holds(term, values, platform, error) && all;
    }
    any = any || all;
  }
  return any || error != nullptr;
}

}  // namespace

std::string_view platform_name(Platform platform) {
  switch (platform) {
    case Platform::kPicoW:
      return "pico_w";
    case Platform::kGpiod:
      return "gpiod";
    case Platform::kSim:
      return "sim";
    case Platform::kUnknown:
      break;
  }
  return "";
}

bool applies(Id id, const Settings& values, Platform platform) {
  const char* error = nullptr;
  return holds(condition(id), values, platform, error);
}

const char* condition_error(std::string_view condition) {
  const char* error = nullptr;
  const Settings defaults;
  holds(condition, defaults, Platform::kSim, error);
  return error;
}

}  // namespace rotord::settings
