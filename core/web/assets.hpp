#pragma once
#include <cstddef>
#include <string_view>

namespace rotord::web {

/// One file of the web UI (web/ in the source tree), gzipped at build time and
/// compiled in as a constant array (flash on the Pico): the UI works with no
/// network access and no file system. See core/web/assets.cmake.
struct Asset {
  const char* path;  ///< "/index.html"
  const char* content_type;
  const unsigned char* gzip_data;
  std::size_t gzip_size;
  const char* etag;  ///< quoted hash of the uncompressed file, for If-None-Match
};

/// The asset served at `path`; "/" is "/index.html". nullptr if none.
const Asset* find_asset(std::string_view path);

std::size_t asset_count();
const Asset& asset_at(std::size_t index);

}  // namespace rotord::web
