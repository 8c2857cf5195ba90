#include "web/assets.hpp"

namespace rotord::web {

// Defined in the generated web_assets.cpp (core/web/embed_assets.cmake).
extern const Asset kAssets[];
extern const std::size_t kAssetCount;

const Asset* find_asset(std::string_view path) {
  if (path == "/") path = "/index.html";
  for (std::size_t n = 0; n < kAssetCount; ++n)
    if (path == kAssets[n].path) return &kAssets[n];
  return nullptr;
}

std::size_t asset_count() {
  return kAssetCount;
}

const Asset& asset_at(std::size_t index) {
  return kAssets[index];
}

}  // namespace rotord::web
